// Keyboard shortcuts (the page's "?" help lists them).
import { addKeyframeAtPlayhead, deleteSelectedKeyframe } from './panels.js';

const typing = (el) => el && (el.tagName === 'INPUT' || el.tagName === 'SELECT' || el.tagName === 'TEXTAREA');

export function wireKeyboard(studio) {
  window.addEventListener('keydown', (e) => {
    if (!studio.state.film) return;
    const ctrl = e.ctrlKey || e.metaKey;
    if (ctrl && handleCtrl(studio, e)) { e.preventDefault(); return; }
    if (ctrl || e.altKey || typing(document.activeElement) || nativeKey(document.activeElement, e.key)) return;
    if (handlePlain(studio, e)) e.preventDefault();
  });
  // A button clicked with the mouse gives the focus back, so that Space plays
  // the film instead of pressing the button again.
  document.addEventListener('click', (e) => {
    const button = e.target.closest && e.target.closest('button');
    if (button && e.detail > 0) button.blur();
  });
  // So does a menu, a check box or a slider once changed.
  document.addEventListener('change', (e) => {
    const el = e.target;
    if (el.tagName === 'SELECT' || el.type === 'checkbox' || el.type === 'range') el.blur();
  });
}

// Keys the focused element handles itself (the video's own controls, a button).
function nativeKey(el, key) {
  if (!el) return false;
  if (el.tagName === 'VIDEO') return [' ', 'ArrowLeft', 'ArrowRight', 'Home', 'End'].includes(key);
  if (el.tagName === 'BUTTON' || el.tagName === 'SUMMARY') return key === ' ' || key === 'Enter';
  return false;
}

function handleCtrl(studio, e) {
  const key = e.key.toLowerCase();
  if (key === 's') { studio.save(); return true; }
  if (typing(document.activeElement)) return false;   // the field's own undo
  if (key === 'z' && e.shiftKey) { studio.edits.redo(); return true; }
  if (key === 'z') { studio.edits.undo(); return true; }
  if (key === 'y') { studio.edits.redo(); return true; }
  return false;
}

function handlePlain(studio, e) {
  const video = studio.video, film = studio.state.film, tl = studio.timeline;
  const t = studio.currentTime();
  const frame = 1 / (film.fps || 24);
  const actions = {
    ' ': () => (video.paused ? video.play() : video.pause()),
    ArrowLeft: () => studio.seek(t - (e.shiftKey ? 1 : frame)),
    ArrowRight: () => studio.seek(t + (e.shiftKey ? 1 : frame)),
    Home: () => studio.seek(0),
    End: () => studio.seek(film.duration_s),
    PageUp: () => studio.seek(neighbourShotStart(film, t, -1)),
    PageDown: () => studio.seek(neighbourShotStart(film, t, +1)),
    '+': () => zoom(studio, tl, t, 0.5),
    '=': () => zoom(studio, tl, t, 0.5),
    '-': () => zoom(studio, tl, t, 2),
    0: () => studio.setView(0, film.duration_s),
    k: () => addKeyframeAtPlayhead(studio),
    Delete: () => deleteSelectedKeyframe(studio),
    Backspace: () => deleteSelectedKeyframe(studio),
    '?': () => { const h = document.getElementById('help'); h.hidden = !h.hidden; },
    Escape: () => { document.getElementById('help').hidden = true; },
  };
  const action = actions[e.key];
  if (!action) return false;
  action();
  return true;
}

function zoom(studio, tl, t, factor) {
  studio.setView(t - (t - tl.view.from) * factor, t + (tl.view.to - t) * factor);
}

function neighbourShotStart(film, t, direction) {
  const starts = film.shots.map((s) => s.start_s);
  if (direction > 0) return starts.find((s) => s > t + 1e-3) ?? film.duration_s;
  const before = starts.filter((s) => s < t - 0.05);
  return before.length ? before[before.length - 1] : 0;
}

// The per-shot panel, the effect panel and the effect blocks on the timeline.
import { EFFECTS, METAPHORS, table1Name, freeGap } from './edits.js';
import { laneByKey } from './timeline.js';

const $ = (id) => document.getElementById(id);
const MIN_EFFECT_S = 0.1;

// ---- shot panel
export function wireShotPanel(studio) {
  const edits = studio.edits;
  const shot = () => studio.state.selectedShot;
  $('model-select').addEventListener('change', (e) => edits.setShotField(shot(), 'model', e.target.value || undefined));
  const setGain = (value) => {
    const gain = Number(value);
    if (value === '' || !isFinite(gain)) return edits.setShotField(shot(), 'gain', undefined);
    edits.setShotField(shot(), 'gain', Math.min(4, Math.max(0, gain)));
  };
  $('gain-input').addEventListener('change', (e) => setGain(e.target.value));
  $('gain-slider').addEventListener('input', (e) => { $('gain-input').value = e.target.value; });
  $('gain-slider').addEventListener('change', (e) => setGain(e.target.value));
  $('mute-checkbox').addEventListener('change', (e) => edits.setShotField(shot(), 'mute', e.target.checked || undefined));
  $('washout-select').addEventListener('change', (e) => edits.setWashoutField(shot(), 'mode', e.target.value || undefined));
  const numeric = [['washout-return-accel', 'return_accel_m_s2'], ['washout-window', 'window_s'],
    ['washout-tau', 'tau_s'], ['washout-order', 'order']];
  for (const [id, field] of numeric) {
    $(id).addEventListener('change', (e) => {
      const v = e.target.value === '' ? undefined : Number(e.target.value);
      edits.setWashoutField(shot(), field, field === 'order' && v !== undefined ? Math.round(v) : v);
    });
  }
  $('reset-shot').addEventListener('click', () => edits.resetShot(shot()));
}

export function renderShotPanel(studio) {
  const { film, selectedShot } = studio.state;
  const info = film && film.shots.find((s) => s.shot === selectedShot);
  $('shot-panel').classList.toggle('disabled', !info);
  if (!info) return;
  const edit = studio.edits.shotEdit(selectedShot);
  $('shot-title').textContent = `Shot #${info.shot}`;
  $('shot-title').insertAdjacentHTML('beforeend',
    ` <span class="muted">${info.start_s.toFixed(2)}–${info.end_s.toFixed(2)} s</span>`);
  renderQuality(info.quality);
  $('model-select').options[0].textContent = `default (${film.model || 'cinematic'})`;
  setValue('model-select', edit.model || '');
  setValue('gain-input', edit.gain !== undefined ? edit.gain : 1);
  setValue('gain-slider', edit.gain !== undefined ? edit.gain : 1);
  $('mute-checkbox').checked = !!edit.mute;
  const washout = edit.washout || {};
  setValue('washout-select', washout.mode || '');
  setValue('washout-return-accel', washout.return_accel_m_s2 ?? '');
  setValue('washout-window', washout.window_s ?? '');
  setValue('washout-tau', washout.tau_s ?? '');
  setValue('washout-order', washout.order ?? '');
  $('reset-shot').disabled = Object.keys(edit).length <= 1;
}

// An input being typed in keeps its text.
function setValue(id, value) {
  const el = $(id);
  if (document.activeElement !== el) el.value = value;
}

function renderQuality(q) {
  const el = $('shot-quality');
  if (!q) { el.textContent = ''; return; }
  const parts = [];
  if (q.median_confidence !== undefined) parts.push(`confidence ${fmt(q.median_confidence)}`);
  if (q.inlier_ratio !== undefined) parts.push(`inliers ${fmt(q.inlier_ratio)}`);
  if (q.reprojection_rms_px !== undefined) parts.push(`rms ${fmt(q.reprojection_rms_px)} px`);
  if (q.lost_frames) parts.push(`${q.lost_frames} lost frames`);
  if (q.focal_observable === false) parts.push('focal not observable');
  el.textContent = parts.join(' · ');
  if (q.doubtful) el.insertAdjacentHTML('afterbegin', '<span class="doubtful">⚠ doubtful estimate</span> · ');
}
const fmt = (v) => (typeof v === 'number' ? v.toFixed(2) : String(v));

// ---- effect panel
export function wireKeyframePanel(studio) {
  const edits = studio.edits;
  const select = $('keyframe-effect');
  for (const name of EFFECTS) select.add(new Option(`${name.replace('_', ' ')} — ${METAPHORS[name]}`, name));
  const selected = () => studio.state.selectedKeyframe;
  select.addEventListener('change', (e) => edits.setKeyframe(selected(), { effect: e.target.value }));
  const setIntensity = (value) => {
    const v = Number(value);
    if (value !== '' && isFinite(v)) edits.setKeyframe(selected(), { intensity: Math.min(1, Math.max(-1, v)) });
  };
  $('keyframe-intensity').addEventListener('change', (e) => setIntensity(e.target.value));
  $('keyframe-intensity-slider').addEventListener('input', (e) => { $('keyframe-intensity').value = e.target.value; });
  $('keyframe-intensity-slider').addEventListener('change', (e) => setIntensity(e.target.value));
  $('keyframe-start').addEventListener('change', (e) => setBound(studio, 'start_s', Number(e.target.value)));
  $('keyframe-end').addEventListener('change', (e) => setBound(studio, 'end_s', Number(e.target.value)));
  $('add-keyframe').addEventListener('click', () => addKeyframeAtPlayhead(studio));
  $('delete-keyframe').addEventListener('click', () => deleteSelectedKeyframe(studio));
  $('restore-effects').addEventListener('click', () => { studio.state.selectedKeyframe = -1; edits.restoreAutomaticEffects(); });
}

// A typed start or end, kept inside the gap between the neighbours.
function setBound(studio, field, value) {
  const i = studio.state.selectedKeyframe;
  const list = studio.edits.keyframes();
  const k = list[i];
  if (!k || !isFinite(value)) return;
  const [lo, hi] = freeGap(list, i, (k.start_s + k.end_s) / 2, studio.state.film.duration_s);
  const segment = { start_s: k.start_s, end_s: k.end_s };
  if (field === 'start_s') segment.start_s = Math.min(Math.max(lo, value), k.end_s - MIN_EFFECT_S);
  else segment.end_s = Math.max(Math.min(hi, value), k.start_s + MIN_EFFECT_S);
  studio.edits.setKeyframe(i, segment);
}

export function addKeyframeAtPlayhead(studio) {
  const t = studio.currentTime();
  const list = studio.edits.keyframes();
  const duration = studio.state.film.duration_s;
  if (list.some((k) => t >= k.start_s && t < k.end_s)) return studio.toast('An effect is already there: move the playhead to a free place.');
  const [, hi] = freeGap(list, -1, t, duration);
  const end = Math.min(hi, t + 2);
  if (end - t < MIN_EFFECT_S * 2) return studio.toast('No room for an effect at the playhead.');
  const index = studio.edits.addKeyframe({ start_s: round6(t), end_s: round6(end), effect: studio.state.lastEffect || 'zoom_in', intensity: 1 });
  studio.state.selectedKeyframe = index;
  studio.render();
}

export function deleteSelectedKeyframe(studio) {
  const i = studio.state.selectedKeyframe;
  if (i < 0 || i >= studio.edits.keyframes().length) return;
  studio.state.selectedKeyframe = -1;
  studio.edits.deleteKeyframe(i);
}

export function renderKeyframePanel(studio) {
  const i = studio.state.selectedKeyframe;
  const k = studio.edits.keyframes()[i];
  $('keyframe-fields').classList.toggle('inactive', !k);
  for (const id of ['keyframe-effect', 'keyframe-intensity', 'keyframe-intensity-slider', 'keyframe-start', 'keyframe-end', 'delete-keyframe']) {
    $(id).disabled = !k;
  }
  $('restore-effects').disabled = !studio.edits.hasKeyframes;
  $('keyframe-title').textContent = k
    ? `#${i} · ${k.start_s.toFixed(2)}–${k.end_s.toFixed(2)} s${studio.edits.hasKeyframes ? '' : ' · automatic'}`
    : 'none selected';
  if (!k) return;
  setValue('keyframe-effect', table1Name(k.effect));
  setValue('keyframe-intensity', k.intensity);
  setValue('keyframe-intensity-slider', k.intensity);
  setValue('keyframe-start', k.start_s.toFixed(2));
  setValue('keyframe-end', k.end_s.toFixed(2));
}

// ---- effect blocks over the timeline's effects lane
export function renderKeyframeBlocks(studio) {
  const layer = $('keyframe-layer');
  const lane = laneByKey('effects');
  layer.style.top = `${lane.top}px`;
  layer.style.height = `${lane.height}px`;
  const list = studio.edits.keyframes();
  while (layer.children.length > list.length) layer.lastChild.remove();
  while (layer.children.length < list.length) layer.appendChild(newBlock(studio));
  list.forEach((k, i) => updateBlock(studio, layer.children[i], k, i));
}

function newBlock(studio) {
  const block = document.createElement('div');
  block.className = 'keyframe';
  block.innerHTML = '<span class="label"></span><span class="edge l"></span><span class="edge r"></span>';
  block.addEventListener('pointerdown', (e) => startDrag(studio, block, e));
  return block;
}

function updateBlock(studio, block, k, i) {
  const tl = studio.timeline;
  const x0 = tl.timeToX(k.start_s), x1 = tl.timeToX(k.end_s);
  block.id = `keyframe-${i}`;
  block.dataset.testid = `keyframe-${i}`;
  block.dataset.index = i;
  block.style.left = `${x0}px`;
  block.style.width = `${Math.max(4, x1 - x0)}px`;
  block.hidden = x1 < 0 || x0 > tl.width;
  block.classList.toggle('selected', i === studio.state.selectedKeyframe);
  block.classList.toggle('automatic', !studio.edits.hasKeyframes);
  block.classList.toggle('negative', k.intensity < 0);
  const name = table1Name(k.effect);
  block.title = `${name} (${METAPHORS[name] || ''}), intensity ${k.intensity}, ${k.start_s.toFixed(2)}–${k.end_s.toFixed(2)} s`;
  block.querySelector('.label').textContent = `${METAPHORS[name] || name} ${Number(k.intensity).toFixed(2)}`;
}

// Drag the body to move, an edge to resize; the segment stays between its neighbours.
function startDrag(studio, block, e) {
  if (e.button !== 0) return;
  e.preventDefault();
  e.stopPropagation();
  const index = Number(block.dataset.index);
  const list = studio.edits.keyframes();
  const k = list[index];
  const mode = e.target.classList.contains('l') ? 'start' : e.target.classList.contains('r') ? 'end' : 'move';
  const [lo, hi] = freeGap(list, index, (k.start_s + k.end_s) / 2, studio.state.film.duration_s);
  const drag = { x: e.clientX, start: k.start_s, end: k.end_s, lo, hi, moved: false };
  studio.state.selectedKeyframe = index;
  studio.state.lastEffect = table1Name(k.effect);
  studio.edits.beginGesture();
  block.classList.add('dragging');
  const move = (ev) => dragTo(studio, index, mode, drag, ev.clientX);
  const up = () => {
    window.removeEventListener('pointermove', move);
    window.removeEventListener('pointerup', up);
    block.classList.remove('dragging');
    studio.edits.endGesture();
  };
  window.addEventListener('pointermove', move);
  window.addEventListener('pointerup', up);
  studio.render();
}

function dragTo(studio, index, mode, drag, clientX) {
  const tl = studio.timeline;
  const dt = ((clientX - drag.x) / tl.width) * (tl.view.to - tl.view.from);
  const snap = (t) => snapToFrame(t, studio.state.film.fps);
  let start = drag.start, end = drag.end;
  if (mode === 'move') {
    const length = drag.end - drag.start;
    start = Math.min(Math.max(drag.lo, snap(drag.start + dt)), drag.hi - length);
    end = start + length;
  } else if (mode === 'start') {
    start = Math.min(Math.max(drag.lo, snap(drag.start + dt)), drag.end - MIN_EFFECT_S);
  } else {
    end = Math.max(Math.min(drag.hi, snap(drag.end + dt)), drag.start + MIN_EFFECT_S);
  }
  studio.edits.moveKeyframeLive(index, round6(start), round6(end));
}

const snapToFrame = (t, fps) => (fps > 0 ? Math.round(t * fps) / fps : t);
// Microseconds: readable numbers in the edits file, a moved effect keeps its length.
const round6 = (t) => Math.round(t * 1e6) / 1e6;

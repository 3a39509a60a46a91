// hapcine studio: the page's state and wiring (docs/studio.md).
import { api, videoPending } from './api.js';
import { EditsModel } from './edits.js';
import { Timeline, LANES, TIMELINE_HEIGHT, formatTime } from './timeline.js';
import { SeatView } from './seat_view.js';
import * as panels from './panels.js';
import { wireKeyboard } from './keys.js';

const $ = (id) => document.getElementById(id);
const MAX_OVERVIEW_POINTS = 2000, MAX_POINTS = 20000, DETAIL_DELAY_MS = 60;

const state = {
  films: [], film: null, selectedShot: -1, selectedKeyframe: -1, lastEffect: 'zoom_in',
  saving: false, curvesLoadMs: null, detailRequests: 0,
};

const studio = {
  state,
  edits: new EditsModel(() => studio.render()),
  timeline: new Timeline($('timeline')),
  seat: null,
  video: $('video'),
  currentTime: () => $('video').currentTime || 0,
  toast,
  render,
  seek,
  setView,
  save,
};
studio.seat = new SeatView($('seat-view'), $('seat-readout'), (from, to) => api.track(state.film.id, from, to));
state.edits = studio.edits;
studio.timeline.onThumbnail = () => scheduleRender();
state.view = studio.timeline.view;

window.hapcineStudio = {
  timeToX: (t) => studio.timeline.timeToX(t),
  xToTime: (x) => studio.timeline.xToTime(x),
  state,
  setView,
  lanes: LANES,
  timeline: studio.timeline,
};

// ---- films
async function init() {
  buildLaneLabels();
  wireTimeline();
  wireToolbar();
  panels.wireShotPanel(studio);
  panels.wireKeyframePanel(studio);
  wireKeyboard(studio);
  // Any change of the canvases' size (window, a wrapped tool bar) redraws them.
  const observer = new ResizeObserver(() => onResize());
  observer.observe($('timeline-wrap'));
  observer.observe($('seat-view'));
  window.addEventListener('beforeunload', (e) => { if (studio.edits.dirty) { e.preventDefault(); e.returnValue = ''; } });
  onResize();
  requestAnimationFrame(tick);
  try {
    state.films = await api.films();
  } catch (e) {
    return toast(`Cannot list the films: ${e.message}`);
  }
  const select = $('film-select');
  for (const f of state.films) select.add(new Option(f.name, f.id));
  select.addEventListener('change', () => switchFilm(select.value));
  const wanted = location.hash.slice(1);
  const first = state.films.find((f) => f.id === wanted) || state.films[0];
  if (!first) return toast('The server has no film.');
  select.value = first.id;
  await loadFilm(first.id);
}

async function switchFilm(id) {
  if (studio.edits.dirty && !confirm('This film has unsaved edits. Leave them?')) {
    $('film-select').value = state.film.id;
    return;
  }
  await loadFilm(id);
}

async function loadFilm(id) {
  location.hash = id;
  const started = performance.now();
  // The overview needs only the duration (in the list): all three at once.
  const summary = state.films.find((f) => f.id === id);
  const overview = summary ? api.curves(id, 0, summary.duration_s, overviewPoints()) : null;
  const [film, edits] = await Promise.all([api.film(id), api.edits(id)]);
  state.film = film;
  state.selectedShot = film.shots.length ? film.shots[0].shot : -1;
  state.selectedKeyframe = -1;
  $('film-info').textContent = `${film.width}×${film.height} · ${Number(film.fps).toFixed(3).replace(/\.?0+$/, '')} fps · ${formatTime(film.duration_s)} · ${film.shots.length} shot(s) · ${film.model}`;
  document.title = `${film.name} — hapcine studio`;
  studio.timeline.setFilm(film);
  state.view = studio.timeline.view;
  studio.seat.setSeat(film.seat, film.duration_s);
  studio.seat.invalidate();
  studio.edits.load(edits, film.effects);
  setSaveStatus('', '');
  loadVideo(film.video_url);
  await loadCurves(overview);
  state.curvesLoadMs = performance.now() - started;
  render();
  state.readyMs = performance.now();   // since the navigation started: the page is usable
}

// The whole film at about one bucket per pixel (the view starts there).
const overviewPoints = () => Math.min(MAX_OVERVIEW_POINTS, Math.max(500, Math.ceil(studio.timeline.width)));

async function loadCurves(pending = null) {
  const overview = await (pending || api.curves(state.film.id, 0, state.film.duration_s, overviewPoints()));
  studio.timeline.setOverview(overview);
  requestDetail();
}

async function loadVideo(url) {
  const video = studio.video;
  const overlay = $('video-overlay');
  for (;;) {
    let pending = null;
    try { pending = await videoPending(url); } catch (e) { /* the element reports its own errors */ }
    if (!pending) break;
    overlay.hidden = false;
    const eta = pending.eta_s !== undefined ? ` · about ${Math.ceil(pending.eta_s)} s left` : '';
    overlay.textContent = `Making a playable copy of the film: ${Math.round(100 * (pending.progress || 0))} %${eta}`;
    await sleep(1000);
  }
  overlay.hidden = true;
  video.src = url;
}

// ---- level of detail: the visible range at one bucket per pixel
let detailTimer = null;
function requestDetail() {
  clearTimeout(detailTimer);
  detailTimer = setTimeout(fetchDetail, DETAIL_DELAY_MS);
}

async function fetchDetail() {
  const film = state.film;
  const { from, to } = studio.timeline.view;
  if (!film || (from <= 0 && to >= film.duration_s && studio.timeline.overview)) return;
  const serial = ++state.detailRequests;
  const points = Math.min(MAX_POINTS, Math.max(50, Math.ceil(studio.timeline.width)));
  try {
    // Rounded outwards to the 0.1 ms the request carries, so that the answer covers the view.
    const curves = await api.curves(film.id, Math.floor(from * 1e4) / 1e4, Math.ceil(to * 1e4) / 1e4, points);
    if (serial !== state.detailRequests || film !== state.film) return;
    studio.timeline.setDetail(curves);
    render();
  } catch (e) { /* the overview stays */ }
}

// ---- view and seeking
function setView(from, to) {
  const film = state.film;
  if (!film) return;
  const duration = film.duration_s;
  const minSpan = Math.min(duration, Math.max(0.25, 6 / (film.fps || 24)));
  let span = Math.min(duration, Math.max(minSpan, to - from));
  from = Math.min(Math.max(0, from), duration - span);
  studio.timeline.view = { from, to: from + span };
  state.view = studio.timeline.view;
  render();
  requestDetail();
}

function zoomAround(t, factor) {
  const { from, to } = studio.timeline.view;
  setView(t - (t - from) * factor, t + (to - t) * factor);
}

function seek(t) {
  const film = state.film;
  if (!film) return;
  studio.video.currentTime = Math.min(Math.max(0, t), film.duration_s);
  drawPlayhead();
}

function wireTimeline() {
  const canvas = $('timeline');
  canvas.addEventListener('pointerdown', (e) => {
    const pan = e.button === 1 || (e.button === 0 && (e.shiftKey || e.altKey));
    if (e.button !== 0 && !pan) return;
    e.preventDefault();
    canvas.setPointerCapture(e.pointerId);
    const x0 = e.offsetX, view0 = { ...studio.timeline.view };
    const onMove = (ev) => {
      if (pan) {
        const dt = ((ev.offsetX - x0) / studio.timeline.width) * (view0.to - view0.from);
        setView(view0.from - dt, view0.to - dt);
      } else seekAtX(ev.offsetX, ev.offsetY);
    };
    if (!pan) seekAtX(e.offsetX, e.offsetY, true);
    canvas.addEventListener('pointermove', onMove);
    canvas.addEventListener('pointerup', () => canvas.removeEventListener('pointermove', onMove), { once: true });
  });
  canvas.addEventListener('wheel', (e) => {
    e.preventDefault();
    const tl = studio.timeline;
    if (e.shiftKey || Math.abs(e.deltaX) > Math.abs(e.deltaY)) {
      const d = (e.shiftKey ? e.deltaY : e.deltaX) || e.deltaY;
      const dt = (d / tl.width) * (tl.view.to - tl.view.from);
      setView(tl.view.from + dt, tl.view.to + dt);
    } else zoomAround(tl.xToTime(e.offsetX), Math.exp(e.deltaY * 0.0015));
  }, { passive: false });
  canvas.addEventListener('dblclick', (e) => {
    const lane = LANES.find((l) => e.offsetY >= l.top && e.offsetY < l.top + l.height);
    if (lane && lane.key === 'effects') panels.addKeyframeAtPlayhead(studio);
  });
}

// A click selects the shot under it (and no effect) and seeks.
function seekAtX(x, y, first = false) {
  const t = studio.timeline.xToTime(x);
  if (first) state.selectedKeyframe = -1;
  seek(t);
  render();
}

function wireToolbar() {
  $('undo').addEventListener('click', () => studio.edits.undo());
  $('redo').addEventListener('click', () => studio.edits.redo());
  $('save').addEventListener('click', save);
  $('zoom-in').addEventListener('click', () => zoomAround(studio.currentTime(), 0.5));
  $('zoom-out').addEventListener('click', () => zoomAround(studio.currentTime(), 2));
  $('zoom-fit').addEventListener('click', () => setView(0, state.film ? state.film.duration_s : 1));
  $('help-button').addEventListener('click', () => { $('help').hidden = !$('help').hidden; });
  for (const kind of ['haptic', 'hjif', 'preview']) $(`export-${kind}`).addEventListener('click', () => exportFilm(kind));
}

function buildLaneLabels() {
  const labels = $('lane-labels');
  for (const lane of LANES) {
    const div = document.createElement('div');
    div.style.height = `${lane.height}px`;
    div.textContent = lane.label;
    if (lane.series && lane.series.length > 1) {
      const legend = document.createElement('div');
      legend.className = 'legend';
      for (const [name, color] of lane.series) {
        const item = document.createElement('i');
        item.style.color = color;
        item.textContent = name.replace(/^(head|left|right)_/, '');
        legend.appendChild(item);
      }
      div.appendChild(legend);
    }
    labels.appendChild(div);
  }
}

// ---- rendering
let renderPending = false;
// One render at the next frame for any number of requests (thumbnails arriving).
function scheduleRender() {
  if (renderPending) return;
  renderPending = true;
  requestAnimationFrame(() => { renderPending = false; render(); });
}

function render() {
  if (!state.film) return;
  const tl = studio.timeline;
  const started = performance.now();
  tl.draw({ editsModel: studio.edits, selectedShot: state.selectedShot });
  state.drawMs = performance.now() - started;
  panels.renderKeyframeBlocks(studio);
  panels.renderShotPanel(studio);
  panels.renderKeyframePanel(studio);
  $('undo').disabled = !studio.edits.canUndo;
  $('redo').disabled = !studio.edits.canRedo;
  $('save').classList.toggle('dirty', studio.edits.dirty);
  $('save').textContent = studio.edits.dirty ? 'Save •' : 'Save';
  $('view-range').textContent = `${formatTime(tl.view.from, 0.1)} – ${formatTime(tl.view.to, 0.1)}`;
  drawPlayhead();
}

function onResize() {
  $('timeline').style.height = `${TIMELINE_HEIGHT}px`;
  studio.timeline.resize();
  studio.seat.resize();
  if (state.film) studio.seat.draw(studio.currentTime());
  render();
  requestDetail();
}

function shotAt(t) {
  const shots = state.film ? state.film.shots : [];
  let found = shots.length ? shots[0].shot : -1;
  for (const s of shots) if (t >= s.start_s) found = s.shot;
  return found;
}

function drawPlayhead() {
  const tl = studio.timeline;
  const t = studio.currentTime();
  const x = tl.timeToX(t);
  const playhead = $('playhead');
  playhead.hidden = x < 0 || x > tl.width;
  playhead.style.left = `${x}px`;
}

let lastShown = null;
// Every animation frame: playhead, seat, clock; the view follows a playing video.
function tick() {
  requestAnimationFrame(tick);
  if (!state.film) return;
  const t = studio.currentTime();
  const tl = studio.timeline;
  if (!studio.video.paused && (t > tl.view.to || t < tl.view.from)) {
    const span = tl.view.to - tl.view.from;
    setView(t - 0.1 * span, t + 0.9 * span);
  }
  const shot = shotAt(t);
  if (shot !== state.selectedShot) { state.selectedShot = shot; render(); }
  if (t === lastShown && studio.video.paused && !studio.seat.loading) return;
  lastShown = t;
  drawPlayhead();
  studio.seat.draw(t);
  showClock(t);
}

function showClock(t) {
  const film = state.film;
  $('time-display').textContent = `${formatTime(t, 0.1)} / ${formatTime(film.duration_s, 0.1)}`;
  const frame = Math.floor(t * film.fps + 1e-6);
  $('clock-detail').textContent = `frame ${frame} · shot #${state.selectedShot}`;
}

// ---- save
async function save() {
  if (state.saving || !state.film) return;
  // A field being typed in commits its value (its change event) first.
  if (document.activeElement && document.activeElement !== document.body) document.activeElement.blur();
  if (!studio.edits.dirty) return setSaveStatus('ok', `No changes · revision ${studio.edits.revision}`);
  state.saving = true;
  $('save').disabled = true;
  setSaveStatus('', 'Saving…');
  const started = performance.now();
  try {
    const answer = await api.saveEdits(state.film.id, studio.edits.toJson());
    studio.edits.markSaved(answer.revision);
    await refreshAfterSave();
    state.lastSaveMs = performance.now() - started;
    setSaveStatus('ok', `Saved · revision ${answer.revision} · track updated`);
  } catch (e) {
    if (e.status === 409) showConflict(e.body.revision);
    else setSaveStatus('error', `Not saved: ${e.message}`);
  } finally {
    state.saving = false;
    $('save').disabled = false;
  }
}

async function refreshAfterSave() {
  const film = await api.film(state.film.id);
  Object.assign(state.film, { shots: film.shots, effects: film.effects, revision: film.revision });
  if (!studio.edits.hasKeyframes) studio.edits.automaticEffects = film.effects || [];
  studio.seat.invalidate();
  await loadCurves();
  render();
}

function showConflict(current) {
  const el = setSaveStatus('conflict',
    `Not saved: this film was saved elsewhere (revision ${current ?? '?'}; yours is based on ${studio.edits.revision}).`);
  const reload = document.createElement('button');
  reload.id = 'reload-edits';
  reload.textContent = 'Reload theirs';
  reload.title = 'Load the saved edits; your unsaved changes are dropped';
  reload.addEventListener('click', reloadEdits);
  const overwrite = document.createElement('button');
  overwrite.id = 'overwrite-edits';
  overwrite.textContent = 'Save mine over theirs';
  overwrite.addEventListener('click', () => {
    studio.edits.edits.revision = current;
    save();
  });
  el.append(reload, overwrite);
}

async function reloadEdits() {
  const edits = await api.edits(state.film.id);
  const film = await api.film(state.film.id);
  Object.assign(state.film, { shots: film.shots, effects: film.effects });
  studio.edits.load(edits, film.effects);
  state.selectedKeyframe = -1;
  studio.seat.invalidate();
  await loadCurves();
  setSaveStatus('ok', `Reloaded · revision ${edits.revision}`);
  render();
}

function setSaveStatus(kind, text) {
  const el = $('save-status');
  el.className = kind;
  el.textContent = text;
  return el;
}

// ---- export
async function exportFilm(kind) {
  const text = $('export-text'), bar = $('export-progress'), status = $('export-status');
  status.classList.remove('error');
  text.textContent = `Exporting ${kind}…`;
  try {
    const answer = await api.exportFilm(state.film.id, kind);
    const path = answer.job ? await followJob(answer.job, bar, text) : answer.path;
    text.textContent = `Wrote ${path.split('/').pop()}`;
    text.title = path;
  } catch (e) {
    status.classList.add('error');
    text.textContent = `Export failed: ${e.message}`;
  } finally {
    bar.hidden = true;
  }
}

async function followJob(jobId, bar, text) {
  bar.hidden = false;
  for (;;) {
    const job = await api.job(jobId);
    if (job.state === 'done') return job.path;
    if (job.state === 'failed') throw new Error(job.error || 'the job failed');
    bar.value = job.progress || 0;
    const eta = job.eta_s !== undefined && job.eta_s !== null ? ` · ${Math.ceil(job.eta_s)} s left` : '';
    text.textContent = `Preview ${Math.round(100 * (job.progress || 0))} %${eta}`;
    await sleep(500);
  }
}

// ---- messages
let toastTimer = null;
function toast(message, kind = 'error') {
  const el = $('toast');
  el.textContent = message;
  el.className = kind;
  el.hidden = false;
  clearTimeout(toastTimer);
  toastTimer = setTimeout(() => { el.hidden = true; }, 5000);
}

const sleep = (ms) => new Promise((resolve) => setTimeout(resolve, ms));

init().catch((e) => toast(e.message));

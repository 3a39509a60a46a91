// The timeline: one canvas whose x maps linearly to time over the visible
// range [view.from, view.to] (x = 0 at the canvas' left edge, in CSS pixels).
// Lanes, top to bottom: ruler, shots, effects (keyframe blocks are DOM
// elements over the canvas so they can be dragged and found by tests), camera
// angles, field of view, translation, confidence, and the three actuators.

const COLORS = {
  x: '#ff6b6b', y: '#6bdc6b', z: '#5aa9ff', pan: '#ffb547', tilt: '#5ee0c6', roll: '#d98cff',
  fov: '#f7e463', confidence: '#7fd17f', grid: '#2b313c', text: '#9aa3b2', lowconf: 'rgba(255,80,80,0.13)',
};

// Each lane: key, label, height, series drawn (name in the curves answer, colour, legend).
export const LANES = [
  { key: 'ruler', label: '', height: 22 },
  { key: 'shots', label: 'Shots', height: 50 },
  { key: 'effects', label: 'Effects', height: 30 },
  { key: 'angles', label: 'Pan · tilt · roll (°)', height: 62, series: [
    ['pan', COLORS.pan], ['tilt', COLORS.tilt], ['roll', COLORS.roll]] },
  { key: 'fov', label: 'FOV (°)', height: 36, series: [['fov', COLORS.fov]] },
  { key: 'translation', label: 'Translation x · y · z', height: 50, series: [
    ['tx', COLORS.x], ['ty', COLORS.y], ['tz', COLORS.z]] },
  { key: 'confidence', label: 'Confidence', height: 30, series: [['confidence', COLORS.confidence]], range: [0, 1] },
  { key: 'head', label: 'Head (mm)', height: 44, actuator: true, series: [
    ['head_x', COLORS.x], ['head_y', COLORS.y], ['head_z', COLORS.z]] },
  { key: 'left', label: 'Left hand (mm)', height: 44, actuator: true, series: [
    ['left_x', COLORS.x], ['left_y', COLORS.y], ['left_z', COLORS.z]] },
  { key: 'right', label: 'Right hand (mm)', height: 44, actuator: true, series: [
    ['right_x', COLORS.x], ['right_y', COLORS.y], ['right_z', COLORS.z]] },
];
let top = 0;
for (const lane of LANES) { lane.top = top; top += lane.height; }
export const TIMELINE_HEIGHT = top;
export const laneByKey = (key) => LANES.find((l) => l.key === key);

// Under this the frame is as doubtful as a doubtful shot's median (docs/estimate.md,
// "Shot quality"); lost frames have confidence 0.
const LOW_CONFIDENCE = 0.12;
const MAX_THUMBNAIL_LOADS = 2;
const MIN_THUMBNAIL_PX = 40, MIN_LABEL_PX = 36, MIN_DETAIL_PX = 5;

export class Timeline {
  constructor(canvas) {
    this.canvas = canvas;
    this.ctx = canvas.getContext('2d');
    this.film = null;
    this.view = { from: 0, to: 1 };
    this.overview = null;   // curves of the whole film
    this.detail = null;     // curves of (about) the visible range, at screen resolution
    this.thumbnails = new Map();
    this.ranges = {};
    this.width = 0;
  }

  setFilm(film) {
    this.film = film;
    this.view = { from: 0, to: film.duration_s };
    this.thumbnailQueue = [];
    this.thumbnailsLoading = 0;
  }

  // Thumbnails are made by the server on first request: ask only for the shots
  // wide enough on screen to show one, a few at a time, so that a film of
  // hundreds of shots does not hold up the curves.
  wantThumbnail(shot) {
    const url = shot.thumbnail_url;
    if (!url || this.thumbnails.has(url)) return;
    this.thumbnails.set(url, null);
    this.thumbnailQueue.push(url);
    this.pumpThumbnails();
  }

  pumpThumbnails() {
    while (this.thumbnailsLoading < MAX_THUMBNAIL_LOADS && this.thumbnailQueue.length) {
      const url = this.thumbnailQueue.shift();
      const image = new Image();
      this.thumbnailsLoading++;
      image.onload = image.onerror = () => {
        this.thumbnailsLoading--;
        this.thumbnails.set(url, image);
        this.pumpThumbnails();
        if (this.onThumbnail) this.onThumbnail();
      };
      image.src = url;
    }
  }

  setOverview(curves) { this.overview = curves; this.ranges = seriesRanges(curves); this.detail = null; }
  setDetail(curves) { this.detail = curves; }

  timeToX(t) { return ((t - this.view.from) / (this.view.to - this.view.from)) * this.width; }
  xToTime(x) { return this.view.from + (x / this.width) * (this.view.to - this.view.from); }

  resize() {
    const ratio = window.devicePixelRatio || 1;
    this.width = this.canvas.clientWidth;
    this.canvas.width = Math.round(this.width * ratio);
    this.canvas.height = Math.round(TIMELINE_HEIGHT * ratio);
    this.ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  }

  // The curves that cover the view best: the detail when it spans the view.
  visibleCurves() {
    const d = this.detail;
    if (d && d.from <= this.view.from + 1e-4 && d.to >= this.view.to - 1e-4) return d;
    return this.overview;
  }

  draw(state = {}) {
    if (!this.film || !this.width) return;
    const ctx = this.ctx;
    ctx.clearRect(0, 0, this.width, TIMELINE_HEIGHT);
    this.drawRuler();
    this.drawShots(state.editsModel, state.selectedShot);
    const curves = this.visibleCurves();
    if (curves) this.drawLowConfidence(curves);
    for (const lane of LANES) {
      this.drawLaneFrame(lane);
      if (lane.series && curves) this.drawSeries(lane, curves);
    }
    this.drawCuts();
  }

  drawLaneFrame(lane) {
    const ctx = this.ctx;
    ctx.fillStyle = COLORS.grid;
    ctx.fillRect(0, lane.top + lane.height - 1, this.width, 1);
    if (lane.series) {
      ctx.fillStyle = 'rgba(255,255,255,0.06)';
      ctx.fillRect(0, lane.top + lane.height / 2, this.width, 1);
    }
  }

  drawRuler() {
    const ctx = this.ctx;
    const span = this.view.to - this.view.from;
    const step = niceStep(span / Math.max(1, this.width / 90));
    ctx.fillStyle = '#161a21';
    ctx.fillRect(0, 0, this.width, LANES[0].height);
    ctx.fillStyle = COLORS.text;
    ctx.font = '11px system-ui, sans-serif';
    ctx.textBaseline = 'middle';
    for (let t = Math.ceil(this.view.from / step) * step; t <= this.view.to; t += step) {
      const x = Math.round(this.timeToX(t)) + 0.5;
      ctx.fillRect(x, 14, 1, 8);
      ctx.fillText(formatTime(t, step), x + 3, 9);
    }
  }

  drawShots(editsModel, selectedShot) {
    const lane = laneByKey('shots');
    for (const shot of this.film.shots) {
      // Clamped to the canvas: a long shot at a high zoom stays cheap, its label in view.
      const x0 = Math.max(-4, this.timeToX(shot.start_s)), x1 = Math.min(this.width + 4, this.timeToX(shot.end_s));
      if (x1 < 0 || x0 > this.width) continue;
      const edit = editsModel ? editsModel.shotEdit(shot.shot) : { shot: shot.shot };
      this.drawShotBlock(shot, edit, x0, x1, lane, shot.shot === selectedShot, this.timeToX(shot.start_s));
    }
  }

  drawShotBlock(shot, edit, x0, x1, lane, selected, stripX) {
    const ctx = this.ctx;
    const y = lane.top + 3, h = lane.height - 6, w = Math.max(1, x1 - x0 - 2);
    if (w < MIN_DETAIL_PX) return this.drawThinShot(shot, edit, x0, w, y, h, selected);
    if (w >= MIN_THUMBNAIL_PX) this.wantThumbnail(shot);
    ctx.save();
    ctx.beginPath();
    ctx.rect(x0 + 1, y, w, h);
    ctx.clip();
    ctx.fillStyle = shot.shot % 2 ? '#27303d' : '#222a35';
    ctx.fillRect(x0 + 1, y, w, h);
    this.drawFilmstrip(shot, stripX + 1, x0 + 1, y, w, h);
    const muted = edit.mute || edit.gain === 0;
    if (muted) { ctx.fillStyle = 'rgba(10,12,16,0.65)'; ctx.fillRect(x0 + 1, y, w, h); }
    if (shot.quality && shot.quality.doubtful) hatch(ctx, x0 + 1, y, w, h);
    if (w >= MIN_LABEL_PX) this.drawShotLabel(shot, edit, x0 + 1, y, muted);
    ctx.restore();
    ctx.strokeStyle = selected ? '#4da3ff' : 'rgba(255,255,255,0.18)';
    ctx.lineWidth = selected ? 2 : 1;
    ctx.strokeRect(x0 + 1.5, y + 0.5, w - 1, h - 1);
  }

  // Copies of the shot's thumbnail side by side from the shot's start (stripX),
  // the visible ones only.
  // A shot a few pixels wide (a long film seen whole): a plain stripe.
  drawThinShot(shot, edit, x, w, y, h, selected) {
    const ctx = this.ctx;
    const muted = edit.mute || edit.gain === 0;
    ctx.fillStyle = selected ? '#4da3ff' : shot.quality && shot.quality.doubtful ? '#6b3a35'
      : muted ? '#15181d' : shot.shot % 2 ? '#2f3a4a' : '#252d39';
    ctx.fillRect(x + 1, y, w, h);
  }

  drawFilmstrip(shot, stripX, x, y, w, h) {
    const image = this.thumbnails.get(shot.thumbnail_url);
    if (!image || !image.complete || !image.naturalWidth) return;
    const tw = (image.naturalWidth / image.naturalHeight) * h;
    this.ctx.globalAlpha = 0.8;
    const firstTile = stripX + Math.floor((x - stripX) / tw) * tw;
    for (let tx = firstTile; tx < x + w; tx += tw) this.ctx.drawImage(image, tx, y, tw, h);
    this.ctx.globalAlpha = 1;
  }

  drawShotLabel(shot, edit, x, y, muted) {
    const ctx = this.ctx;
    const model = edit.model || shot.model || this.film.model || '';
    let text = `#${shot.shot} ${model}`;
    if (muted) text += ' · muted';
    else if (edit.gain !== undefined && edit.gain !== 1) text += ` · gain ${edit.gain}`;
    if (shot.quality && shot.quality.doubtful) text += ' · doubtful';
    ctx.font = '11px system-ui, sans-serif';
    const width = ctx.measureText(text).width + 8;
    ctx.fillStyle = 'rgba(0,0,0,0.6)';
    ctx.fillRect(x + 2, y + 2, width, 16);
    ctx.fillStyle = Object.keys(edit).length > 1 ? '#ffd27a' : '#e6e9ef';
    ctx.textBaseline = 'middle';
    ctx.fillText(text, x + 6, y + 10);
  }

  drawCuts() {
    const ctx = this.ctx;
    ctx.fillStyle = 'rgba(255,255,255,0.14)';
    for (const shot of this.film.shots.slice(1)) {
      const x = Math.round(this.timeToX(shot.start_s));
      if (x >= 0 && x <= this.width) ctx.fillRect(x, LANES[1].top, 1, TIMELINE_HEIGHT - LANES[1].top);
    }
  }

  // Buckets whose confidence is low: a red tint over the camera lanes.
  drawLowConfidence(curves) {
    const c = curves.series && curves.series.confidence;
    if (!c) return;
    const y0 = laneByKey('angles').top, y1 = laneByKey('confidence').top + laneByKey('confidence').height;
    const half = bucketHalfWidth(curves);
    this.ctx.fillStyle = COLORS.lowconf;
    curves.t.forEach((t, i) => {
      if (!(c.min[i] < LOW_CONFIDENCE)) return;
      const x0 = this.timeToX(t - half), x1 = this.timeToX(t + half);
      this.ctx.fillRect(x0, y0, Math.max(1, x1 - x0), y1 - y0);
    });
  }

  laneRange(lane) {
    if (lane.range) return lane.range;
    if (lane.actuator) {
      const half = this.film.seat && this.film.seat.workspace_half_m ? this.film.seat.workspace_half_m * 1000 : 50;
      return [-half, half];
    }
    let lo = Infinity, hi = -Infinity;
    for (const [name] of lane.series) {
      const r = this.ranges[name];
      if (r) { lo = Math.min(lo, r[0]); hi = Math.max(hi, r[1]); }
    }
    if (!isFinite(lo)) return [-1, 1];
    const m = Math.max(Math.abs(lo), Math.abs(hi), 1e-3) * 1.1;
    return lo >= 0 && lane.key === 'fov' ? [lo - 1, hi + 1] : [-m, m];
  }

  drawSeries(lane, curves) {
    const [lo, hi] = this.laneRange(lane);
    const yOf = (v) => lane.top + lane.height - 3 - ((v - lo) / (hi - lo || 1)) * (lane.height - 6);
    for (const [name, color] of lane.series) {
      const s = curves.series[name];
      if (!s) continue;
      this.drawBand(curves.t, s, yOf, color, lane.key === 'confidence' ? 0.35 : 0.22);
      this.drawLine(curves.t, s.mean, yOf, color);
    }
    this.drawLaneScale(lane, lo, hi);
  }

  // The min..max band as one polygon per run of valid buckets (one fill: a
  // rectangle per bucket costs far more in a software-rendered canvas).
  drawBand(t, s, yOf, color, alpha) {
    const ctx = this.ctx;
    ctx.fillStyle = color;
    ctx.globalAlpha = alpha;
    const half = t.length > 1 ? (t[1] - t[0]) / 2 : 0;
    const valid = (i) => isNum(s.min[i]) && isNum(s.max[i]);
    const [first, last] = this.visibleIndices(t);
    ctx.beginPath();
    for (let i = first; i < last;) {
      if (!valid(i)) { i++; continue; }
      let j = i;
      while (j + 1 < last && valid(j + 1)) j++;
      ctx.moveTo(this.timeToX(t[i] - half), yOf(s.max[i]));
      for (let k = i; k <= j; k++) ctx.lineTo(this.timeToX(t[k]), yOf(s.max[k]));
      ctx.lineTo(this.timeToX(t[j] + half), yOf(s.max[j]));
      ctx.lineTo(this.timeToX(t[j] + half), yOf(s.min[j]) + 1);
      for (let k = j; k >= i; k--) ctx.lineTo(this.timeToX(t[k]), yOf(s.min[k]) + 1);
      ctx.lineTo(this.timeToX(t[i] - half), yOf(s.min[i]) + 1);
      ctx.closePath();
      i = j + 1;
    }
    ctx.fill();
    ctx.globalAlpha = 1;
  }

  drawLine(t, values, yOf, color) {
    const ctx = this.ctx;
    ctx.strokeStyle = color;
    ctx.lineWidth = 1.25;
    ctx.beginPath();
    let pen = false;
    const [first, last] = this.visibleIndices(t);
    for (let i = first; i < last; i++) {
      if (!isNum(values[i])) { pen = false; continue; }
      const x = this.timeToX(t[i]), y = yOf(values[i]);
      if (pen) ctx.lineTo(x, y); else ctx.moveTo(x, y);
      pen = true;
    }
    ctx.stroke();
  }

  // [first, last) of the bucket centres t inside the view, plus one on each side.
  visibleIndices(t) {
    const first = Math.max(0, lowerBound(t, this.view.from) - 1);
    const last = Math.min(t.length, lowerBound(t, this.view.to) + 1);
    return [first, last];
  }

  drawLaneScale(lane, lo, hi) {
    const ctx = this.ctx;
    ctx.fillStyle = 'rgba(154,163,178,0.7)';
    ctx.font = '10px system-ui, sans-serif';
    ctx.textBaseline = 'top';
    ctx.fillText(formatValue(hi), this.width - 40, lane.top + 2);
    ctx.textBaseline = 'bottom';
    ctx.fillText(formatValue(lo), this.width - 40, lane.top + lane.height - 2);
  }
}

function seriesRanges(curves) {
  const ranges = {};
  for (const [name, s] of Object.entries(curves.series || {})) {
    let lo = Infinity, hi = -Infinity;
    for (const v of s.min) if (isNum(v)) lo = Math.min(lo, v);
    for (const v of s.max) if (isNum(v)) hi = Math.max(hi, v);
    if (isFinite(lo)) ranges[name] = [lo, hi];
  }
  return ranges;
}

function lowerBound(sorted, x) {
  let lo = 0, hi = sorted.length;
  while (lo < hi) { const mid = (lo + hi) >> 1; if (sorted[mid] < x) lo = mid + 1; else hi = mid; }
  return lo;
}

function bucketHalfWidth(curves) {
  const n = curves.t.length;
  return n > 0 ? (curves.to - curves.from) / n / 2 : 0;
}

function hatch(ctx, x, y, w, h) {
  ctx.strokeStyle = 'rgba(255,120,80,0.45)';
  ctx.lineWidth = 1;
  ctx.beginPath();
  for (let i = x - h; i < x + w; i += 8) { ctx.moveTo(i, y + h); ctx.lineTo(i + h, y); }
  ctx.stroke();
}

const isNum = (v) => typeof v === 'number' && isFinite(v);

export function niceStep(raw) {
  const steps = [1 / 24, 0.1, 0.2, 0.5, 1, 2, 5, 10, 15, 30, 60, 120, 300, 600, 900, 1800, 3600];
  return steps.find((s) => s >= raw) || 7200;
}

export function formatTime(t, step = 1) {
  const sign = t < 0 ? '-' : '';
  t = Math.abs(t);
  const h = Math.floor(t / 3600), m = Math.floor((t % 3600) / 60), s = t % 60;
  const digits = step < 1 ? 1 : 0;
  const sec = s.toFixed(digits).padStart(digits ? 4 : 2, '0');
  return sign + (h ? `${h}:${String(m).padStart(2, '0')}:${sec}` : `${m}:${sec}`);
}

function formatValue(v) {
  const a = Math.abs(v);
  return a >= 100 ? v.toFixed(0) : a >= 10 ? v.toFixed(1) : v.toFixed(2);
}

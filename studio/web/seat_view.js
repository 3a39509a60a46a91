// The seat seen from above (x right, screen at the top) with each actuator's
// workspace square and its grip, and a gauge of each grip's height, moving
// with the haptic track at the video's time. Samples come from /track in
// windows of a few tens of seconds and are interpolated linearly.

const ACTUATORS = [
  { key: 'head', label: 'Head', centre: 'head_m', color: '#ffb547' },
  { key: 'left', label: 'Left', centre: 'left_hand_m', color: '#5aa9ff' },
  { key: 'right', label: 'Right', centre: 'right_hand_m', color: '#5ee0c6' },
];
const DEFAULT_SEAT = {
  head_m: [0, 0.45, 0.05], left_hand_m: [-0.25, -0.2, -0.25], right_hand_m: [0.25, -0.2, -0.25],
  workspace_half_m: 0.05, usable_half_m: 0.045,
};
const WINDOW_BEFORE_S = 2, WINDOW_AFTER_S = 28, TRAIL_S = 0.6;
// The workspaces (10 cm cubes) are drawn this much larger than the chair so that
// a few millimetres of motion show.
const MAGNIFY = 2.5;

export class SeatView {
  constructor(canvas, readout, fetchTrack) {
    this.canvas = canvas;
    this.readout = readout;   // an element for the three positions in mm
    this.ctx = canvas.getContext('2d');
    this.fetchTrack = fetchTrack;   // (from, to) => Promise<track JSON>
    this.seat = DEFAULT_SEAT;
    this.track = null;
    this.loading = null;
    this.failedAt = -Infinity;
    this.lastTime = 0;
    this.duration = Infinity;
  }

  setSeat(seat, duration_s) {
    this.seat = Object.assign({}, DEFAULT_SEAT, seat || {});
    this.duration = duration_s || Infinity;
  }
  invalidate() { this.track = null; }

  // Ensures the samples around t are loaded (asynchronously).
  ensure(t) {
    const tr = this.track;
    const covered = tr && t >= tr.from && t <= tr.to - 1;
    // A failed request is retried after a pause, not at every frame.
    if (covered || this.loading || performance.now() - this.failedAt < 2000) return;
    const from = Math.max(0, t - WINDOW_BEFORE_S), to = Math.min(this.duration, t + WINDOW_AFTER_S);
    this.loading = this.fetchTrack(from, to)
      .then((json) => { this.track = Object.assign(json, { from, to: to >= this.duration ? Infinity : to }); })
      .catch(() => { this.failedAt = performance.now(); })
      .finally(() => { this.loading = null; this.draw(this.lastTime); });
  }

  // Grip displacements in mm at time t: {head:[x,y,z], left, right} or null.
  sample(t) {
    const tr = this.track;
    if (!tr || !tr.t || !tr.t.length) return null;
    const i = upperBound(tr.t, t);
    const out = {};
    for (const a of ACTUATORS) out[a.key] = interpolate(tr.t, tr[a.key], i, t);
    return out;
  }

  resize() {
    const ratio = window.devicePixelRatio || 1;
    this.width = this.canvas.clientWidth;
    this.height = this.canvas.clientHeight;
    this.canvas.width = Math.round(this.width * ratio);
    this.canvas.height = Math.round(this.height * ratio);
    this.ctx.setTransform(ratio, 0, 0, ratio, 0, 0);
  }

  draw(t) {
    this.lastTime = t;
    this.ensure(t);
    const ctx = this.ctx;
    ctx.clearRect(0, 0, this.width, this.height);
    const gaugeWidth = 80;
    const now = this.sample(t);
    this.drawTopView(this.width - gaugeWidth - 8, now, t);
    this.drawGauges(this.width - gaugeWidth, gaugeWidth, now);
    this.readout.textContent = now
      ? ACTUATORS.map((a) => `${a.key} ${now[a.key].map((v) => v.toFixed(1)).join(' ')}`).join(' · ') + ' mm'
      : '';
  }

  // Seat frame metres -> top-view pixels: x right, z backward (down).
  topViewScale(width) {
    const spanX = 0.8, spanZ = 0.6, h = this.height - 30;
    const scale = Math.min(width / spanX, h / spanZ);
    const ox = width / 2, oz = 20 + h / 2 + 0.1 * scale;   // z = -0.1 m (between head and hands) in the middle
    return { scale, toPx: (x, z) => [ox + x * scale, oz + z * scale] };
  }

  drawTopView(width, now, t) {
    const ctx = this.ctx;
    const { scale, toPx } = this.topViewScale(width);
    drawChair(ctx, toPx, scale);
    const half = this.seat.workspace_half_m * MAGNIFY * scale;
    const usable = this.seat.usable_half_m * MAGNIFY * scale;
    ctx.font = '11px system-ui, sans-serif';
    for (const a of ACTUATORS) {
      const c = this.seat[a.centre];
      const [cx, cz] = toPx(c[0], c[2]);
      ctx.fillStyle = 'rgba(20,24,30,0.85)';
      ctx.fillRect(cx - half, cz - half, 2 * half, 2 * half);
      ctx.strokeStyle = 'rgba(255,255,255,0.45)';
      ctx.strokeRect(cx - half, cz - half, 2 * half, 2 * half);
      ctx.setLineDash([3, 3]);
      ctx.strokeStyle = 'rgba(255,255,255,0.18)';
      ctx.strokeRect(cx - usable, cz - usable, 2 * usable, 2 * usable);
      ctx.setLineDash([]);
      ctx.fillStyle = 'rgba(255,255,255,0.25)';
      ctx.fillRect(cx - 4, cz, 9, 1);
      ctx.fillRect(cx, cz - 4, 1, 9);
      const grip = (d) => toPx(c[0] + (MAGNIFY * d[0]) / 1000, c[2] + (MAGNIFY * d[2]) / 1000);
      this.drawTrail(a, grip, t);
      const [px, pz] = grip(now ? now[a.key] : [0, 0, 0]);
      dot(ctx, px, pz, 5, a.color);
      ctx.fillStyle = '#9aa3b2';
      ctx.fillText(a.label, cx - half + 3, cz - half + 12);
    }
    ctx.fillStyle = '#6f7887';
    ctx.fillText(`top view, screen ↑ (grips ×${MAGNIFY})`, 6, 12);
  }

  drawTrail(a, grip, t) {
    const ctx = this.ctx;
    ctx.strokeStyle = a.color;
    ctx.globalAlpha = 0.5;
    ctx.beginPath();
    for (let k = 0; k <= 12; k++) {
      const s = this.sample(t - TRAIL_S * (1 - k / 12));
      if (!s) break;
      const [px, pz] = grip(s[a.key]);
      if (k) ctx.lineTo(px, pz); else ctx.moveTo(px, pz);
    }
    ctx.stroke();
    ctx.globalAlpha = 1;
  }

  // One vertical bar per actuator: its grip's height within the workspace.
  drawGauges(x0, width, now) {
    const ctx = this.ctx;
    const half = this.seat.workspace_half_m * 1000, usable = this.seat.usable_half_m * 1000;
    const top = 22, bottom = this.height - 22, barW = 14, gap = (width - 3 * barW) / 4;
    const yOf = (mm) => bottom - ((mm + half) / (2 * half)) * (bottom - top);
    ctx.font = '11px system-ui, sans-serif';
    ctx.fillStyle = '#6f7887';
    ctx.fillText('height (y)', x0 + 4, 12);
    ACTUATORS.forEach((a, i) => {
      const x = x0 + gap + i * (barW + gap);
      ctx.fillStyle = '#1b2029';
      ctx.fillRect(x, top, barW, bottom - top);
      ctx.fillStyle = 'rgba(255,255,255,0.08)';
      ctx.fillRect(x, yOf(usable), barW, yOf(-usable) - yOf(usable));
      ctx.fillStyle = 'rgba(255,255,255,0.3)';
      ctx.fillRect(x, yOf(0), barW, 1);
      const y = now ? now[a.key][1] : 0;
      ctx.fillStyle = a.color;
      ctx.fillRect(x - 3, yOf(y) - 2, barW + 6, 4);
      ctx.fillStyle = '#9aa3b2';
      ctx.fillText(a.label[0], x + barW / 2 - 3, bottom + 14);
    });
  }
}

function drawChair(ctx, toPx, scale) {
  ctx.fillStyle = '#222935';
  ctx.strokeStyle = '#39414f';
  const box = (x0, z0, x1, z1) => {
    const [a, b] = toPx(x0, z0), [c, d] = toPx(x1, z1);
    ctx.fillRect(a, b, c - a, d - b);
    ctx.strokeRect(a, b, c - a, d - b);
  };
  box(-0.22, -0.3, 0.22, 0.12);      // seat
  box(-0.3, -0.32, -0.22, 0.12);     // armrests
  box(0.22, -0.32, 0.3, 0.12);
  box(-0.22, 0.08, 0.22, 0.16);      // back
  const [hx, hz] = toPx(0, 0.02);
  ctx.beginPath();
  ctx.ellipse(hx, hz, 0.08 * scale, 0.1 * scale, 0, 0, 2 * Math.PI);
  ctx.fillStyle = '#2c3442';
  ctx.fill();
}

function dot(ctx, x, y, r, color) {
  ctx.beginPath();
  ctx.arc(x, y, r, 0, 2 * Math.PI);
  ctx.fillStyle = color;
  ctx.fill();
  ctx.strokeStyle = '#0d1015';
  ctx.stroke();
}

function upperBound(t, x) {
  let lo = 0, hi = t.length;
  while (lo < hi) { const mid = (lo + hi) >> 1; if (t[mid] <= x) lo = mid + 1; else hi = mid; }
  return lo;
}

function interpolate(t, rows, i, x) {
  if (!rows || !rows.length) return [0, 0, 0];
  if (i <= 0) return rows[0];
  if (i >= t.length) return rows[t.length - 1];
  const u = (x - t[i - 1]) / (t[i] - t[i - 1] || 1);
  return rows[i].map((v, k) => rows[i - 1][k] + u * (v - rows[i - 1][k]));
}

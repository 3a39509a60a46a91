// The film's edits (docs/formats.md, "Edits file") with undo and redo.
// Every change is a snapshot of the whole edits object: they are small, and a
// snapshot makes undo exact whatever the change was.

const clone = (value) => JSON.parse(JSON.stringify(value));

export const EFFECTS = ['crane_shot', 'dutch_angle', 'arcing', 'traveling', 'tilting', 'zoom_in', 'vertigo'];
export const METAPHORS = {
  crane_shot: 'flying away', dutch_angle: 'instability', arcing: 'intensification',
  traveling: 'crab walk', tilting: 'inferiority', zoom_in: 'walk forward', vertigo: 'vertigo',
};
const TABLE2_TO_TABLE1 = {
  flying_away: 'crane_shot', instability: 'dutch_angle', intensification: 'arcing',
  crab_walk: 'traveling', inferiority: 'tilting', walk_forward: 'zoom_in',
};
// The Table 1 name of an effect given by either name.
export const table1Name = (effect) => TABLE2_TO_TABLE1[effect] || effect;

export class EditsModel {
  constructor(onChange) {
    this.onChange = onChange;
    this.edits = { format: 'hapcine-edits', version: 1, revision: 0 };
    this.automaticEffects = [];
    this.undoStack = [];
    this.redoStack = [];
    this.saved = '';
    this.gestureStart = null;
  }

  // A freshly loaded edits file; effective = the segments the server uses now.
  load(edits, effective) {
    this.edits = clone(edits);
    if (!this.edits.format) this.edits.format = 'hapcine-edits';
    if (!this.edits.version) this.edits.version = 1;
    if (typeof this.edits.revision !== 'number') this.edits.revision = 0;
    this.automaticEffects = this.edits.keyframes ? [] : clone(effective || []);
    this.undoStack = [];
    this.redoStack = [];
    this.saved = this.snapshot();
    this.changed();
  }

  snapshot() { return JSON.stringify(this.edits); }
  get revision() { return this.edits.revision; }
  get dirty() { return this.snapshot() !== this.saved; }
  get canUndo() { return this.undoStack.length > 0; }
  get canRedo() { return this.redoStack.length > 0; }
  changed() { if (this.onChange) this.onChange(); }

  // One undoable step.
  apply(mutate) {
    const before = this.snapshot();
    mutate(this.edits);
    if (this.snapshot() === before) return;
    this.undoStack.push(before);
    this.redoStack = [];
    this.changed();
  }

  // A drag: one undo step from its start to its end, live updates between.
  beginGesture() { this.gestureStart = this.snapshot(); }
  applyLive(mutate) { mutate(this.edits); this.changed(); }
  endGesture() {
    if (this.gestureStart !== null && this.gestureStart !== this.snapshot()) {
      this.undoStack.push(this.gestureStart);
      this.redoStack = [];
    }
    this.gestureStart = null;
    this.changed();
  }

  undo() { this.step(this.undoStack, this.redoStack); }
  redo() { this.step(this.redoStack, this.undoStack); }
  step(from, to) {
    if (!from.length) return;
    to.push(this.snapshot());
    this.edits = JSON.parse(from.pop());
    this.changed();
  }

  markSaved(revision) {
    this.edits.revision = revision;
    // The revision is not an edit: rewrite the history with it so undo after a
    // save does not send a stale base revision.
    const fix = (s) => { const e = JSON.parse(s); e.revision = revision; return JSON.stringify(e); };
    this.undoStack = this.undoStack.map(fix);
    this.redoStack = this.redoStack.map(fix);
    this.saved = this.snapshot();
    this.changed();
  }

  toJson() { return clone(this.edits); }

  // ---- shots
  shotEdit(shot) {
    return (this.edits.shots || []).find((s) => s.shot === shot) || { shot };
  }
  // value undefined removes the field (the command-line setting applies again).
  setShotField(shot, field, value) {
    this.apply((edits) => editShot(edits, shot, (entry) => {
      if (value === undefined) delete entry[field]; else entry[field] = value;
    }));
  }
  setWashoutField(shot, field, value) {
    this.apply((edits) => editShot(edits, shot, (entry) => {
      const washout = entry.washout || {};
      if (value === undefined) delete washout[field]; else washout[field] = value;
      if (Object.keys(washout).length) entry.washout = washout; else delete entry.washout;
    }));
  }
  resetShot(shot) {
    this.apply((edits) => {
      edits.shots = (edits.shots || []).filter((s) => s.shot !== shot);
      if (!edits.shots.length) delete edits.shots;
    });
  }

  // ---- keyframes (semantic effect segments)
  get hasKeyframes() { return Array.isArray(this.edits.keyframes); }
  keyframes() { return this.edits.keyframes || this.automaticEffects; }
  // The first change to the segments copies the automatic ones into the edits.
  ownKeyframes(edits) {
    if (!edits.keyframes) edits.keyframes = clone(this.automaticEffects);
    return edits.keyframes;
  }
  setKeyframe(index, fields) {
    this.apply((edits) => Object.assign(this.ownKeyframes(edits)[index], fields));
  }
  moveKeyframeLive(index, start_s, end_s) {
    this.applyLive((edits) => Object.assign(this.ownKeyframes(edits)[index], { start_s, end_s }));
  }
  addKeyframe(segment) {
    let index = -1;
    this.apply((edits) => {
      const list = this.ownKeyframes(edits);
      list.push(segment);
      list.sort((a, b) => a.start_s - b.start_s);
      index = list.indexOf(segment);
    });
    return index;
  }
  deleteKeyframe(index) {
    this.apply((edits) => this.ownKeyframes(edits).splice(index, 1));
  }
  restoreAutomaticEffects() {
    this.apply((edits) => { delete edits.keyframes; });
  }
}

function editShot(edits, shot, mutate) {
  const shots = edits.shots || [];
  let entry = shots.find((s) => s.shot === shot);
  if (!entry) { entry = { shot }; shots.push(entry); }
  mutate(entry);
  edits.shots = shots.filter((s) => Object.keys(s).length > 1).sort((a, b) => a.shot - b.shot);
  if (!edits.shots.length) delete edits.shots;
}

// Room for a segment [start, end] among the others (sorted, non-overlapping):
// the gap it may occupy, excluding the segment at `skip`.
export function freeGap(list, skip, t, duration) {
  let lo = 0, hi = duration;
  list.forEach((s, i) => {
    if (i === skip) return;
    if (s.end_s <= t) lo = Math.max(lo, s.end_s);
    else if (s.start_s >= t) hi = Math.min(hi, s.start_s);
  });
  return [lo, hi];
}

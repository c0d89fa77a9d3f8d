// SPDX-License-Identifier: GPL-2.0-or-later
// Where a texture's wall time goes (synthesisStats().phases, bench:web --texture): consecutive phases, each mark
// taking the time since the one before, so that the phases add up to the wall time and a step that is not named
// shows as what it was waiting behind instead of vanishing. Keys that hold the synthesis kernel contain `kernel`.
// The phase of a run that takes the field to the GPU (interleaved-run.js), which quick-edits.js reads too.
export const FIELD_UPLOAD_PHASE = 'field to the GPU';

export class PhaseClock {
  constructor(t0 = performance.now()) {
    this.t0 = t0;
    this.last = t0;
    this.phases = {};
  }

  // The time since the previous mark (or the start) goes to `phase`; returns it.
  mark(phase) {
    const now = performance.now();
    const ms = now - this.last;
    this.phases[phase] = (this.phases[phase] ?? 0) + ms;
    this.last = now;
    return ms;
  }

  // `ms` of what was marked as `from` moved to `to` (a split found out afterwards, as a GPU timer's).
  move(from, to, ms) {
    const moved = Math.max(0, Math.min(ms, this.phases[from] ?? 0));
    if (moved <= 0) return;
    this.phases[from] -= moved;
    this.phases[to] = (this.phases[to] ?? 0) + moved;
  }

  get wallMs() {
    return this.last - this.t0;
  }

  // {phases: {name: ms}, wallMs}, rounded to 0.1 ms.
  summary() {
    const round = (x) => Math.round(10 * x) / 10;
    const phases = Object.fromEntries(Object.entries(this.phases).map(([k, v]) => [k, round(v)]));
    return { phases, wallMs: round(this.wallMs) };
  }
}

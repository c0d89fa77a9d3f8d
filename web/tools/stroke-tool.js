// Drawing strokes on the surface with the mouse (or pen/touch). Samples are {face, bary} in the core's face
// order. The ToolController (tools.js) hands this tool a press that landed on the model; the live polyline is
// drawn on the surface while dragging and becomes edge constraints on release.

const MAX_PIXEL_STEP = 1.5; // fast drags are re-sampled so consecutive samples stay close on the surface
const MIN_SAMPLE_GAP = 0.2; // × mean edge length, within one face

export class StrokeTool {
  constructor(viewer, { onStroke, onTooShort }) {
    this.viewer = viewer;
    this.onStroke = onStroke;
    this.onTooShort = onTooShort;
    this.drawing = null; // {samples, lastX, lastY}
  }

  // A press on the model starts a stroke; elsewhere it is left to orbit.
  claims(e) {
    return this.viewer.pick(e.clientX, e.clientY);
  }

  down(e, hit) {
    this.viewer.clearStroke(); // the previous stroke's line may still wait for its field
    this.drawing = { samples: [], lastX: e.clientX, lastY: e.clientY };
    this.#addSample(hit);
  }

  move(e) {
    if (!this.drawing) return;
    const events = e.getCoalescedEvents?.() ?? [];
    for (const ev of events.length ? events : [e]) this.#trace(ev.clientX, ev.clientY);
  }

  up(e) {
    if (!this.drawing) return;
    this.#trace(e.clientX, e.clientY);
    this.#finish(true, e);
  }

  cancel() {
    if (this.drawing) this.#finish(false);
  }

  // Walks the screen segment from the last pointer position in small steps so no face is skipped.
  #trace(x, y) {
    const d = this.drawing;
    const dx = x - d.lastX, dy = y - d.lastY;
    const steps = Math.max(1, Math.ceil(Math.hypot(dx, dy) / MAX_PIXEL_STEP));
    for (let s = 1; s <= steps; s++) {
      const hit = this.viewer.pick(d.lastX + (dx * s) / steps, d.lastY + (dy * s) / steps);
      if (hit) this.#addSample(hit);
    }
    d.lastX = x;
    d.lastY = y;
  }

  #addSample(hit) {
    const samples = this.drawing.samples;
    const last = samples[samples.length - 1];
    if (last) {
      const gap = Math.hypot(hit.point[0] - last.point[0], hit.point[1] - last.point[1], hit.point[2] - last.point[2]);
      if (gap === 0 || (hit.face === last.face && gap < MIN_SAMPLE_GAP * this.viewer.meanEdge)) return;
    }
    samples.push(hit);
    this.viewer.strokeAdd(hit);
  }

  #finish(commit, e) {
    const samples = this.drawing.samples;
    this.drawing = null;
    // The live polyline stays until the new field is drawn, so the stroke never blinks out in between.
    if (!commit) return this.viewer.clearStroke();
    const points = samples.map(({ face, bary }) => ({ face, bary: [...bary] }));
    if (points.length >= 2) this.onStroke(points, e);
    else {
      this.viewer.clearStroke();
      this.onTooShort?.();
    }
  }
}

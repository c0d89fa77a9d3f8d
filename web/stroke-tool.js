// Drawing strokes on the surface with the mouse (or pen/touch). Samples are {face, bary} in the core's face
// order. Pointer events are taken in the capture phase on the viewport so OrbitControls never sees a press
// that starts a stroke; a press off the model still orbits.

const MAX_PIXEL_STEP = 1.5; // fast drags are re-sampled so consecutive samples stay close on the surface
const MIN_SAMPLE_GAP = 0.2; // × mean edge length, within one face

export class StrokeTool {
  constructor(viewer, eventTarget, onStroke, onTooShort) {
    this.viewer = viewer;
    this.onStroke = onStroke;
    this.onTooShort = onTooShort;
    this.active = false;
    this.drawing = null; // {pointerId, samples, lastX, lastY}
    eventTarget.addEventListener('pointerdown', (e) => this.#down(e), { capture: true });
    eventTarget.addEventListener('pointermove', (e) => this.#move(e), { capture: true });
    eventTarget.addEventListener('pointerup', (e) => this.#up(e, true), { capture: true });
    eventTarget.addEventListener('pointercancel', (e) => this.#up(e, false), { capture: true });
  }

  setActive(active) {
    this.active = active;
    this.viewer.canvas.classList.toggle('tool-stroke', active);
    if (!active && this.drawing) this.#finish(false);
  }

  #down(e) {
    if (!this.active || this.drawing || e.button !== 0 || e.target !== this.viewer.canvas) return;
    const hit = this.viewer.pick(e.clientX, e.clientY);
    if (!hit) return;
    e.stopPropagation();
    e.preventDefault();
    this.viewer.controls.enabled = false;
    this.viewer.canvas.setPointerCapture?.(e.pointerId);
    this.drawing = { pointerId: e.pointerId, samples: [], lastX: e.clientX, lastY: e.clientY };
    this.#addSample(hit);
  }

  #move(e) {
    const d = this.drawing;
    if (!d || e.pointerId !== d.pointerId) return;
    e.stopPropagation();
    const events = e.getCoalescedEvents?.() ?? [];
    for (const ev of events.length ? events : [e]) this.#trace(ev.clientX, ev.clientY);
  }

  #up(e, commit) {
    const d = this.drawing;
    if (!d || e.pointerId !== d.pointerId) return;
    e.stopPropagation();
    if (commit) this.#trace(e.clientX, e.clientY);
    this.viewer.canvas.releasePointerCapture?.(e.pointerId);
    this.#finish(commit);
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

  #finish(commit) {
    const samples = this.drawing.samples;
    this.drawing = null;
    this.viewer.controls.enabled = true;
    this.viewer.clearStroke();
    if (!commit) return;
    const points = samples.map(({ face, bary }) => ({ face, bary: [...bary] }));
    if (points.length >= 2) this.onStroke(points);
    else this.onTooShort?.();
  }
}

// The pointer tools and the controller that routes presses to the active one. Pointer events are taken in
// the capture phase on the viewport, so OrbitControls never sees a press a tool claims; a press off the
// model (or on empty surface with the select tool) still orbits.
import { FeatureTool } from './feature-tool.js';
import { SingularityTool } from './singularity-tool.js';
import { StrokeTool } from './stroke-tool.js';

const CLICK_SLOP_PX = 6; // a press that moves less than this is a click

export const TOOLS = ['orbit', 'select', 'stroke', 'vector', 'source', 'sink', 'vortex', 'singularity', 'feature'];

export class ToolController {
  // viewer: picks and draws the gestures; target: the element that receives the pointer events.
  // actions: {onStroke(points, event), onVector(face, vector3, event), onPlace(kind, hit, event),
  // onSelect(uid | null), flash(text), singularity: SingularityTool's actions, feature: FeatureTool's};
  // readonly(): true while only orbit and select may be used.
  constructor(viewer, target, actions, readonly = () => false) {
    this.readonly = readonly;
    this.viewer = viewer;
    this.actions = actions;
    this.tool = 'orbit';
    this.active = null; // {pointerId, handler} while a tool owns a press
    this.passive = null; // a press left to orbit, watched for a click (select tool: deselect)
    this.tools = {
      stroke: new StrokeTool(viewer, {
        onStroke: actions.onStroke,
        onTooShort: () => actions.flash('Stroke too short: drag across the surface.'),
      }),
      vector: new VectorTool(viewer, actions),
      source: new PlaceTool('source', viewer, actions),
      sink: new PlaceTool('sink', viewer, actions),
      vortex: new PlaceTool('vortex', viewer, actions),
      select: new SelectTool(viewer, actions),
      singularity: new SingularityTool(viewer, actions.singularity),
      feature: new FeatureTool(viewer, actions.feature),
    };
    this.listening = new AbortController();
    const options = { capture: true, signal: this.listening.signal };
    target.addEventListener('pointerdown', (e) => this.#down(e), options);
    target.addEventListener('pointermove', (e) => this.#move(e), options);
    target.addEventListener('pointerup', (e) => this.#up(e), options);
    target.addEventListener('pointercancel', (e) => this.#cancel(e), options);
  }

  dispose() {
    this.listening.abort();
  }

  // In readonly mode only orbit and select are available.
  setTool(name) {
    if (!TOOLS.includes(name)) return;
    if (this.readonly() && name !== 'orbit' && name !== 'select') name = 'orbit';
    if (this.active) this.#release(this.active.pointerId, () => this.active.handler.cancel());
    this.tool = name;
    this.viewer.canvas.dataset.tool = name;
    this.viewer.canvas.classList.toggle('tool-stroke', name === 'stroke');
  }

  #down(e) {
    if (this.active || e.button !== 0 || e.target !== this.viewer.canvas) return;
    const handler = this.tools[this.tool];
    this.passive = { x: e.clientX, y: e.clientY, pointerId: e.pointerId };
    if (!handler) return;
    const claim = handler.claims(e);
    if (!claim) return;
    e.stopPropagation();
    e.preventDefault();
    this.passive = null;
    this.viewer.controls.enabled = false;
    this.viewer.canvas.setPointerCapture?.(e.pointerId);
    this.active = { pointerId: e.pointerId, handler, x: e.clientX, y: e.clientY };
    handler.down(e, claim);
  }

  #move(e) {
    if (!this.active || e.pointerId !== this.active.pointerId) return;
    e.stopPropagation();
    this.active.handler.move(e);
  }

  #up(e) {
    if (this.passive && e.pointerId === this.passive.pointerId) {
      const moved = Math.hypot(e.clientX - this.passive.x, e.clientY - this.passive.y);
      this.passive = null;
      if (moved < CLICK_SLOP_PX) this.tools[this.tool]?.clickedEmpty?.(e);
    }
    if (!this.active || e.pointerId !== this.active.pointerId) return;
    e.stopPropagation();
    const { handler, x, y } = this.active;
    const isClick = Math.hypot(e.clientX - x, e.clientY - y) < CLICK_SLOP_PX;
    this.#release(e.pointerId, () => handler.up(e, isClick));
  }

  #cancel(e) {
    this.passive = null;
    if (!this.active || e.pointerId !== this.active.pointerId) return;
    const { handler } = this.active;
    this.#release(e.pointerId, () => handler.cancel());
  }

  #release(pointerId, then) {
    this.active = null;
    this.viewer.controls.enabled = true;
    this.viewer.canvas.releasePointerCapture?.(pointerId);
    then();
  }
}

// Every tool but select claims presses on the model (returns the pick) and leaves the rest to orbit.
class SurfaceTool {
  claims(e) {
    return this.viewer.pick(e.clientX, e.clientY);
  }
}

// Click-drag on a triangle: the drag, projected into the face's plane, is the vector. Its magnitude is the
// drag length in units of a fifth of the model's radius, so a short drag asks for a weak field.
class VectorTool extends SurfaceTool {
  constructor(viewer, actions) {
    super();
    this.viewer = viewer;
    this.actions = actions;
    this.drag = null;
  }

  static unit(viewer) {
    return 0.2 * viewer.surface.radius;
  }

  down(e, hit) {
    this.drag = { face: hit.face, from: hit.point, normal: this.viewer.surface.normal(hit.face), to: hit.point };
  }

  move(e) {
    const d = this.drag;
    const q = this.viewer.rayOnPlane(e.clientX, e.clientY, d.from, d.normal);
    if (!q) return;
    d.to = q;
    this.viewer.handles.showPreview(d.from, q, d.normal);
    this.viewer.requestRender();
    const mag = Math.hypot(q[0] - d.from[0], q[1] - d.from[1], q[2] - d.from[2]) / VectorTool.unit(this.viewer);
    this.actions.flash(`Vector magnitude ${mag.toFixed(2)}`, 800);
  }

  up(e, isClick) {
    if (!isClick) this.move(e);
    const d = this.drag;
    this.drag = null;
    this.viewer.handles.hidePreview();
    this.viewer.requestRender();
    if (isClick) return this.actions.flash('Drag from the triangle in the direction the field should take.');
    const unit = VectorTool.unit(this.viewer);
    const v = [0, 1, 2].map((k) => (d.to[k] - d.from[k]) / unit);
    this.actions.onVector(d.face, v, e);
  }

  cancel() {
    this.drag = null;
    this.viewer.handles.hidePreview();
    this.viewer.requestRender();
  }
}

// Source, sink, vortex: a click on the model places one (the nearest vertex of the face for sources and
// sinks, the face itself for vortices). A press that turns into a drag places nothing.
class PlaceTool extends SurfaceTool {
  constructor(kind, viewer, actions) {
    super();
    this.kind = kind;
    this.viewer = viewer;
    this.actions = actions;
    this.hit = null;
  }

  down(e, hit) {
    this.hit = hit;
  }

  move() {}

  up(e, isClick) {
    const hit = this.hit;
    this.hit = null;
    if (isClick) this.actions.onPlace(this.kind, hit, e);
  }

  cancel() {
    this.hit = null;
  }
}

// Select/edit: a press on a handle selects it (and is not passed to orbit); a click on nothing deselects.
class SelectTool {
  constructor(viewer, actions) {
    this.viewer = viewer;
    this.actions = actions;
  }

  claims(e) {
    return this.viewer.handles.pickAt(this.viewer, e.clientX, e.clientY);
  }

  down(e, uid) {
    this.actions.onSelect(uid);
  }

  move() {}
  up() {}
  cancel() {}

  clickedEmpty() {
    this.actions.onSelect(null);
  }
}

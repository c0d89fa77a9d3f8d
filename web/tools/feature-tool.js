// The Feature tool: sharp feature edges added or removed with the pointer. A click takes the mesh edge of
// the face under the pointer nearest it on screen; a drag takes every edge whose middle part it passes within
// SNAP_PX of (near a vertex every edge there is close: none is taken), so a drag along a crease takes the
// crease's edges and not those of the faces beside it. The edges show as a
// preview while dragging and go to the actions as one gesture on release (one SetFeatures step). Removing:
// the tool's option, or Alt or Shift held at the press. Boundary edges belong to the boundary condition: a
// drag passes over them; a click on one is reported, for the core to refuse by name.

const MAX_PIXEL_STEP = 2; // a fast drag is sampled every this many pixels, so no edge is skipped
const SNAP_PX = 8; // a drag takes an edge this close to the pointer on screen ...
const MIDDLE = [0.2, 0.8]; // ... beside this part of it (as a fraction of its length from its first end)

export class FeatureTool {
  // actions: {onFeatures(edges, remove), removing(): the tool's option says remove}
  constructor(viewer, actions) {
    this.viewer = viewer;
    this.actions = actions;
    this.drag = null; // {edges: Map key → [a, b], remove, lastX, lastY, click: the first edge}
  }

  claims(e) {
    return this.viewer.pick(e.clientX, e.clientY);
  }

  down(e, hit) {
    const remove = e.altKey || e.shiftKey || this.actions.removing();
    this.drag = { edges: new Map(), remove, lastX: e.clientX, lastY: e.clientY, click: null };
    const near = this.#nearestEdge(hit, e.clientX, e.clientY);
    this.drag.click = near.edge;
    if (snaps(near)) this.#take(near.edge);
  }

  move(e) {
    const d = this.drag;
    if (!d) return;
    const events = e.getCoalescedEvents?.() ?? [];
    for (const ev of events.length ? events : [e]) this.#trace(ev.clientX, ev.clientY);
  }

  up(e, isClick) {
    const d = this.drag;
    if (!d) return;
    if (!isClick) this.#trace(e.clientX, e.clientY);
    this.drag = null;
    this.viewer.features.setPreview([]);
    this.viewer.requestRender();
    const edges = isClick ? [d.click] : [...d.edges.values()];
    this.actions.onFeatures(edges, d.remove);
  }

  cancel() {
    this.drag = null;
    this.viewer.features.setPreview([]);
    this.viewer.requestRender();
  }

  // Walks the screen segment from the last pointer position in small steps.
  #trace(x, y) {
    const d = this.drag;
    const dx = x - d.lastX, dy = y - d.lastY;
    const steps = Math.max(1, Math.ceil(Math.hypot(dx, dy) / MAX_PIXEL_STEP));
    for (let s = 1; s <= steps; s++) {
      const px = d.lastX + (dx * s) / steps, py = d.lastY + (dy * s) / steps;
      const hit = this.viewer.pick(px, py);
      if (!hit) continue;
      const near = this.#nearestEdge(hit, px, py);
      if (snaps(near)) this.#take(near.edge);
    }
    d.lastX = x;
    d.lastY = y;
  }

  #take([a, b]) {
    const d = this.drag, key = `${a},${b}`;
    if (d.edges.has(key)) return;
    d.edges.set(key, [a, b]);
    this.viewer.features.setPreview([...d.edges.values()], d.remove);
    this.viewer.requestRender();
  }

  // The edge of the hit face nearest the pointer on screen: {edge: [a, b] lower vertex first, px, t, boundary}.
  #nearestEdge(hit, x, y) {
    const s = this.viewer.surface, T = s.triangles, f = hit.face;
    const q = [0, 1, 2].map((k) => this.viewer.projectToScreen(s.vertex(T[3 * f + k])));
    let best = null;
    for (let k = 0; k < 3; k++) {
      const { px, t } = segmentDistance(q[k], q[(k + 1) % 3], x, y);
      if (best && px >= best.px) continue;
      const a = T[3 * f + k], b = T[3 * f + ((k + 1) % 3)];
      best = { edge: a < b ? [a, b] : [b, a], px, t, boundary: s.neighbour[3 * f + k] < 0 };
    }
    return best;
  }
}

// A drag sample takes the edge it passes beside the middle of, close on screen, unless it is a boundary edge.
const snaps = ({ px, t, boundary }) => px <= SNAP_PX && t >= MIDDLE[0] && t <= MIDDLE[1] && !boundary;

// Distance in pixels from (x, y) to the screen segment p–q, and where along it (0 at p, 1 at q) it is nearest.
function segmentDistance(p, q, x, y) {
  const ux = q.x - p.x, uy = q.y - p.y, l2 = ux * ux + uy * uy;
  const t = l2 > 0 ? Math.max(0, Math.min(1, ((x - p.x) * ux + (y - p.y) * uy) / l2)) : 0;
  return { px: Math.hypot(p.x + t * ux - x, p.y + t * uy - y), t };
}

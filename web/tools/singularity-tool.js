// The Singularity tool: prescribed singularities placed, moved and removed with the pointer. A click on the
// model places one at the nearest vertex of the face under the pointer, with the index the tool's options
// pick; a press on a prescribed marker selects it, and a drag from there moves it (ghost markers show where,
// one move on release); a drag from empty surface draws out a +/- pair: +1/N at the press, -1/N at the
// release. The selection is the session's (a prescribed singularity is a constraint of the design), so Delete
// and the constraint list treat it as any other. The tool makes no edit itself: it reports each gesture to its
// actions; the core refuses what it cannot take (a boundary vertex, a vertex that already has one) and the
// page shows why.

export class SingularityTool {
  // actions: {onAdd(vertex), onMove(id, vertex), onPair(plusVertex, minusVertex), onSelect(id | null),
  // symmetry(): the field's N}
  constructor(viewer, actions) {
    this.viewer = viewer;
    this.actions = actions;
    this.drag = null; // {marker | null, from, to}: from, to vertices
  }

  // A press on a prescribed marker (it floats over the surface) or on the model; elsewhere it orbits.
  claims(e) {
    const marker = this.viewer.singularities.prescribedAt(this.viewer, e.clientX, e.clientY);
    if (marker) return { marker };
    const hit = this.viewer.pick(e.clientX, e.clientY);
    return hit && { hit };
  }

  down(e, { marker, hit }) {
    if (marker) {
      this.actions.onSelect(marker.id);
      this.drag = { marker, from: marker.vertex, to: marker.vertex };
    } else {
      const v = this.#vertexOf(hit);
      this.drag = { marker: null, from: v, to: v };
    }
  }

  move(e) {
    const d = this.drag;
    if (!d) return;
    const hit = this.viewer.pick(e.clientX, e.clientY);
    if (hit) d.to = this.#vertexOf(hit);
    this.#preview();
  }

  up(e, isClick) {
    const d = this.drag;
    if (!d) return;
    if (!isClick) this.move(e);
    this.#endPreview();
    this.drag = null;
    if (d.marker) {
      if (!isClick && d.to !== d.from) this.actions.onMove(d.marker.id, d.to);
    } else if (isClick || d.to === d.from) {
      this.actions.onAdd(d.from);
    } else {
      this.actions.onPair(d.from, d.to);
    }
  }

  cancel() {
    this.drag = null;
    this.#endPreview();
  }

  // A click off the model: nothing selected.
  clickedEmpty() {
    this.actions.onSelect(null);
  }

  #vertexOf(hit) {
    return this.viewer.surface.nearestCorner(hit.face, hit.point);
  }

  // Ghosts where the gesture would put singularities: the moved one's new vertex, or the pair's two ends.
  #preview() {
    const d = this.drag, N = this.actions.symmetry();
    let ghosts = [];
    if (d.marker && d.to !== d.from) ghosts = [{ vertex: d.to, index: d.marker.index }];
    else if (!d.marker && d.to !== d.from) ghosts = [{ vertex: d.from, index: 1 / N }, { vertex: d.to, index: -1 / N }];
    this.viewer.singularities.setGhosts(ghosts);
    this.viewer.requestRender();
  }

  #endPreview() {
    this.viewer.singularities.setGhosts([]);
    this.viewer.requestRender();
  }
}

// Sharp features drawn as lines on the surface: the feature edges the field follows (one LineSegments), and
// while the Feature tool drags, the edges its gesture will add or remove (a second one, brighter, over it).
// Each end is lifted off the surface along its vertex normal by a fraction of the mean edge (the depth
// offset that keeps the line in front of the faces it lies on, and behind anything nearer the eye).
import { BufferAttribute, BufferGeometry, LineBasicMaterial, LineSegments } from 'three';

export const FEATURE_COLOR = 0xf472b6; // pink: no singularity ramp, handle or stroke uses it
const ADD_COLOR = 0xfde047; // a gesture's edges to add (yellow) ...
const REMOVE_COLOR = 0x64748b; // ... or to remove (slate)
const LIFT = 0.02; // × mean edge length

export class FeaturesView {
  constructor(scene) {
    this.lines = segments(FEATURE_COLOR, 2);
    this.preview = segments(ADD_COLOR, 3);
    scene.add(this.lines, this.preview);
    this.surface = null;
    this.edges = []; // [[a, b], ...] drawn now
  }

  setSurface(surface) {
    this.surface = surface;
    this.setEdges([]);
    this.setPreview([]);
  }

  // edges: [[a, b], ...] vertex pairs (the design's features in use).
  setEdges(edges) {
    this.edges = edges.map(([a, b]) => [a, b]);
    this.#fill(this.lines, this.edges);
  }

  // The edges a gesture touches so far, [[a, b], ...]; remove: drawn as edges to take away.
  setPreview(edges, remove = false) {
    this.preview.material.color.setHex(remove ? REMOVE_COLOR : ADD_COLOR);
    this.#fill(this.preview, edges);
  }

  #fill(object, edges) {
    const s = this.surface;
    object.visible = !!s && edges.length > 0;
    if (!object.visible) return;
    const lift = LIFT * s.meanEdge, n = s.vertexNormals;
    const out = new Float32Array(6 * edges.length);
    edges.forEach(([a, b], k) => {
      for (const [j, v] of [a, b].entries()) {
        const p = s.vertex(v);
        const l = Math.hypot(n[3 * v], n[3 * v + 1], n[3 * v + 2]) || 1;
        for (let c = 0; c < 3; c++) out[6 * k + 3 * j + c] = p[c] + (lift * n[3 * v + c]) / l;
      }
    });
    object.geometry.dispose();
    object.geometry = new BufferGeometry();
    object.geometry.setAttribute('position', new BufferAttribute(out, 3));
  }

  // The feature edges as drawn (vertex pairs), for the tests.
  drawn() {
    return this.lines.visible ? this.edges.map((e) => [...e]) : [];
  }

  dispose() {
    for (const o of [this.lines, this.preview]) {
      o.parent?.remove(o);
      o.geometry.dispose();
      o.material.dispose();
    }
  }
}

function segments(color, renderOrder) {
  const object = new LineSegments(new BufferGeometry(), new LineBasicMaterial({ color, depthTest: true }));
  object.renderOrder = renderOrder;
  object.visible = false;
  return object;
}

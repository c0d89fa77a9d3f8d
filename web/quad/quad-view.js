// SPDX-License-Identifier: GPL-2.0-or-later
// The quad mesh drawn over the model: its edges as one LineSegments, and its irregular vertices as points, blue
// where three edges meet, red where five do, amber for any other valence. A quad's edges are chords of the
// surface, which on a convex part runs above them: every end is lifted along the quad mesh's vertex normal by
// a fraction of the edge length (more than a chord's sag, L²/8R, wherever the quads are small against the
// curvature, as a remesh makes them), and the surface's own polygon offset does the rest where it is flat.
// A stale mesh (the design changed since) is drawn dimmer. Owns its objects; imports three.js and its own folder.
import { BufferAttribute, BufferGeometry, Color, Group, LineBasicMaterial, LineSegments, Points, PointsMaterial }
  from 'three';
import { meanEdgeLength, uniqueEdges, valences, vertexNormals } from './quad-mesh.js';

const LINE_COLOR = 0x2dd4bf; // teal: no field view, handle or marker uses it
const STALE_COLOR = 0x5b6b70;
const VALENCE_COLORS = { 3: 0x3b82f6, 5: 0xef4444 };
const OTHER_VALENCE_COLOR = 0xf59e0b;
const LINE_LIFT = 0.04; // × edge length
const POINT_LIFT = 0.08;
const POINT_SIZE = 7; // pixels

export class QuadView {
  constructor(viewer) {
    this.viewer = viewer;
    this.group = new Group();
    this.group.visible = false;
    this.lines = new LineSegments(new BufferGeometry(), new LineBasicMaterial({ color: LINE_COLOR }));
    this.lines.renderOrder = 2;
    this.points = new Points(
      new BufferGeometry(),
      new PointsMaterial({ size: POINT_SIZE, sizeAttenuation: false, vertexColors: true }),
    );
    this.points.renderOrder = 3;
    this.group.add(this.lines, this.points);
    viewer.scene.add(this.group);
    this.hasMesh = false;
    this.visible = true;
  }

  // mesh: {positions, faceStart, faceVertices, irregular}; edgeLength: the core's target (else the mean edge);
  // derived: {edges, valence, normals} of the mesh (quad-mesh.js) where the worker made them, else made here.
  // The lines are the mesh's vertices, lifted once each, joined by an index of its edges: one pass over the
  // vertices on this thread, not two ends per edge.
  setMesh(mesh, { edgeLength = 0, stale = false, derived = null } = {}) {
    const edges = derived?.edges ?? uniqueEdges(mesh);
    const valence = derived?.valence ?? valences(mesh, edges), normals = derived?.normals ?? vertexNormals(mesh);
    const length = edgeLength > 0 ? edgeLength : meanEdgeLength(mesh, edges);
    const p = mesh.positions;
    const lifted = (out, at, v, lift) => {
      for (let c = 0; c < 3; c++) out[at + c] = p[3 * v + c] + lift * normals[3 * v + c];
    };
    const vertices = new Float32Array(p.length);
    for (let v = 0; v < p.length / 3; v++) lifted(vertices, 3 * v, v, LINE_LIFT * length);
    const point = new Float32Array(3 * mesh.irregular.length), colour = new Float32Array(point.length);
    const c = new Color();
    mesh.irregular.forEach((v, k) => {
      lifted(point, 3 * k, v, POINT_LIFT * length);
      c.setHex(VALENCE_COLORS[valence[v]] ?? OTHER_VALENCE_COLOR).toArray(colour, 3 * k);
    });
    this.#geometry(this.lines, { position: vertices }, edges);
    this.#geometry(this.points, { position: point, color: colour });
    this.hasMesh = true;
    this.setStale(stale);
    this.#show();
  }

  #geometry(object, attributes, index = null) {
    object.geometry.dispose();
    object.geometry = new BufferGeometry();
    for (const [name, array] of Object.entries(attributes))
      object.geometry.setAttribute(name, new BufferAttribute(array, 3));
    if (index) object.geometry.setIndex(new BufferAttribute(index, 1));
  }

  setVisible(visible) {
    this.visible = !!visible;
    this.#show();
  }

  setStale(stale) {
    this.lines.material.color.setHex(stale ? STALE_COLOR : LINE_COLOR);
    this.viewer.requestRender();
  }

  clear() {
    this.hasMesh = false;
    this.#geometry(this.lines, { position: new Float32Array(0) });
    this.#geometry(this.points, { position: new Float32Array(0), color: new Float32Array(0) });
    this.#show();
  }

  #show() {
    this.group.visible = this.visible && this.hasMesh;
    this.viewer.requestRender();
  }

  dispose() {
    this.group.parent?.remove(this.group);
    for (const o of [this.lines, this.points]) {
      o.geometry.dispose();
      o.material.dispose();
    }
  }
}

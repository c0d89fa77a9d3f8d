// Singularity markers: a disc with the index written on it, lying in the tangent plane at the singular
// vertex. An N-field's (N ≥ 2) indices are fractions: the disc is then coloured on the ramp of
// singularity-style.js and the index, as a fraction, is a tag beside it that faces the viewer (a disc 22 px
// across has no room for "−1/4").
// Two kinds: the free singularities the field placed itself (the Singularities view, built only while it is
// shown) and the prescribed ones of the design (always shown, like the constraint handles: they are what the
// user placed), larger and ringed in cyan, the selected one in white. While the Singularity tool drags, ghost
// markers show where a move or a +/- pair will go.
import {
  CircleGeometry,
  DoubleSide,
  Group,
  Matrix4,
  Mesh,
  MeshBasicMaterial,
  Sprite,
  SpriteMaterial,
  Vector3,
} from 'three';
import { worldPerPixel } from '../geometry/arrow-sampling.js';
import { symmetryOf } from '../geometry/nfield.js';
import { TAG_ASPECT } from './markers.js';
import { indexLabel, PRESCRIBED_RING, SELECTED_RING, singularityFill } from './singularity-style.js';

// Singularity markers lie on the surface: a labelled disc in the tangent plane at the vertex, lifted by a
// hair and drawn with a negative polygon offset so it wins against the surface it lies on but against nothing
// above it. Handles float above the surface, so one at the same vertex always shows over the marker. The disc
// keeps a constant size in pixels and turns about the normal so its label reads upright.
const SINGULARITY_PX = 22;
const PRESCRIBED_PX = 30; // a prescribed marker: larger, its rim clear of a free marker's
const PICK_PX = 16; // a press this close to a prescribed marker's vertex is on the marker
const SINGULARITY_LIFT = 0.01; // × mean edge length
const TAG_PX = 20; // tag height
const TAG_GAP_PX = 14; // from the vertex to the tag's left edge: clear of the disc

export class SingularitiesView {
  constructor(scene, labels) {
    this.labels = labels;
    this.group = new Group();
    scene.add(this.group);
    this.showFree = false; // the Singularities view (free singularities); prescribed ones always show
    // Tags apart from the discs: drawn() and the disc code see discs only.
    this.tags = new Group();
    scene.add(this.tags);
    this.list = [];
    this.prescribed = []; // [{vertex, index, id}] of the design
    this.selected = null; // the id of the selected prescribed singularity
    this.ghosts = []; // [{vertex, index}] drawn while a tool drags
    this.symmetry = 1;
    this.disc = new CircleGeometry(0.5, 32);
  }

  setSurface(surface) {
    this.surface = surface;
    this.prescribed = [];
    this.prescribedKey = null;
    this.ghosts = [];
    this.selected = null;
    this.setSingularities([]);
  }

  // The Singularities view: the free singularities shown or not (the prescribed ones always are).
  setVisible(on) {
    const was = this.showFree;
    this.showFree = on;
    if (on !== was) this.#build();
  }

  // The design's prescribed singularities, [{vertex, index, id}], and the field's N.
  setPrescribed(list, symmetry = 1) {
    const key = JSON.stringify([list, symmetry]);
    if (key === this.prescribedKey) return; // after most edits: as they were
    this.prescribedKey = key;
    this.prescribed = list;
    this.symmetry = symmetryOf(symmetry);
    this.#build();
  }

  setSelected(id) {
    if (id === this.selected) return;
    this.selected = id;
    this.#build();
  }

  // Ghost markers, [{vertex, index}], over everything else (a move's or a pair's preview); [] to end.
  setGhosts(list) {
    if (!list.length && !this.ghosts.length) return;
    this.ghosts = list;
    this.#build();
  }

  // The prescribed singularity whose vertex is within PICK_PX of a client pixel and in sight, or null.
  prescribedAt(viewer, clientX, clientY) {
    let best = null, bestD = PICK_PX;
    for (const p of this.prescribed) {
      const q = viewer.projectToScreen(this.surface.vertex(p.vertex));
      const d = Math.hypot(q.x - clientX, q.y - clientY);
      if (d <= bestD && viewer.isVisible(this.surface.vertex(p.vertex))) [best, bestD] = [p, d];
    }
    return best;
  }

  // Markers are built only while shown: a hidden view costs nothing per edit.
  // list: [{vertex, index}]; symmetry: the field's N (1 when absent), which says how indices are written.
  setSingularities(list, symmetry = 1) {
    this.list = list;
    this.symmetry = symmetryOf(symmetry);
    this.#build();
  }

  #build() {
    for (const m of [...this.group.children, ...this.tags.children]) m.material.dispose();
    this.group.clear();
    this.tags.clear();
    const s = this.surface;
    if (!s) return;
    const pinned = new Set(this.prescribed.map((p) => p.vertex));
    // A field that has not settled (or is zero) can report a singularity at almost every vertex; drawing
    // thousands of markers would only hide the model.
    const free = this.showFree ? this.list.filter((x) => !x.prescribed && !pinned.has(x.vertex)).slice(0, 400) : [];
    for (const x of free) this.#marker(x, null);
    for (const p of this.prescribed) this.#marker(p, p.id === this.selected ? SELECTED_RING : PRESCRIBED_RING);
    for (const g of this.ghosts) this.#marker(g, SELECTED_RING, 0.6);
  }

  // One marker (ring: null for a free singularity, else the rim of a prescribed one or a ghost).
  #marker({ vertex, index }, ring, opacity = 1) {
    const s = this.surface, N = this.symmetry;
    const label = indexLabel(index, N);
    const fill = singularityFill(index);
    // N = 1: the index on the disc, as always; N ≥ 2: a plain disc, the index on the tag.
    const onDisc = N === 1 ? label : '';
    const material = new MeshBasicMaterial({
      map: this.labels.get(`sing:${fill}:${onDisc}:${ring}`, fill, onDisc, { ringColor: ring }),
      transparent: true,
      opacity,
      side: DoubleSide,
      polygonOffset: true,
      polygonOffsetFactor: -2,
      polygonOffsetUnits: -2,
    });
    const marker = new Mesh(this.disc, material);
    const p = s.vertex(vertex), n = s.vertexNormals;
    const normal = new Vector3(n[3 * vertex], n[3 * vertex + 1], n[3 * vertex + 2]).normalize();
    marker.position.set(p[0], p[1], p[2]).addScaledVector(normal, SINGULARITY_LIFT * s.meanEdge);
    const px = ring ? PRESCRIBED_PX : SINGULARITY_PX;
    marker.userData = { vertex, normal, prescribed: !!ring, ghost: opacity < 1, px };
    marker.renderOrder = ring ? 2 : 1;
    this.group.add(marker);
    if (N > 1) this.tags.add(this.#tag(vertex, label, fill, marker.position, ring));
  }

  // A sprite of fixed size in pixels, anchored at the vertex and drawn to its right (center.x < 0).
  #tag(vertex, label, fill, at, rim) {
    const map = this.labels.getTag(`tag:${fill}:${label}:${rim}`, fill, label, rim ?? fill);
    const tag = new Sprite(new SpriteMaterial({ map, sizeAttenuation: false, depthTest: true, transparent: true }));
    tag.center.set(-TAG_GAP_PX / (TAG_ASPECT * TAG_PX), 0.5);
    tag.userData = { vertex, at: at.clone(), label, prescribed: !!rim };
    tag.renderOrder = 3;
    return tag;
  }

  // Tags keep their size in pixels (sprite scales without attenuation are in units of the view height ×
  // tan(fov/2)). Each is pulled towards the eye along its view ray, by more than its own height: it stays where
  // it was on screen, clear of the surface curving up beside the vertex, and still hidden behind the model.
  #scaleTags(camera, h) {
    const k = (2 * Math.tan((camera.fov * Math.PI) / 360)) / h, toEye = new Vector3();
    for (const t of this.tags.children) {
      const { at } = t.userData;
      t.scale.set(TAG_ASPECT * TAG_PX * k, TAG_PX * k, 1);
      toEye.subVectors(camera.position, at).normalize();
      t.position.copy(at).addScaledVector(toEye, 1.5 * TAG_PX * worldPerPixel(camera, at, h));
    }
  }

  updateScale(camera, renderer) {
    if (!this.group.children.length) return;
    const h = renderer.domElement.clientHeight || renderer.domElement.height || 1;
    const right = new Vector3().setFromMatrixColumn(camera.matrixWorld, 0);
    const x = new Vector3(), y = new Vector3(), basis = new Matrix4();
    for (const m of this.group.children) {
      const { normal } = m.userData;
      // The screen's right, laid into the tangent plane (or any tangent when the normal faces sideways).
      x.copy(right).addScaledVector(normal, -right.dot(normal));
      if (x.lengthSq() < 1e-8) x.set(1, 0, 0).addScaledVector(normal, -normal.x);
      x.normalize();
      y.crossVectors(normal, x);
      m.quaternion.setFromRotationMatrix(basis.makeBasis(x, y, normal));
      m.scale.setScalar(m.userData.px * worldPerPixel(camera, m.position, h));
    }
    this.#scaleTags(camera, h);
  }

  // The tags as drawn (N ≥ 2): each singular vertex's label, e.g. "+1/2" (flagged when prescribed).
  drawnTags() {
    return this.tags.children.map(({ userData: u }) =>
      u.prescribed ? { vertex: u.vertex, label: u.label, prescribed: true } : { vertex: u.vertex, label: u.label },
    );
  }

  // Each marker's vertex and the corners of its disc as drawn (world coordinates), for checking it lies on
  // the surface; `prescribed` for the design's pinned ones, `ghost` for a drag's preview.
  drawn() {
    return this.group.children.map((m) => {
      m.updateMatrixWorld();
      const P = m.geometry.getAttribute('position'), v = new Vector3(), corners = [];
      for (let i = 0; i < P.count; i++)
        corners.push(...v.fromBufferAttribute(P, i).applyMatrix4(m.matrixWorld).toArray());
      const { vertex, prescribed, ghost } = m.userData;
      return { vertex, corners, prescribed, ghost };
    });
  }
}

// Singularity markers: a disc with the index written on it, lying in the tangent plane at the singular
// vertex. Built only while the view is shown. An N-field's (N ≥ 2) indices are fractions: the disc is then
// coloured on the ramp of singularity-style.js and the index, as a fraction, is a tag beside it that faces
// the viewer (a disc 22 px across has no room for "−1/4").
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
import { indexLabel, singularityFill } from './singularity-style.js';

// Singularity markers lie on the surface: a labelled disc in the tangent plane at the vertex, lifted by a
// hair and drawn with a negative polygon offset so it wins against the surface it lies on but against nothing
// above it. Handles float above the surface, so one at the same vertex always shows over the marker. The disc
// keeps a constant size in pixels and turns about the normal so its label reads upright.
const SINGULARITY_PX = 22;
const SINGULARITY_LIFT = 0.01; // × mean edge length
const TAG_PX = 20; // tag height
const TAG_GAP_PX = 14; // from the vertex to the tag's left edge: clear of the disc

export class SingularitiesView {
  constructor(scene, labels) {
    this.labels = labels;
    this.group = new Group();
    this.group.visible = false;
    scene.add(this.group);
    // Tags apart from the discs: drawn() and the disc code see discs only.
    this.tags = new Group();
    this.tags.visible = false;
    scene.add(this.tags);
    this.list = [];
    this.symmetry = 1;
    this.disc = new CircleGeometry(0.5, 32);
  }

  setSurface(surface) {
    this.surface = surface;
    this.setSingularities([]);
  }

  setVisible(on) {
    const was = this.group.visible;
    this.group.visible = this.tags.visible = on;
    if (on && !was) this.#build();
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
    const s = this.surface, list = this.list, N = this.symmetry;
    if (!s || !this.group.visible) return;
    const lift = SINGULARITY_LIFT * s.meanEdge;
    // A field that has not settled (or is zero) can report a singularity at almost every vertex; drawing
    // thousands of markers would only hide the model.
    for (const { vertex, index } of list.slice(0, 400)) {
      const label = indexLabel(index, N);
      const fill = singularityFill(index);
      // N = 1: the index on the disc, as always; N ≥ 2: a plain disc, the index on the tag.
      const onDisc = N === 1 ? label : '';
      const material = new MeshBasicMaterial({
        map: this.labels.get(`sing:${fill}:${onDisc}`, fill, onDisc),
        transparent: true,
        side: DoubleSide,
        polygonOffset: true,
        polygonOffsetFactor: -2,
        polygonOffsetUnits: -2,
      });
      const marker = new Mesh(this.disc, material);
      const p = s.vertex(vertex), n = s.vertexNormals;
      const normal = new Vector3(n[3 * vertex], n[3 * vertex + 1], n[3 * vertex + 2]).normalize();
      marker.position.set(p[0], p[1], p[2]).addScaledVector(normal, lift);
      marker.userData = { vertex, normal };
      marker.renderOrder = 1;
      this.group.add(marker);
      if (N > 1) this.tags.add(this.#tag(vertex, label, fill, marker.position));
    }
  }

  // A sprite of fixed size in pixels, anchored at the vertex and drawn to its right (center.x < 0).
  #tag(vertex, label, fill, at) {
    const map = this.labels.getTag(`tag:${fill}:${label}`, fill, label);
    const tag = new Sprite(new SpriteMaterial({ map, sizeAttenuation: false, depthTest: true, transparent: true }));
    tag.center.set(-TAG_GAP_PX / (TAG_ASPECT * TAG_PX), 0.5);
    tag.userData = { vertex, at: at.clone(), label };
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
    if (!this.group.visible || !this.group.children.length) return;
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
      m.scale.setScalar(SINGULARITY_PX * worldPerPixel(camera, m.position, h));
    }
    this.#scaleTags(camera, h);
  }

  // The tags as drawn (N ≥ 2): each singular vertex's label, e.g. "+1/2".
  drawnTags() {
    return this.tags.children.map((t) => ({ vertex: t.userData.vertex, label: t.userData.label }));
  }

  // Each marker's vertex and the corners of its disc as drawn (world coordinates), for checking it lies on
  // the surface.
  drawn() {
    return this.group.children.map((m) => {
      m.updateMatrixWorld();
      const P = m.geometry.getAttribute('position'), v = new Vector3(), corners = [];
      for (let i = 0; i < P.count; i++)
        corners.push(...v.fromBufferAttribute(P, i).applyMatrix4(m.matrixWorld).toArray());
      return { vertex: m.userData.vertex, corners };
    });
  }
}

// Singularity markers: a disc with the index written on it, lying in the tangent plane at the singular
// vertex. Built only while the view is shown.
import { CircleGeometry, DoubleSide, Group, Matrix4, Mesh, MeshBasicMaterial, Vector3 } from 'three';
import { worldPerPixel } from '../geometry/arrow-sampling.js';

function indexLabel(index) {
  const r = Math.round(index);
  return r > 0 ? `+${r}` : r < 0 ? `\u2212${-r}` : '0';
}

// Singularity markers lie on the surface: a labelled disc in the tangent plane at the vertex, lifted by a
// hair and drawn with a negative polygon offset so it wins against the surface it lies on but against nothing
// above it. Handles float above the surface, so one at the same vertex always shows over the marker. The disc
// keeps a constant size in pixels and turns about the normal so its label reads upright.
const SINGULARITY_PX = 22;
const SINGULARITY_LIFT = 0.01; // × mean edge length

export class SingularitiesView {
  constructor(scene, labels) {
    this.labels = labels;
    this.group = new Group();
    this.group.visible = false;
    scene.add(this.group);
    this.list = [];
    this.disc = new CircleGeometry(0.5, 32);
  }

  setSurface(surface) {
    this.surface = surface;
    this.setSingularities([]);
  }

  setVisible(on) {
    const was = this.group.visible;
    this.group.visible = on;
    if (on && !was) this.#build();
  }

  // Markers are built only while shown: a hidden view costs nothing per edit.
  setSingularities(list) {
    this.list = list;
    this.#build();
  }

  #build() {
    for (const m of this.group.children) m.material.dispose();
    this.group.clear();
    const s = this.surface, list = this.list;
    if (!s || !this.group.visible) return;
    const lift = SINGULARITY_LIFT * s.meanEdge;
    // A field that has not settled (or is zero) can report a singularity at almost every vertex; drawing
    // thousands of markers would only hide the model.
    for (const { vertex, index } of list.slice(0, 400)) {
      const label = indexLabel(index);
      const fill = index > 0 ? '#facc15' : '#c084fc';
      const material = new MeshBasicMaterial({
        map: this.labels.get(`sing:${label}`, fill, label),
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
  }

  // Each marker's vertex and the corners of its disc as drawn (world coordinates), for checking it lies on
  // the surface.
  drawn() {
    return this.group.children.map((m) => {
      m.updateMatrixWorld();
      const P = m.geometry.getAttribute('position'), v = new Vector3(), corners = [];
      for (let i = 0; i < P.count; i++) corners.push(...v.fromBufferAttribute(P, i).applyMatrix4(m.matrixWorld).toArray());
      return { vertex: m.userData.vertex, corners };
    });
  }
}

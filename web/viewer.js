// three.js view of the core's welded mesh and its per-face field. Face i of the rendered geometry is face i
// of the core, so picks translate to core surface points without any remapping.
import {
  AmbientLight,
  BufferAttribute,
  BufferGeometry,
  Color,
  DirectionalLight,
  DoubleSide,
  DynamicDrawUsage,
  HemisphereLight,
  InstancedMesh,
  Line,
  LineBasicMaterial,
  Matrix4,
  Mesh,
  MeshBasicMaterial,
  MeshStandardMaterial,
  PerspectiveCamera,
  Raycaster,
  Scene,
  SRGBColorSpace,
  Vector2,
  Vector3,
  WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { MeshBVH, acceleratedRaycast } from 'three-mesh-bvh';

const BACKGROUND = 0x1b1d21;
const ARROW_LENGTH = 0.6; // × mean edge length
const ARROW_LIFT = 0.02; // × mean edge length, keeps arrows above the surface they lie on
const STROKE_LIFT = 0.15;

// A flat arrow in the xy-plane, unit length along +x, centred on the origin so it sits on the barycentre.
function arrowGeometry() {
  const shaftW = 0.05, headW = 0.2, headL = 0.38;
  const x0 = -0.5, xh = 0.5 - headL, x1 = 0.5;
  // prettier-ignore
  const p = new Float32Array([
    x0, -shaftW, 0,  xh, -shaftW, 0,  xh, shaftW, 0,
    x0, -shaftW, 0,  xh, shaftW, 0,   x0, shaftW, 0,
    xh, -headW, 0,   x1, 0, 0,        xh, headW, 0,
  ]);
  const g = new BufferGeometry();
  g.setAttribute('position', new BufferAttribute(p, 3));
  return g;
}

// Magnitude colour ramp (blue → cyan → yellow → red): readable on the grey surface at both ends.
const RAMP = [0x2563eb, 0x06b6d4, 0xfacc15, 0xef4444].map((c) => new Color(c));
function rampColor(t, out) {
  const s = Math.min(Math.max(t, 0), 1) * (RAMP.length - 1);
  const i = Math.min(Math.floor(s), RAMP.length - 2);
  return out.copy(RAMP[i]).lerp(RAMP[i + 1], s - i);
}

export class Viewer {
  constructor(container) {
    this.container = container;
    this.renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.outputColorSpace = SRGBColorSpace;
    this.renderer.setClearColor(BACKGROUND, 1);
    this.canvas = this.renderer.domElement;
    this.canvas.id = 'view';
    this.canvas.tabIndex = 0;
    container.prepend(this.canvas);

    this.scene = new Scene();
    this.camera = new PerspectiveCamera(40, 1, 0.01, 100);
    this.camera.position.set(0, 0, 3);
    this.scene.add(this.camera);
    this.scene.add(new HemisphereLight(0xdde4ff, 0x2a2d33, 0.9));
    this.scene.add(new AmbientLight(0xffffff, 0.15));
    // A headlight: the side the user looks at is always lit, whichever way they orbit.
    const head = new DirectionalLight(0xffffff, 2.2);
    head.position.set(0.4, 0.6, 1);
    this.camera.add(head);

    this.controls = new OrbitControls(this.camera, this.canvas);
    this.controls.enableDamping = false; // render on demand; damping would need a running loop
    this.controls.addEventListener('change', () => this.requestRender());

    this.raycaster = new Raycaster();
    this.raycaster.firstHitOnly = true;

    this.surface = null;
    this.arrows = null;
    this.arrowsVisible = true;
    this.strokeLine = null;
    this.meanEdge = 1;
    this.fieldMax = 0;

    this._renderQueued = false;
    new ResizeObserver(() => this.resize()).observe(container);
    this.resize();
  }

  resize() {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    this.renderNow();
  }

  requestRender() {
    if (this._renderQueued) return;
    this._renderQueued = true;
    requestAnimationFrame(() => {
      this._renderQueued = false;
      this.renderNow();
    });
  }

  renderNow() {
    this.renderer.render(this.scene, this.camera);
  }

  // positions: Float64Array (3 per vertex), triangles: Int32Array (3 per face), both from the core.
  setMesh(positions, triangles) {
    this.clearStroke();
    this.#disposeMesh();
    this.positions = positions;
    this.triangles = triangles;
    const nF = triangles.length / 3;

    const geom = new BufferGeometry();
    geom.setAttribute('position', new BufferAttribute(Float32Array.from(positions), 3));
    geom.setIndex(new BufferAttribute(Uint32Array.from(triangles), 1));
    geom.computeVertexNormals();
    geom.computeBoundingSphere();
    // indirect: the default build reorders the index buffer, and then hit.faceIndex no longer names the
    // core's face. Indirect mode leaves the triangles in place and reports original indices.
    geom.boundsTree = new MeshBVH(geom, { indirect: true });

    const material = new MeshStandardMaterial({
      color: 0xb9bec8,
      roughness: 0.65,
      metalness: 0.0,
      side: DoubleSide, // open scans: the inside shows through holes
      polygonOffset: true, // arrows and strokes lie in the face planes
      polygonOffsetFactor: 1,
      polygonOffsetUnits: 1,
    });
    this.surface = new Mesh(geom, material);
    this.surface.raycast = acceleratedRaycast;
    this.scene.add(this.surface);

    // Per-face frames the arrows need: barycentre and unit normal, in double precision.
    this.faceCentres = new Float64Array(3 * nF);
    this.faceNormals = new Float64Array(3 * nF);
    let edgeSum = 0;
    const P = positions;
    for (let f = 0; f < nF; f++) {
      const a = 3 * triangles[3 * f], b = 3 * triangles[3 * f + 1], c = 3 * triangles[3 * f + 2];
      const ux = P[b] - P[a], uy = P[b + 1] - P[a + 1], uz = P[b + 2] - P[a + 2];
      const vx = P[c] - P[a], vy = P[c + 1] - P[a + 1], vz = P[c + 2] - P[a + 2];
      const wx = P[c] - P[b], wy = P[c + 1] - P[b + 1], wz = P[c + 2] - P[b + 2];
      edgeSum += Math.hypot(ux, uy, uz) + Math.hypot(vx, vy, vz) + Math.hypot(wx, wy, wz);
      let nx = uy * vz - uz * vy, ny = uz * vx - ux * vz, nz = ux * vy - uy * vx;
      const nl = Math.hypot(nx, ny, nz) || 1;
      nx /= nl; ny /= nl; nz /= nl;
      this.faceNormals.set([nx, ny, nz], 3 * f);
      this.faceCentres.set(
        [(P[a] + P[b] + P[c]) / 3, (P[a + 1] + P[b + 1] + P[c + 1]) / 3, (P[a + 2] + P[b + 2] + P[c + 2]) / 3],
        3 * f,
      );
    }
    // Each interior edge is counted twice; the mean is still the mean over face sides, which is what sizes arrows.
    this.meanEdge = nF ? edgeSum / (3 * nF) : 1;

    this.arrows = new InstancedMesh(
      arrowGeometry(),
      new MeshBasicMaterial({ color: 0xffffff, side: DoubleSide }),
      Math.max(nF, 1),
    );
    this.arrows.instanceMatrix.setUsage(DynamicDrawUsage);
    this.arrows.frustumCulled = false;
    this.arrows.visible = false;
    this.scene.add(this.arrows);

    this.frame();
    this.renderNow();
  }

  #disposeMesh() {
    for (const obj of [this.surface, this.arrows]) {
      if (!obj) continue;
      this.scene.remove(obj);
      obj.geometry.dispose();
      obj.material.dispose();
      if (obj.isInstancedMesh) obj.dispose();
    }
    this.surface = this.arrows = null;
  }

  // Puts the whole model in view from a fixed, slightly raised front-right direction.
  frame() {
    const s = this.surface.geometry.boundingSphere;
    const r = Math.max(s.radius, 1e-9);
    const dist = (r / Math.sin((this.camera.fov * Math.PI) / 360)) * 1.05;
    const dir = new Vector3(0.35, 0.25, 1).normalize();
    this.camera.position.copy(s.center).addScaledVector(dir, dist);
    this.camera.near = dist / 100;
    this.camera.far = dist * 10;
    this.camera.up.set(0, 1, 0);
    this.camera.updateProjectionMatrix();
    this.controls.target.copy(s.center);
    this.controls.update();
  }

  // vectors: Float64Array, 3 per face. Arrows share one length; colour carries the magnitude.
  setField(vectors) {
    if (!this.arrows) return;
    const nF = this.triangles.length / 3;
    const N = this.faceNormals, C = this.faceCentres;
    const mags = new Float64Array(nF);
    let max = 0;
    for (let f = 0; f < nF; f++) {
      const m = Math.hypot(vectors[3 * f], vectors[3 * f + 1], vectors[3 * f + 2]);
      mags[f] = Number.isFinite(m) ? m : 0;
      if (mags[f] > max) max = mags[f];
    }
    this.fieldMax = max;
    const len = ARROW_LENGTH * this.meanEdge;
    const lift = ARROW_LIFT * this.meanEdge;
    const m4 = new Matrix4();
    const zero = new Matrix4().makeScale(0, 0, 0);
    const x = new Vector3(), y = new Vector3(), z = new Vector3(), color = new Color();
    // Faces whose vector is negligible next to the largest get no arrow rather than a noisy direction.
    const floor = max * 1e-6;
    for (let f = 0; f < nF; f++) {
      z.set(N[3 * f], N[3 * f + 1], N[3 * f + 2]);
      x.set(vectors[3 * f], vectors[3 * f + 1], vectors[3 * f + 2]);
      x.addScaledVector(z, -x.dot(z)); // in the face plane, whatever rounding the core left
      if (!(mags[f] > floor) || x.lengthSq() === 0) {
        this.arrows.setMatrixAt(f, zero);
        this.arrows.setColorAt(f, color.setRGB(0, 0, 0));
        continue;
      }
      x.normalize();
      y.crossVectors(z, x);
      m4.makeBasis(x.multiplyScalar(len), y.multiplyScalar(len), z);
      m4.setPosition(C[3 * f] + lift * z.x, C[3 * f + 1] + lift * z.y, C[3 * f + 2] + lift * z.z);
      this.arrows.setMatrixAt(f, m4);
      this.arrows.setColorAt(f, rampColor(max > 0 ? mags[f] / max : 0, color));
    }
    this.arrows.instanceMatrix.needsUpdate = true;
    if (this.arrows.instanceColor) this.arrows.instanceColor.needsUpdate = true;
    this.arrows.visible = this.arrowsVisible && max > 0;
    this.renderNow();
  }

  setArrowsVisible(visible) {
    this.arrowsVisible = visible;
    if (this.arrows) this.arrows.visible = visible && this.fieldMax > 0;
    this.renderNow();
  }

  // Client pixel coordinates → {face, bary, point} on the surface, or null.
  pick(clientX, clientY) {
    if (!this.surface) return null;
    const rect = this.canvas.getBoundingClientRect();
    const ndc = new Vector2(
      ((clientX - rect.left) / rect.width) * 2 - 1,
      -((clientY - rect.top) / rect.height) * 2 + 1,
    );
    this.raycaster.setFromCamera(ndc, this.camera);
    const hit = this.raycaster.intersectObject(this.surface, false)[0];
    if (!hit || hit.faceIndex == null) return null;
    const face = hit.faceIndex;
    const point = [hit.point.x, hit.point.y, hit.point.z];
    return { face, bary: this.barycentric(face, point), point };
  }

  // Barycentric coordinates of a point (projected) in face f, from the core's double-precision positions;
  // three-mesh-bvh hits carry no barycentrics.
  barycentric(f, [px, py, pz]) {
    const P = this.positions, T = this.triangles;
    const a = 3 * T[3 * f], b = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
    const e0 = [P[b] - P[a], P[b + 1] - P[a + 1], P[b + 2] - P[a + 2]];
    const e1 = [P[c] - P[a], P[c + 1] - P[a + 1], P[c + 2] - P[a + 2]];
    const q = [px - P[a], py - P[a + 1], pz - P[a + 2]];
    const dot = (u, v) => u[0] * v[0] + u[1] * v[1] + u[2] * v[2];
    const d00 = dot(e0, e0), d01 = dot(e0, e1), d11 = dot(e1, e1);
    const d20 = dot(q, e0), d21 = dot(q, e1);
    const den = d00 * d11 - d01 * d01;
    let v = den ? (d11 * d20 - d01 * d21) / den : 1 / 3;
    let w = den ? (d00 * d21 - d01 * d20) / den : 1 / 3;
    let u = 1 - v - w;
    // A hit on an edge can land a hair outside in float32; the core wants a point in the face.
    u = Math.max(u, 0); v = Math.max(v, 0); w = Math.max(w, 0);
    const s = u + v + w || 1;
    return [u / s, v / s, w / s];
  }

  pointFromBary(f, [u, v, w]) {
    const P = this.positions, T = this.triangles;
    const a = 3 * T[3 * f], b = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
    return [0, 1, 2].map((k) => u * P[a + k] + v * P[b + k] + w * P[c + k]);
  }

  projectToScreen([x, y, z]) {
    const v = new Vector3(x, y, z).project(this.camera);
    const rect = this.canvas.getBoundingClientRect();
    return { x: rect.left + ((v.x + 1) / 2) * rect.width, y: rect.top + ((1 - v.y) / 2) * rect.height };
  }

  // The live stroke: a polyline lifted off the surface along each sample's face normal.
  strokeAdd(sample) {
    if (!this.strokeLine) {
      const g = new BufferGeometry();
      g.setAttribute('position', new BufferAttribute(new Float32Array(3 * 256), 3));
      g.setDrawRange(0, 0);
      this.strokeLine = new Line(g, new LineBasicMaterial({ color: 0xff7a1a, depthTest: true }));
      this.strokeLine.frustumCulled = false;
      this.strokeLine.renderOrder = 2;
      this.scene.add(this.strokeLine);
    }
    const g = this.strokeLine.geometry;
    let attr = g.getAttribute('position');
    const n = g.drawRange.count;
    if (n + 1 > attr.count) {
      const grown = new Float32Array(attr.array.length * 2);
      grown.set(attr.array);
      attr = new BufferAttribute(grown, 3);
      g.setAttribute('position', attr);
    }
    const lift = STROKE_LIFT * this.meanEdge;
    const N = this.faceNormals, f = sample.face;
    const p = this.pointFromBary(f, sample.bary);
    attr.setXYZ(n, p[0] + lift * N[3 * f], p[1] + lift * N[3 * f + 1], p[2] + lift * N[3 * f + 2]);
    attr.needsUpdate = true;
    g.setDrawRange(0, n + 1);
    this.requestRender();
  }

  clearStroke() {
    if (!this.strokeLine) return;
    this.scene.remove(this.strokeLine);
    this.strokeLine.geometry.dispose();
    this.strokeLine.material.dispose();
    this.strokeLine = null;
    this.requestRender();
  }
}

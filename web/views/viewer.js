// three.js view of the core's welded mesh. Face i of the rendered geometry is face i of the core, so picks
// translate to core surface points without any remapping. The field views live in arrows-view.js,
// streamlines-view.js and singularities-view.js, the constraint handles in handles.js, the feature lines in
// features-view.js; this module owns the scene, the camera, picking and the surface itself (its geometry made by
// surface-geometry.js). Normals come from the Surface (geometry/surface.js), computed once per mesh.
import {
  AmbientLight,
  Color,
  DirectionalLight,
  DoubleSide,
  HemisphereLight,
  Mesh,
  MeshStandardMaterial,
  PerspectiveCamera,
  Plane,
  Raycaster,
  Scene,
  SRGBColorSpace,
  Vector2,
  Vector3,
  WebGLRenderer,
} from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { acceleratedRaycast } from 'three-mesh-bvh';
import { adoptBVH } from '../geometry/mesh-bvh-transfer.js';
import { ArrowsView } from './arrows-view.js';
import { MeshStaging } from './mesh-staging.js';
import { frameModel, framingDistance, refitToAspect } from './camera.js';
import { FeaturesView } from './features-view.js';
import { worldPerPixelAt } from '../geometry/arrow-sampling.js';
import { viridis } from './colormap.js';
import { magnitudeScale } from '../geometry/magnitudes.js';
import { HandlesView, RIBBON_PX } from './handles.js';
import { LicView } from './lic.js';
import { LabelTextures } from './markers.js';
import { BandMaterial, GrowingBand } from './screen-ribbon.js';
import { SingularitiesView } from './singularities-view.js';
import { StreamlinesView } from './streamlines-view.js';
import { meshGeometry } from './surface-geometry.js';
import { SurfaceLayer } from './surface-layer.js';
import { warmUpShaders } from './shader-warm-up.js';

const BACKGROUND = 0x1b1d21;
const SURFACE_GREY = 0xb9bec8;
const STROKE_LIFT = 0.15; // × mean edge length

export class Viewer {
  constructor(container) {
    this.container = container;
    this.renderer = new WebGLRenderer({ antialias: true, preserveDrawingBuffer: true, alpha: true });
    // three.js rebuilds its GL state when a lost context comes back, but draws nothing until asked: without
    // this the canvas stays blank until the next interaction.
    this.renderer.domElement.addEventListener('webglcontextrestored', () => {
      this._renderQueued = false;
      this.surfaceLayer.invalidate();
      this.requestRender();
    });
    // Checking a new program's compile log is a synchronous round trip to the GPU process, which waits for every
    // frame still in flight: with software GL and a million triangles the first stroke's new program held the
    // page's thread for 2.3 s. The shaders are the project's own and covered by the picture tests.
    this.renderer.debug.checkShaderErrors = false;
    // The same round trip, asked once and kept by three.js, for the first texture with anisotropic filtering
    // (the synthesized texture's exemplar): 94 ms of an armadillo-sub2 texture update's task, asked here while
    // the GPU process has no frame to finish.
    this.renderer.capabilities.getMaxAnisotropy();
    this.renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
    this.renderer.outputColorSpace = SRGBColorSpace;
    this.renderer.setClearColor(BACKGROUND, 1);
    this.canvas = this.renderer.domElement;
    this.canvas.id = 'view';
    this.canvas.setAttribute('part', 'canvas');
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

    this.surface = null; // Surface (geometry/topology), set by setMesh
    this.surfaceMesh = null; // the three.js mesh
    this.surfaceStandIn = null; // a mesh shown in the surface's place when visible (the synthesized texture's)
    this.strokeBand = null; // the live stroke (GrowingBand) while it is drawn
    this.colorMapOn = false;
    this.arrows = new ArrowsView(this.scene);
    this.streamlines = new StreamlinesView(this.scene);
    this.labels = new LabelTextures();
    this.singularities = new SingularitiesView(this.scene, this.labels);
    this.handles = new HandlesView(this.scene, this.labels);
    this.features = new FeaturesView(this.scene); // sharp feature edges, as lines on the surface
    this.lic = new LicView();
    this.surfaceLayer = new SurfaceLayer(); // a big surface drawn once per view (surface-layer.js)
    this.afterRender = []; // callbacks (time) → void, run once after the next render
    this.staging = new MeshStaging(this.renderer, this.camera);
    this.renderCount = 0; // frames drawn, for measuring responsiveness while the worker is busy
    this._renderQueued = false;
    this.disposed = false;
    this.surfaceLayer.warmUp(this.renderer);
    this.staging.warmUp();
    warmUpShaders(this.renderer, this.scene, this.camera, this.labels).catch(() => {});
    this.resizeObserver = new ResizeObserver(() => this.resize());
    this.resizeObserver.observe(container);
    this.resize();
  }

  // Frees the GPU side now rather than at garbage collection: browsers cap live WebGL contexts per page
  // (about 16 in Chromium), so an element that leaves the page must give its context back at once.
  dispose() {
    if (this.disposed) return;
    this.disposed = true;
    this.resizeObserver.disconnect();
    this.controls.dispose();
    this.clearStroke();
    this.#disposeMesh();
    this.staging.dispose();
    this.scene.traverse((o) => {
      o.geometry?.dispose();
      for (const m of [o.material].flat()) m?.dispose();
    });
    this.labels.dispose();
    this.lic.dispose();
    this.surfaceLayer.dispose();
    this.renderer.dispose();
    this.renderer.forceContextLoss();
    this.canvas.remove();
  }
  get meanEdge() {
    return this.surface?.meanEdge ?? 1;
  }

  resize() {
    const w = Math.max(1, this.container.clientWidth);
    const h = Math.max(1, this.container.clientHeight);
    this.renderer.setSize(w, h, false);
    const oldAspect = this.camera.aspect;
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    // A rotated phone or a closed drawer changes the aspect: keep the model's fit to the narrower field of view.
    if (oldAspect !== this.camera.aspect) refitToAspect(this, oldAspect);
    this.renderNow();
  }

  // At the next animation frame, unless renderNow() drew since the last request (a stripe pattern asks, then
  // draws at once): with software GL a frame drawn again costs the GPU process 45-60 ms on bunny00.
  requestRender() {
    if (this.disposed) return;
    this._renderOwed = true;
    if (this._renderQueued) return;
    this._renderQueued = true;
    requestAnimationFrame(() => {
      this._renderQueued = false;
      if (this._renderOwed) this.renderNow();
    });
  }

  // A frame owed for a change that another will follow soon (a stroke's field, then its texture): drawn once
  // drawDeferred() is called, when any frame is drawn meanwhile, or after `ms` at the latest. With software GL a
  // frame of a textured model costs the GPU process 45-60 ms, which the texture's own work then waited for.
  deferFrame(ms) {
    clearTimeout(this.deferTimer);
    this.deferTimer = setTimeout(() => this.drawDeferred(), ms);
  }

  // The frame deferFrame() held back, if it is still owed, at the next animation frame.
  drawDeferred() {
    if (!this.deferTimer) return; // none owed (a timer's id is never 0)
    clearTimeout(this.deferTimer);
    this.deferTimer = null;
    this.requestRender();
  }

  renderNow() {
    if (this.disposed) return;
    this._renderOwed = false;
    clearTimeout(this.deferTimer);
    this.deferTimer = null;
    this.frameLog?.push(performance.now()); // the page tests' record of frames (element/api.js)
    this.arrows.updateView(this.camera, this.controls.target, this.canvas.clientHeight || this.canvas.height);
    this.singularities.updateScale(this.camera, this.renderer);
    this.handles.updateScale(this.camera, this.renderer);
    const surface = this.surfaceStandIn?.visible ? this.surfaceStandIn : this.surfaceMesh;
    this.surfaceLayer.render(this.renderer, this.scene, this.camera, surface, this.lic.visible);
    this.lic.render(this.renderer, this.camera);
    this.renderCount++;
    if (this.afterRender.length) {
      const done = this.afterRender.splice(0);
      const t = performance.now();
      for (const fn of done) fn(t);
    }
  }

  // Resolves (with the time) at the animation frame after the next render, whether that is a queued one or
  // a synchronous renderNow() that comes first: no extra render just to measure.
  nextRenderShown() {
    return new Promise((resolve) => {
      this.afterRender.push(() => requestAnimationFrame(() => resolve(performance.now())));
    });
  }

  // surface: a Surface (surface.js) built from the core's mesh. When the worker sent them
  // (geometry/mesh-bvh-transfer.js), surface.bvh (a SerializedMeshBVH) and surface.float32 ({positions, normals,
  // index, colors}) are drawn from as they are and the bounds tree is adopted, not built: on a scanned mesh the
  // build and the Float64→Float32 copies held the page's thread for seconds (issue 28). Without them (small
  // meshes, tests) all of it is done here.
  setMesh(surface) {
    this.clearStroke();
    this.#disposeMesh();
    this.surface = surface;
    const geom = this.staging.take(surface) ?? meshGeometry(surface);
    const material = new MeshStandardMaterial({
      color: SURFACE_GREY,
      roughness: 0.65,
      metalness: 0.0,
      side: DoubleSide, // open scans: the inside shows through holes
      polygonOffset: true, // arrows, lines and handles lie in the face planes
      polygonOffsetFactor: 1,
      polygonOffsetUnits: 1,
    });
    this.surfaceMesh = new Mesh(geom, material);
    this.surfaceMesh.raycast = acceleratedRaycast;
    this.scene.add(this.surfaceMesh);
    this.#applyColorMapMaterial();
    for (const view of [this.arrows, this.streamlines, this.singularities, this.handles, this.features])
      view.setSurface(surface);
    this.streamlines.normalAt = (x, y, z) => this.#normalNear(x, y, z);
    this.lic.setSurface(geom, surface.meanEdge, surface);
    this.frame();
    // At the next frame, not now: a model's adoption draws its field in the same task (session 'model', then
    // 'change'), and a first frame of the bare mesh made the second one wait for it (software GL: ~0.4 s at
    // 832k faces, inside the adoption's task).
    this.requestRender();
  }

  // A big model's mesh, ahead of its field (session 'surface'): its buffers go to the GPU in tasks of their own
  // (mesh-staging.js), and setMesh of the same surface draws them; the arrows' samples for its framed view are
  // made ahead, a slice per task (arrows-view.js prepare). Resolves with the number of uploads when all is done.
  stageMesh(surface) {
    const staged = this.staging.stage(surface, () => meshGeometry(surface));
    return staged.then(async (uploads) => {
      const radius = surface.float32?.boundingSphere?.[3];
      if (this.staging.staged?.surface === surface && radius > 0) {
        const height = this.canvas.clientHeight || this.canvas.height;
        const wpp = worldPerPixelAt(this.camera, framingDistance(this.camera, radius), height);
        await this.arrows.prepare(surface, wpp, () => new Promise((resolve) => setTimeout(resolve, 0)));
      }
      return uploads;
    });
  }

  #disposeMesh() {
    if (!this.surfaceMesh) return;
    this.scene.remove(this.surfaceMesh);
    this.surfaceMesh.geometry.boundsTree = null;
    this.surfaceMesh.geometry.dispose();
    this.surfaceMesh.material.dispose();
    this.surfaceMesh = null;
  }

  // The normal of the face closest to a point (for direction cues drawn in the surface).
  #normalNear(x, y, z) {
    const hit = this.#boundsTree()?.closestPointToPoint(new Vector3(x, y, z));
    return hit ? this.surface.normal(hit.faceIndex) : [0, 0, 1];
  }

  // The surface's bounds tree; a big model's is adopted here once it has come (Surface.adoptPicking), and
  // until then there is none: no pick hits (a ray cast through 832k triangles one by one would hold the page).
  #boundsTree() {
    const geom = this.surfaceMesh?.geometry;
    if (geom && !geom.boundsTree && this.surface?.bvh && !this.surface.pickingFollows) adoptBVH(geom, this.surface.bvh);
    return geom?.boundsTree ?? null;
  }

  // Puts the whole model in view (camera.js): on load, Frame/Home/F, and the view presets.
  frame(preset = 'home') {
    return frameModel(this, preset);
  }

  // Magnitude colour map from per-vertex vectors. The ramp tops out at the 98th percentile, not the maximum:
  // sources and vortices make a few huge values that would leave the rest of the model one colour.
  // Returns the magnitude at the top of the ramp (for the legend).
  // scale (optional): magnitudeScale(vertexVectors), when the caller has it already.
  // symmetry, faceVectors (optional): an N-field's N and face representatives, for the flow texture (its
  // corners are matched to the faces'); the colours need neither (|v| is the same for every representative).
  setVertexField(vertexVectors, scale = magnitudeScale(vertexVectors), { symmetry = 1, faceVectors = null } = {}) {
    if (!this.surfaceMesh) return 0;
    const attr = this.surfaceMesh.geometry.getAttribute('color');
    const n = vertexVectors.length / 3;
    const { top } = scale;
    const c = new Color();
    for (let v = 0; v < n; v++) {
      const m = Math.hypot(vertexVectors[3 * v], vertexVectors[3 * v + 1], vertexVectors[3 * v + 2]);
      viridis(top > 0 && Number.isFinite(m) ? m / top : 0, c);
      attr.setXYZ(v, c.r, c.g, c.b);
    }
    attr.needsUpdate = true;
    this.lic.setField(vertexVectors, { symmetry, faceVectors });
    this.vertexFieldMax = top;
    return top;
  }

  setColorMap(on) {
    this.colorMapOn = on;
    this.#applyColorMapMaterial();
    this.arrows.setNeutral(on); // ramp-coloured arrows would vanish on a ramp-coloured surface
    this.requestRender();
  }

  #applyColorMapMaterial() {
    const m = this.surfaceMesh?.material;
    if (!m) return;
    m.vertexColors = this.colorMapOn;
    m.color.set(this.colorMapOn ? 0xffffff : SURFACE_GREY);
    m.needsUpdate = true;
  }

  // Client pixel coordinates → {face, bary, point} on the surface, or null.
  pick(clientX, clientY) {
    if (!this.#boundsTree()) return null;
    this.raycaster.setFromCamera(this.#ndc(clientX, clientY), this.camera);
    const hit = this.raycaster.intersectObject(this.surfaceMesh, false)[0];
    if (!hit || hit.faceIndex == null) return null;
    const face = hit.faceIndex;
    const point = [hit.point.x, hit.point.y, hit.point.z];
    return { face, bary: this.barycentric(face, point), point };
  }

  // Where the view ray through a client pixel meets the plane through `point` with normal `normal`, or null.
  rayOnPlane(clientX, clientY, point, normal) {
    this.raycaster.setFromCamera(this.#ndc(clientX, clientY), this.camera);
    const plane = new Plane().setFromNormalAndCoplanarPoint(new Vector3(...normal), new Vector3(...point));
    const out = new Vector3();
    return this.raycaster.ray.intersectPlane(plane, out) ? [out.x, out.y, out.z] : null;
  }

  #ndc(clientX, clientY) {
    const rect = this.canvas.getBoundingClientRect();
    return new Vector2(((clientX - rect.left) / rect.width) * 2 - 1, -((clientY - rect.top) / rect.height) * 2 + 1);
  }

  // Barycentric coordinates of a point (projected) in face f, from the core's double-precision positions;
  // three-mesh-bvh hits carry no barycentrics.
  barycentric(f, point) {
    return this.surface.baryOf(f, point);
  }

  pointFromBary(f, bary) {
    return this.surface.pointFromBary(f, bary);
  }

  projectToScreen([x, y, z]) {
    const v = new Vector3(x, y, z).project(this.camera);
    const rect = this.canvas.getBoundingClientRect();
    return { x: rect.left + ((v.x + 1) / 2) * rect.width, y: rect.top + ((1 - v.y) / 2) * rect.height };
  }

  // Whether a surface point is the first thing the view ray to it meets (not hidden behind other surface).
  isVisible(point, tolerance = 2) {
    const s = this.projectToScreen(point);
    const hit = this.pick(s.x, s.y);
    if (!hit) return false;
    const d = Math.hypot(hit.point[0] - point[0], hit.point[1] - point[1], hit.point[2] - point[2]);
    return d <= tolerance * this.meanEdge;
  }

  // The live stroke: a band as wide on screen as the stroke handles' ribbons, through the samples lifted off
  // the surface along their face normals.
  strokeAdd(sample) {
    if (!this.strokeBand) {
      this.strokeBand = new GrowingBand(new BandMaterial({ color: 0xff7a1a, widthPx: RIBBON_PX }));
      this.strokeBand.mesh.renderOrder = 2;
      this.scene.add(this.strokeBand.mesh);
    }
    const lift = STROKE_LIFT * this.meanEdge;
    const n = this.surface.normal(sample.face);
    const p = this.pointFromBary(sample.face, sample.bary);
    this.strokeBand.push([p[0] + lift * n[0], p[1] + lift * n[1], p[2] + lift * n[2]], n);
    this.requestRender();
  }

  clearStroke() {
    if (!this.strokeBand) return;
    this.scene.remove(this.strokeBand.mesh);
    this.strokeBand.dispose();
    this.strokeBand = null;
    this.requestRender();
  }
}

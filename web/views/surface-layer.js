// The big surface drawn once per view, not once per frame. With software GL (SwiftShader) a frame of an
// 832k-face scan costs the GPU process ~0.85 s of CPU, and every stroke draws two (its preview, its exact
// field) on the cores the exact solve needs. The field's layers (arrows, lines, handles, markers) change far
// more often than the surface's own picture, which depends only on the camera, the drawing buffer and the
// surface's geometry and material: so on a mesh this big (with software GL, on any: layerMinFaces) the surface
// is drawn into a target (colour and depth, multisampled like the canvas unless GL is software: layerSamples)
// when one of those changes, and every frame copies that target onto the canvas, depth included, before the
// scene is drawn over it without the surface.
// The depth copy keeps the layers lying in the face planes (polygon offset) and the surface hiding what is
// behind it exactly as before.
// A surface whose colours follow the field (the magnitude colour map), that another view replaces (material
// preview) or that the flow texture draws over is drawn in the scene as usual. The synthesized texture's model
// stands in for the surface (viewer.surfaceStandIn): its picture too depends on the view alone, and on the
// textures it shows, which it counts in userData.pictureVersion. The copy covers only the rectangle the
// surface's bounding box projects to: outside it the layer holds the clear colour at the far depth, which the
// canvas's clear already gives, and with software GL the copy costs by the pixel (a full-screen copy into the
// multisampled canvas was 20-30 of a field frame's 37-44 ms, drawn while the exact solve runs).
//
// Owns its render target and copy pass. Imports three.js and gl-renderer.js.
import {
  AlwaysDepth,
  Color,
  DepthTexture,
  Mesh,
  NoBlending,
  OrthographicCamera,
  PlaneGeometry,
  Scene,
  ShaderMaterial,
  SRGBColorSpace,
  UnsignedIntType,
  Vector2,
  Vector4,
  WebGLRenderTarget,
} from 'three';
import { isSoftwareGL } from './gl-renderer.js';

// From this many faces the surface is drawn into the layer (on a GPU a bunny00 frame, 75k faces, was done 7-11 ms
// after its stroke's field, queue included, on the H200 machine; the cached path costs a copy per frame and a
// target the size of the canvas).
export const SURFACE_LAYER_FACES = 200_000;
// With software GL, every surface: there the surface drawn into the multisampled canvas costs by the sample and
// the small triangle, and the layer (single-sampled there, layerSamples) wins on an edit's frame and on an
// orbit's alike, whatever the size. GPU-process ms a frame at 1024x720 on a 2-core machine (medians of 12, an
// edit's / an orbit's), drawn directly against from the layer: the default bunny (3.7k faces) 93 / 102 against
// 48 / 91, homer (9.9k) 105 / 114 against 44 / 83, camel (19.5k) 165 / 165 against 45 / 111, bunny00 (75k)
// 319 / 295 against 48 / 187 (docs/benchmarks.md, "Views and layout").
export const SOFTWARE_SURFACE_LAYER_FACES = 1;

// The face count from which the layer applies for this renderer's GL.
export function layerMinFaces(renderer) {
  return isSoftwareGL(renderer.getContext()) ? SOFTWARE_SURFACE_LAYER_FACES : SURFACE_LAYER_FACES;
}

const COPY_VERTEX = /* glsl */ `
varying vec2 vUv;
void main() {
  vUv = uv;
  gl_Position = vec4(position.xy, 0.0, 1.0);
}`;

// The target's colour is linear (sRGB-encoded storage, decoded when sampled): the copy encodes it for the
// canvas as the renderer would have.
const COPY_FRAGMENT = /* glsl */ `
uniform sampler2D uColor;
uniform sampler2D uDepth;
varying vec2 vUv;
void main() {
  gl_FragColor = texture2D(uColor, vUv);
  gl_FragDepth = texture2D(uDepth, vUv).r;
  #include <colorspace_fragment>
}`;

// The pass that copies the layer onto the canvas (compiled ahead: SurfaceLayer.warmUp).
export function copyMaterial() {
  return new ShaderMaterial({
    uniforms: { uColor: { value: null }, uDepth: { value: null } },
    vertexShader: COPY_VERTEX,
    fragmentShader: COPY_FRAGMENT,
    blending: NoBlending,
    depthTest: true, // depth is only written where the test is on: Always passes
    depthFunc: AlwaysDepth,
    depthWrite: true,
  });
}

// A target like the layer's, for compiling the surface's programs as they draw into it (linear output).
// samples: 4 like the canvas, or 0 with software GL (layerSamples).
export function layerTarget(width, height, samples = 0) {
  const depthTexture = new DepthTexture(width, height, UnsignedIntType);
  return new WebGLRenderTarget(width, height, { samples, depthTexture, colorSpace: SRGBColorSpace });
}

// The layer's samples: 4, as the canvas's antialiasing has, except with software GL (SwiftShader, llvmpipe, WARP),
// where the multisampled layer is what a big model's first frame costs: SwiftShader drew armadillo-sub2's
// 832k faces into four samples in 5.1-7.9 s of the GPU process beside the exact solve on a 2-core machine
// (the solve's factorization 8.2-8.5 s then), into one in 1.9 s (the factorization 6.4 s). The surface's
// silhouette is then drawn without antialiasing; the layers over it keep the canvas's.
export function layerSamples(renderer) {
  return isSoftwareGL(renderer.getContext()) ? 0 : 4;
}

// The pixels (x, y from the bottom left, width, height) of a width x height drawing buffer that `mesh` can
// cover seen by `camera`: the projection of its bounding box, widened by two pixels for the multisampled
// edges; null when the box reaches behind the camera's near plane (then all of it).
export function screenRectOf(mesh, camera, width, height) {
  const g = mesh.geometry;
  const version = g.getAttribute('position')?.version;
  // A box the geometry came with (a big surface's, from its BVH's root) is taken as it is: computing it here
  // is a pass over every vertex on the page's thread. It is computed again when the positions change after.
  g.userData.boundingBoxVersion ??= g.boundingBox ? version : undefined;
  if (!g.boundingBox || g.userData.boundingBoxVersion !== version) {
    g.computeBoundingBox();
    g.userData.boundingBoxVersion = version;
  }
  const box = g.boundingBox;
  if (box.isEmpty() || ![box.min.x, box.min.y, box.min.z, box.max.x, box.max.y, box.max.z].every(Number.isFinite))
    return null;
  camera.updateMatrixWorld();
  const toClip = camera.projectionMatrix.clone().multiply(camera.matrixWorldInverse).multiply(mesh.matrixWorld);
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  const corner = new Vector4();
  for (let k = 0; k < 8; k++) {
    const { min, max } = box;
    corner.set(k & 1 ? max.x : min.x, k & 2 ? max.y : min.y, k & 4 ? max.z : min.z, 1).applyMatrix4(toClip);
    if (!(corner.w > 0) || corner.z < -corner.w) return null;
    x0 = Math.min(x0, corner.x / corner.w);
    x1 = Math.max(x1, corner.x / corner.w);
    y0 = Math.min(y0, corner.y / corner.w);
    y1 = Math.max(y1, corner.y / corner.w);
  }
  const px = (v, size) => ((v + 1) / 2) * size;
  const left = Math.max(0, Math.floor(px(x0, width)) - 2), right = Math.min(width, Math.ceil(px(x1, width)) + 2);
  const bottom = Math.max(0, Math.floor(px(y0, height)) - 2), top = Math.min(height, Math.ceil(px(y1, height)) + 2);
  return { x: left, y: bottom, width: Math.max(0, right - left), height: Math.max(0, top - bottom) };
}

export class SurfaceLayer {
  constructor() {
    this.minFaces = null; // layerMinFaces(), asked at the first frame or compile (unless a caller set it)
    this.target = null;
    this.key = null;
    this.size = new Vector2();
    this.clearColor = new Color();
    this.drawn = 0; // times the surface was drawn into the layer
    this.copied = 0; // frames that copied it instead
    this.rect = null; // the drawing buffer's pixels the copy covers (screenRectOf; null: all)
    this.samples = null; // the target's (layerSamples), asked once
    this.material = copyMaterial();
    this.copyScene = new Scene();
    this.copyScene.add(new Mesh(new PlaneGeometry(2, 2), this.material));
    this.copyCamera = new OrthographicCamera(-1, 1, 1, -1, 0, 1);
    this.emptyScene = new Scene();
  }

  // Whether the surface's picture depends on nothing but the view, and the mesh is big enough to gain.
  applies(surfaceMesh, licVisible) {
    const m = surfaceMesh?.material;
    if (!m || licVisible || !surfaceMesh.visible || !m.visible || m.vertexColors || m.map) return false;
    return this.#bigEnough(surfaceMesh);
  }

  // A mesh whose pixels are what costs (userData.costlyPixels: the synthesized texture's, magnified per pixel
  // from four texels: 0.4-0.9 s a frame of the 75k-face bunny with software GL) gains at any size.
  #bigEnough(mesh) {
    if (mesh.userData?.costlyPixels) return true;
    const g = mesh.geometry;
    return (g.index ?? g.getAttribute('position')).count / 3 >= this.minFaces;
  }

  // Compiles a stand-in's program ahead of its first frame, for where render() will draw it (the layer's
  // linear output or the canvas): three.js's first draw of a new program asks for its link status and its
  // uniforms, which wait for the GPU process (~125 ms at 832k faces with software GL). Resolves when linked
  // (at once without KHR_parallel_shader_compile: then the GPU process links it while the page goes on).
  async compile(renderer, scene, camera, mesh) {
    this.minFaces ??= layerMinFaces(renderer);
    const target = this.#bigEnough(mesh) ? layerTarget(1, 1) : null;
    const previous = renderer.getRenderTarget();
    let linked = null;
    try {
      renderer.setRenderTarget(target);
      if (renderer.extensions.has('KHR_parallel_shader_compile')) linked = renderer.compileAsync(mesh, camera, scene);
      else renderer.compile(mesh, camera, scene);
    } finally {
      renderer.setRenderTarget(previous);
      target?.dispose();
    }
    await linked;
    // Its first draw would then fetch the program's uniforms, another round trip to the GPU process, which
    // behind a synthesis is busy for a while: fetched now, right after the link.
    renderer.properties.get(mesh.material).currentProgram?.getUniforms();
  }

  // The copy's program, compiled when the viewer starts (shader-warm-up.js reads it back later) for where it is
  // drawn: onto the canvas, in a scene without lights. three.js keys a program by the scene's lights too, so
  // compiled in the lit scene it was another program, and a big model's first field made this one (a 31-46 ms
  // wait for its link in that task, with software GL).
  warmUp(renderer) {
    const previous = renderer.getRenderTarget();
    try {
      renderer.setRenderTarget(null);
      renderer.compile(this.copyScene, this.copyCamera);
    } finally {
      renderer.setRenderTarget(previous);
    }
  }

  // Draws scene with camera, the surface from the layer where that applies (else as part of the scene).
  render(renderer, scene, camera, surfaceMesh, licVisible) {
    this.minFaces ??= layerMinFaces(renderer);
    if (!this.applies(surfaceMesh, licVisible)) {
      renderer.render(scene, camera);
      return;
    }
    renderer.getDrawingBufferSize(this.size);
    const key = this.#keyOf(renderer, camera, surfaceMesh);
    if (key !== this.key) this.#drawSurface(renderer, camera, surfaceMesh, key);
    else this.copied++;
    const autoClear = renderer.autoClear;
    // Cleared as a direct render clears (three.js converts the clear colour for the canvas there; a bare clear
    // would take the colour last set, the layer's linear one): outside the copy's rectangle this is the picture.
    renderer.autoClear = true;
    renderer.render(this.emptyScene, this.copyCamera);
    renderer.autoClear = false;
    this.#copy(renderer);
    surfaceMesh.visible = false;
    try {
      renderer.render(scene, camera);
    } finally {
      surfaceMesh.visible = true;
      renderer.autoClear = autoClear;
    }
  }

  // The layer onto the canvas, within its rectangle (three.js takes the scissor in CSS pixels).
  #copy(renderer) {
    const r = this.rect;
    if (r) {
      const ratio = renderer.getPixelRatio();
      renderer.setScissor(r.x / ratio, r.y / ratio, r.width / ratio, r.height / ratio);
      renderer.setScissorTest(true);
    }
    try {
      renderer.render(this.copyScene, this.copyCamera);
    } finally {
      if (r) renderer.setScissorTest(false);
    }
  }

  // What the surface's picture depends on, as a string: the drawing buffer, the camera (the headlight rides
  // on it), the surface's transform, geometry, material and the textures a stand-in shows.
  #keyOf(renderer, camera, mesh) {
    camera.updateMatrixWorld();
    mesh.updateMatrixWorld();
    const g = mesh.geometry;
    const versions = ['position', 'normal'].map((n) => g.getAttribute(n)?.version ?? -1);
    return [
      this.size.x,
      this.size.y,
      renderer.getPixelRatio(),
      renderer.getClearColor(this.clearColor).getHex(),
      renderer.getClearAlpha(),
      ...camera.matrixWorld.elements,
      ...camera.projectionMatrix.elements,
      ...mesh.matrixWorld.elements,
      mesh.id,
      g.id,
      g.index?.version ?? -1,
      ...versions,
      mesh.material.id,
      mesh.material.version,
      mesh.userData.pictureVersion ?? 0,
    ].join(' ');
  }

  #drawSurface(renderer, camera, mesh, key) {
    const { x, y } = this.size;
    if (!this.target || this.target.width !== x || this.target.height !== y) this.#makeTarget(renderer, x, y);
    const previous = renderer.getRenderTarget();
    // The surface alone, in the scene it belongs to (its lights), everything else hidden for the pass.
    const scene = mesh.parent;
    const hidden = scene.children.filter((o) => o !== mesh && o.visible && !o.isLight && o !== camera);
    for (const o of hidden) o.visible = false;
    try {
      renderer.setRenderTarget(this.target);
      renderer.clear();
      renderer.render(scene, camera);
    } finally {
      for (const o of hidden) o.visible = true;
      renderer.setRenderTarget(previous);
    }
    this.key = key;
    this.rect = screenRectOf(mesh, camera, x, y);
    this.drawn++;
  }

  #makeTarget(renderer, width, height) {
    this.target?.dispose();
    this.samples ??= layerSamples(renderer);
    this.target = layerTarget(width, height, this.samples);
    this.material.uniforms.uColor.value = this.target.texture;
    this.material.uniforms.uDepth.value = this.target.depthTexture;
  }

  // The view changed in a way the key does not see (a lost context): draw the surface again.
  invalidate() {
    this.key = null;
  }

  dispose() {
    this.target?.dispose();
    this.target = null;
    this.material.dispose();
    this.copyScene.children[0].geometry.dispose();
  }
}

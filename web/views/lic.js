// Flow-texture view: line integral convolution (LIC) of white noise along the field, in screen space, on the
// GPU. Two passes after the ordinary scene render:
//   1. the surface is drawn into a half-float target: the field's direction on screen (unit, in drawing-buffer
//      pixels), a shading term and a coverage mask, with a depth texture;
//   2. a full-screen pass averages a fixed noise texture along that direction field (±LIC_STEPS steps of one
//      pixel, re-reading the direction at each step) and writes the streaked grey over the surface. It writes
//      the surface's own depth and tests it against the scene's, so arrows, lines and handles in front of the
//      surface stay visible.
// The noise is anchored to the screen: a still picture is exact, while an orbit makes the streaks swim.
// An N-field (N ≥ 2) takes both passes once per family of lines, on a surface copy of its own (lic-lines.js).
import {
  BufferAttribute,
  Color,
  DataTexture,
  DepthTexture,
  DoubleSide,
  HalfFloatType,
  LessEqualDepth,
  LinearFilter,
  Mesh,
  NearestFilter,
  OrthographicCamera,
  PlaneGeometry,
  RGBAFormat,
  RepeatWrapping,
  Scene,
  ShaderMaterial,
  UnsignedByteType,
  Vector2,
  WebGLRenderTarget,
} from 'three';
import { randomSequence } from '../geometry/arrow-sampling.js';
import { symmetryOf } from '../geometry/nfield.js';
import { LINE_DIRECTION_VERTEX, lineGeometry, linePasses, setLineField } from './lic-lines.js';

export const LIC_STEPS = 20; // each way: streaks of about 2 × 20 px
const NOISE_SIZE = 256;

// Pass 1: per pixel, the field's direction projected to the screen. The field is interpolated in 3D and
// projected per fragment (not per vertex), so a curved surface bends the direction correctly inside a face.
const DIRECTION_VERTEX = /* glsl */ `
attribute vec3 licField;
varying vec3 vWorld;
varying vec3 vField;
varying vec3 vNormal;
void main() {
  vec4 world = modelMatrix * vec4(position, 1.0);
  vWorld = world.xyz;
  vField = mat3(modelMatrix) * licField;
  vNormal = normalize(mat3(modelMatrix) * normal);
  gl_Position = projectionMatrix * viewMatrix * world;
}`;
const DIRECTION_FRAGMENT = /* glsl */ `
uniform mat4 projectionMatrix; // three.js declares it for vertex shaders only
uniform vec2 resolution;
uniform float eps;
varying vec3 vWorld;
varying vec3 vField;
varying vec3 vNormal;
void main() {
  float len = length(vField);
  vec2 dir = vec2(0.0);
  if (len > 0.0) {
    vec4 a = projectionMatrix * viewMatrix * vec4(vWorld, 1.0);
    vec4 b = projectionMatrix * viewMatrix * vec4(vWorld + eps * vField / len, 1.0);
    vec2 d = (b.xy / b.w - a.xy / a.w) * 0.5 * resolution;
    float l = length(d);
    if (l > 0.0) dir = d / l;
  }
  vec3 toEye = normalize(cameraPosition - vWorld);
  float shade = abs(dot(normalize(vNormal), toEye));
  gl_FragColor = vec4(dir, shade, 1.0);
}`;

const CONVOLVE_VERTEX = /* glsl */ `
void main() { gl_Position = vec4(position.xy, 0.0, 1.0); }`;
// lines (N-fields): each pass is blended in at passAlpha, and a streak stops where the direction turns to
// another family (|cos| < minCos) rather than following it.
const convolveFragment = (lines) => /* glsl */ `
uniform sampler2D directions;
uniform sampler2D depths;
uniform sampler2D noise;
uniform vec2 resolution;
uniform float contrast;
${lines ? 'uniform float passAlpha;\nuniform float minCos;' : ''}
const float NOISE_PX = 2.0;
// One noise texel per NOISE_PX pixels, bilinear: pixel-sized nearest noise would leave stair steps along
// oblique streaks, which bias their direction towards the diagonals.
float noiseAt(vec2 p) { return texture2D(noise, p / (NOISE_PX * ${NOISE_SIZE.toFixed(1)})).r; }
void main() {
  vec2 p0 = gl_FragCoord.xy;
  vec4 here = texture2D(directions, p0 / resolution);
  if (here.a < 0.5) discard;
  float sum = noiseAt(p0);
  float count = 1.0;
  for (int side = 0; side < 2; side++) {
    float s = side == 0 ? 1.0 : -1.0;
    vec2 p = p0;
    vec2 d = here.xy;
    for (int i = 0; i < ${LIC_STEPS}; i++) {
      // Midpoint step: the direction half a pixel ahead, kept on the same side as the last one (the field
      // is a vector field, but a sign flip from interpolation noise would fold the streak back).
      vec4 mid = texture2D(directions, (p + 0.5 * s * d) / resolution);
      if (mid.a < 0.5 || dot(mid.xy, mid.xy) < 0.01${lines ? ' || abs(dot(mid.xy, d)) < minCos' : ''}) break;
      d = dot(mid.xy, d) < 0.0 ? -mid.xy : mid.xy;
      p += s * d;
      sum += noiseAt(p);
      count += 1.0;
    }
  }
  float v = clamp(0.5 + contrast * (sum / count - 0.5), 0.0, 1.0);
  float shade = 0.35 + 0.65 * here.b;
  gl_FragColor = vec4(vec3(v * shade), ${lines ? 'passAlpha' : '1.0'});
  gl_FragDepth = texture2D(depths, p0 / resolution).r;
}`;

// White noise, one value per texel, from a fixed seed (geometry/arrow-sampling.js's generator): the same
// picture on every run.
function noiseTexture(seed = 0x2545f491) {
  const data = new Uint8Array(NOISE_SIZE * NOISE_SIZE * 4);
  const random = randomSequence(seed);
  for (let i = 0; i < NOISE_SIZE * NOISE_SIZE; i++) {
    const v = Math.floor(random() * 256);
    data.set([v, v, v, 255], 4 * i);
  }
  const tex = new DataTexture(data, NOISE_SIZE, NOISE_SIZE, RGBAFormat, UnsignedByteType);
  tex.wrapS = tex.wrapT = RepeatWrapping;
  tex.magFilter = tex.minFilter = LinearFilter;
  tex.needsUpdate = true;
  return tex;
}

function directionMaterial(vertexShader, uniforms) {
  return new ShaderMaterial({
    vertexShader,
    fragmentShader: DIRECTION_FRAGMENT,
    uniforms,
    side: DoubleSide,
    // The surface material's offset: the same depths, so the depth test in pass 2 meets the scene's exactly.
    polygonOffset: true,
    polygonOffsetFactor: 1,
    polygonOffsetUnits: 1,
  });
}

// lines: an N-field's pass, blended into the mean of the passes before it (transparent).
function convolveMaterial(lines, uniforms) {
  return new ShaderMaterial({
    vertexShader: CONVOLVE_VERTEX,
    fragmentShader: convolveFragment(lines),
    uniforms,
    depthTest: true,
    depthWrite: false,
    depthFunc: LessEqualDepth,
    transparent: lines,
  });
}

export class LicView {
  constructor() {
    this.visible = false;
    this.size = new Vector2(1, 1);
    this.directionScene = new Scene();
    this.directionMaterial = directionMaterial(DIRECTION_VERTEX, {
      resolution: { value: this.size },
      eps: { value: 1e-3 },
    });
    this.target = new WebGLRenderTarget(1, 1, { type: HalfFloatType, depthTexture: new DepthTexture(1, 1) });
    this.target.texture.minFilter = this.target.texture.magFilter = NearestFilter;
    this.noise = noiseTexture();
    this.convolveMaterial = convolveMaterial(false, {
      directions: { value: this.target.texture },
      depths: { value: this.target.depthTexture },
      noise: { value: this.noise },
      resolution: { value: this.size },
      contrast: { value: 3.5 },
    });
    this.quadScene = new Scene();
    this.quad = new Mesh(new PlaneGeometry(2, 2), this.convolveMaterial);
    this.quad.frustumCulled = false;
    this.quadScene.add(this.quad);
    this.quadCamera = new OrthographicCamera(-1, 1, 1, -1, 0, 1);
    this.surface = null;
    this.clearColor = new Color();
    this.#initLines();
  }

  // The N-field's passes: their own materials and scene, the surface copy made on the first N-field drawn.
  #initLines() {
    // The uniforms they share with the vector field's passes are the same objects (size, eps, textures).
    const d = this.directionMaterial.uniforms, c = this.convolveMaterial.uniforms;
    this.lineDirectionMaterial = directionMaterial(LINE_DIRECTION_VERTEX, {
      resolution: d.resolution,
      eps: d.eps,
      angle: { value: 0 },
    });
    this.lineConvolveMaterial = convolveMaterial(true, {
      ...c,
      contrast: { value: c.contrast.value },
      passAlpha: { value: 1 },
      minCos: { value: 0 },
    });
    this.lineScene = new Scene();
    this.lineMesh = null;
    this.meshSurface = null; // the Surface the copy is made from
    this.symmetry = 1;
    this.pendingLines = null; // {vertexVectors, faceVectors}: made into the corner field when next drawn
  }

  // The surface mesh's geometry (shared, not copied) and its size for the projection step. surface: the
  // Surface, for N-fields.
  setSurface(geometry, meanEdge, surface = null) {
    if (this.surface) this.directionScene.remove(this.surface);
    this.surface = new Mesh(geometry, this.directionMaterial);
    this.surface.frustumCulled = false;
    this.directionScene.add(this.surface);
    this.directionMaterial.uniforms.eps.value = 0.05 * meanEdge;
    this.#disposeLines();
    this.meshSurface = surface;
    this.pendingLines = null;
  }

  #disposeLines() {
    if (!this.lineMesh) return;
    this.lineScene.remove(this.lineMesh);
    this.lineMesh.geometry.dispose();
    this.lineMesh = null;
  }

  // Per-vertex field (the vertex vectors, 3 per vertex). symmetry: the field's N (1 when absent);
  // faceVectors: its face representatives, the references an N-field's corners are matched to.
  setField(vertexVectors, { symmetry = 1, faceVectors = null } = {}) {
    this.symmetry = symmetryOf(symmetry);
    if (this.symmetry > 1) {
      // Made when drawn: the colour map also hands the field here, and needs no corner field.
      this.pendingLines = { vertexVectors, faceVectors };
      return;
    }
    // Back to a vector field: the copy's memory (four values per corner) is not kept for a later N-field.
    this.pendingLines = null;
    this.#disposeLines();
    const geom = this.surface?.geometry;
    if (!geom) return;
    const n = geom.getAttribute('position').count;
    if (vertexVectors.length !== 3 * n) return;
    const attr = geom.getAttribute('licField');
    if (attr && attr.count === n) {
      attr.array.set(vertexVectors);
      attr.needsUpdate = true;
    } else geom.setAttribute('licField', new BufferAttribute(Float32Array.from(vertexVectors), 3));
  }

  setVisible(on) {
    this.visible = !!on;
  }

  // Draws the flow texture over what `renderer` has just drawn with `camera` (called after the scene render).
  render(renderer, camera) {
    if (!this.visible) return;
    if (this.symmetry > 1) return void this.#renderLines(renderer, camera);
    if (!this.surface?.geometry.getAttribute('licField')) return;
    this.#pass(renderer, camera, this.directionScene, this.convolveMaterial);
  }

  // One direction pass into the target, then one convolution over the screen.
  #pass(renderer, camera, scene, convolve) {
    renderer.getDrawingBufferSize(this.size);
    if (this.target.width !== this.size.x || this.target.height !== this.size.y)
      this.target.setSize(this.size.x, this.size.y);
    const previous = renderer.getRenderTarget();
    const clearAlpha = renderer.getClearAlpha();
    const autoClear = renderer.autoClear;
    renderer.getClearColor(this.clearColor);
    renderer.setRenderTarget(this.target);
    renderer.setClearColor(0x000000, 0);
    renderer.clear(true, true, false);
    renderer.render(scene, camera);
    renderer.setRenderTarget(previous);
    renderer.setClearColor(this.clearColor, clearAlpha);
    renderer.autoClear = false;
    this.quad.material = convolve;
    renderer.render(this.quadScene, this.quadCamera);
    renderer.autoClear = autoClear;
  }

  #renderLines(renderer, camera) {
    if (this.pendingLines && this.meshSurface) {
      if (!this.lineMesh) {
        this.lineMesh = new Mesh(lineGeometry(this.meshSurface), this.lineDirectionMaterial);
        this.lineMesh.frustumCulled = false;
        this.lineScene.add(this.lineMesh);
      }
      const { vertexVectors, faceVectors } = this.pendingLines;
      if (vertexVectors.length === 3 * this.meshSurface.nV)
        setLineField(this.lineMesh.geometry, this.meshSurface, vertexVectors, faceVectors, this.symmetry);
      this.pendingLines = null;
    }
    if (!this.lineMesh?.geometry.getAttribute('licField')) return;
    const u = this.lineConvolveMaterial.uniforms;
    for (const p of linePasses(this.symmetry, this.convolveMaterial.uniforms.contrast.value)) {
      this.lineDirectionMaterial.uniforms.angle.value = p.angle;
      u.passAlpha.value = p.passAlpha;
      u.minCos.value = p.minCos;
      u.contrast.value = p.contrast;
      this.#pass(renderer, camera, this.lineScene, this.lineConvolveMaterial);
    }
  }

  dispose() {
    this.target.dispose();
    this.target.depthTexture?.dispose();
    this.noise.dispose();
    this.directionMaterial.dispose();
    this.convolveMaterial.dispose();
    this.#disposeLines();
    this.lineDirectionMaterial.dispose();
    this.lineConvolveMaterial.dispose();
    this.quad.geometry.dispose();
  }
}

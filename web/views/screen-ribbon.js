// Bands a fixed number of screen pixels wide, whatever the mesh density and the zoom: the stroke handles'
// ribbons and their direction chevrons (handles.js), and the live stroke while it is drawn (viewer.js).
// A vertex is a point of the curve (on the surface), the surface normal and the curve's tangent there, and an
// offset in units of the band's width: along the tangent's direction on screen and across it. The vertex
// shader projects the point, turns the offset into pixels and moves the point towards the eye along its view
// ray, which leaves it where it is on screen: by a few pixels' worth of depth, and by as much more as the
// surface under the band's half-width comes closer where it is seen at a slant, so the surface never cuts
// the band.
import { BufferAttribute, BufferGeometry, Color, DoubleSide, Mesh, ShaderMaterial, Vector2, Vector4 } from 'three';

const VERTEX = /* glsl */ `
uniform vec2 resolution; // the view, in CSS pixels
uniform float widthPx;
uniform float liftPx;
attribute vec3 tangent;
attribute vec2 offset; // (along, across), in units of widthPx
void main() {
  vec4 mv = modelViewMatrix * vec4(position, 1.0);
  bool perspective = projectionMatrix[2][3] == -1.0;
  float wpp = 2.0 * (perspective ? -mv.z : 1.0) / (projectionMatrix[1][1] * resolution.y); // model units per pixel
  vec3 toEye = perspective ? normalize(-mv.xyz) : vec3(0.0, 0.0, 1.0);
  // The surface's depth changes by up to tan(slant) pixels' worth per pixel across the screen (capped: at
  // grazing angles the band is at a silhouette anyway).
  float slope = 0.0;
  if (dot(normal, normal) > 0.0) {
    float c = abs(dot(normalize(normalMatrix * normal), toEye));
    slope = min(sqrt(max(0.0, 1.0 - c * c)) / max(c, 1e-3), 6.0);
  }
  vec3 t = mat3(modelViewMatrix) * tangent;
  float tl = length(t);
  vec4 clip = projectionMatrix * vec4(mv.xyz + toEye * ((liftPx + 0.5 * widthPx * slope) * wpp), 1.0);
  vec4 ahead = projectionMatrix * vec4(mv.xyz + (tl > 0.0 ? t / tl : vec3(1.0, 0.0, 0.0)) * wpp, 1.0);
  vec2 d = (ahead.xy / ahead.w - clip.xy / clip.w) * resolution;
  float l = length(d);
  vec2 along = l > 1e-6 ? d / l : vec2(1.0, 0.0);
  vec2 across = vec2(-along.y, along.x);
  vec2 px = (offset.x * along + offset.y * across) * widthPx;
  clip.xy += px * 2.0 / resolution * clip.w;
  gl_Position = clip;
}`;

const FRAGMENT = /* glsl */ `
uniform vec3 color;
void main() {
  gl_FragColor = vec4(color, 1.0);
  #include <colorspace_fragment>
}`;

export class BandMaterial extends ShaderMaterial {
  // widthPx: the band's width in CSS pixels; liftPx: how far towards the eye, in pixels' worth of depth.
  constructor({ color, widthPx, liftPx = 2 }) {
    super({
      vertexShader: VERTEX,
      fragmentShader: FRAGMENT,
      uniforms: {
        color: { value: new Color(color) },
        resolution: { value: new Vector2(1, 1) },
        widthPx: { value: widthPx },
        liftPx: { value: liftPx },
      },
      side: DoubleSide,
    });
  }

  // As on the built-in materials: material.color.set(…).
  get color() {
    return this.uniforms.color.value;
  }
}

// A mesh drawn with a BandMaterial. The view's size in CSS pixels is read at each draw, from the target drawn
// into: a screenshot at twice the canvas size draws its bands twice as wide, as it does its arrows.
export function bandMesh(geometry, material) {
  const mesh = new Mesh(geometry, material);
  mesh.frustumCulled = false;
  const viewport = new Vector4();
  mesh.onBeforeRender = (renderer) => {
    renderer.getCurrentViewport(viewport);
    const css = renderer.domElement.clientHeight || viewport.w || 1;
    material.uniforms.resolution.value.set((viewport.z * css) / (viewport.w || 1), css);
  };
  return mesh;
}

// A band along a polyline (points [[x, y, z], …], with the surface normal at each): two vertices per point,
// tangents by central differences.
export function bandGeometry(points, normals) {
  const n = points.length;
  const pos = new Float32Array(6 * n);
  const nrm = new Float32Array(6 * n);
  const tan = new Float32Array(6 * n);
  const off = new Float32Array(4 * n);
  for (let k = 0; k < n; k++) {
    const a = points[Math.max(0, k - 1)], b = points[Math.min(n - 1, k + 1)];
    for (let s = 0; s < 2; s++) {
      pos.set(points[k], 6 * k + 3 * s);
      nrm.set(normals[k], 6 * k + 3 * s);
      tan.set([b[0] - a[0], b[1] - a[1], b[2] - a[2]], 6 * k + 3 * s);
      off.set([0, s ? 0.5 : -0.5], 4 * k + 2 * s);
    }
  }
  const g = attributes({ pos, nrm, tan, off });
  g.setIndex(stripIndex(n));
  return g;
}

function attributes({ pos, nrm, tan, off }) {
  const g = new BufferGeometry();
  g.setAttribute('position', new BufferAttribute(pos, 3));
  g.setAttribute('normal', new BufferAttribute(nrm, 3));
  g.setAttribute('tangent', new BufferAttribute(tan, 3));
  g.setAttribute('offset', new BufferAttribute(off, 2));
  return g;
}

function stripIndex(n) {
  const index = [];
  for (let k = 0; k + 1 < n; k++) index.push(2 * k, 2 * k + 1, 2 * k + 2, 2 * k + 1, 2 * k + 3, 2 * k + 2);
  return index;
}

// Filled arrowheads: for each {centre, normal, tangent} a triangle `length` long and `width` wide (in units of
// the band's width) pointing along the tangent on screen.
export function chevronGeometry(cues, { length = 1.5, width = 0.84 } = {}) {
  const corners = [[length / 2, 0], [-length / 2, width / 2], [-length / 2, -width / 2]];
  const pos = [], nrm = [], tan = [], off = [];
  for (const { centre, normal, tangent } of cues) {
    for (const c of corners) pos.push(...centre), nrm.push(...normal), tan.push(...tangent), off.push(...c);
  }
  return attributes({
    pos: new Float32Array(pos),
    nrm: new Float32Array(nrm),
    tan: new Float32Array(tan),
    off: new Float32Array(off),
  });
}

// A band that grows a point at a time (the live stroke): the buffers double when full.
export class GrowingBand {
  constructor(material) {
    this.points = [];
    this.geometry = new BufferGeometry();
    this.mesh = bandMesh(this.geometry, material);
    this.#allocate(256);
  }

  #allocate(capacity) {
    const old = this.geometry.attributes;
    const arrays = {
      pos: new Float32Array(6 * capacity),
      nrm: new Float32Array(6 * capacity),
      tan: new Float32Array(6 * capacity),
      off: new Float32Array(4 * capacity),
    };
    if (old.position) {
      arrays.pos.set(old.position.array);
      arrays.nrm.set(old.normal.array);
      arrays.tan.set(old.tangent.array);
    }
    for (let k = 0; k < capacity; k++) arrays.off.set([0, -0.5, 0, 0.5], 4 * k);
    this.geometry.dispose();
    this.geometry = attributes(arrays);
    this.geometry.setIndex(stripIndex(capacity));
    this.mesh.geometry = this.geometry;
    this.capacity = capacity;
  }

  // p: a point of the curve, n: the surface normal there.
  push(p, n) {
    const P = this.points;
    if (P.length === this.capacity) this.#allocate(2 * this.capacity);
    P.push(p);
    const g = this.geometry, { position, normal, tangent } = g.attributes;
    const k1 = P.length - 1;
    position.array.set([...p, ...p], 6 * k1);
    normal.array.set([...n, ...n], 6 * k1);
    // The new point and the one before it get their tangents (central differences, one-sided at the ends).
    for (let k = Math.max(0, k1 - 1); k <= k1; k++) {
      const a = P[Math.max(0, k - 1)], b = P[Math.min(k1, k + 1)];
      const t = [b[0] - a[0], b[1] - a[1], b[2] - a[2]];
      tangent.array.set([...t, ...t], 6 * k);
    }
    position.needsUpdate = normal.needsUpdate = tangent.needsUpdate = true;
    g.setDrawRange(0, 6 * k1);
  }

  dispose() {
    this.geometry.dispose();
    this.mesh.material.dispose();
  }
}

// Field views drawn over the surface: instanced arrows, streamlines and singularity markers. (The magnitude
// colour map is a vertex-colour mode of the surface itself, in viewer.js.) Each view is handed the Surface
// once per mesh and the field arrays after every change, and only rebuilds what it shows.
import {
  BufferAttribute,
  BufferGeometry,
  CanvasTexture,
  Color,
  DoubleSide,
  DynamicDrawUsage,
  Group,
  InstancedMesh,
  LineBasicMaterial,
  LineSegments,
  Matrix4,
  MeshBasicMaterial,
  SRGBColorSpace,
  Sprite,
  SpriteMaterial,
  Vector3,
} from 'three';
import { scrambled } from './surface.js';

const ARROW_LIFT = 0.02; // × mean edge length, keeps arrows above the surface they lie on

// Magnitude colour ramp (blue → cyan → yellow → red): readable on the grey surface at both ends.
const RAMP = [0x2563eb, 0x06b6d4, 0xfacc15, 0xef4444].map((c) => new Color(c));
export function rampColor(t, out) {
  const s = Math.min(Math.max(t, 0), 1) * (RAMP.length - 1);
  const i = Math.min(Math.floor(s), RAMP.length - 2);
  return out.copy(RAMP[i]).lerp(RAMP[i + 1], s - i);
}

// A flat arrow in the xy-plane, unit length along +x, centred on the origin so it sits on its anchor.
export function arrowGeometry({ shaftW = 0.05, headW = 0.2, headL = 0.38, centred = true } = {}) {
  const x0 = centred ? -0.5 : 0, x1 = centred ? 0.5 : 1, xh = x1 - headL;
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

// Arrow spacing for density level 1..10 (10 = one arrow per face), as a fraction of the model's radius.
function arrowSpacing(level, radius) {
  return level >= 10 ? 0 : radius * 0.15 * ((10 - level) / 9) ** 1.5;
}

// The densest level that puts at most `count` arrows on the surface. Greedy Poisson-disk sampling covers a
// surface of area A with about 0.7 A / r² points at spacing r.
export function arrowDensityFor(surface, count) {
  let area = 0;
  for (let f = 0; f < surface.nF; f++) area += surface.areas[f];
  if (surface.nF <= count) return 10;
  for (let level = 9; level > 1; level--) {
    const r = arrowSpacing(level, surface.radius);
    if ((0.7 * area) / (r * r) <= count) return level;
  }
  return 1;
}

export class ArrowsView {
  constructor(scene) {
    this.scene = scene;
    this.mesh = null;
    this.options = { visible: true, density: 10, scaled: false };
    this.neutral = false;
    this.vectors = null;
    this.faces = null; // faces that carry an arrow at the current density
  }

  setSurface(surface) {
    this.#dispose();
    this.surface = surface;
    this.vectors = null;
    this.faces = null;
    this.mesh = new InstancedMesh(
      arrowGeometry(),
      new MeshBasicMaterial({ color: 0xffffff, side: DoubleSide }),
      Math.max(surface.nF, 1),
    );
    this.mesh.instanceMatrix.setUsage(DynamicDrawUsage);
    this.mesh.frustumCulled = false;
    this.mesh.count = 0;
    this.scene.add(this.mesh);
  }

  #dispose() {
    if (!this.mesh) return;
    this.scene.remove(this.mesh);
    this.mesh.geometry.dispose();
    this.mesh.material.dispose();
    this.mesh.dispose();
    this.mesh = null;
  }

  setOptions(options) {
    const densityChanged = options.density !== undefined && options.density !== this.options.density;
    Object.assign(this.options, options);
    if (densityChanged) this.faces = null;
    this.#rebuild();
  }

  setNeutral(neutral) {
    this.neutral = neutral;
    this.#rebuild();
  }

  setField(faceVectors) {
    this.vectors = faceVectors;
    this.#rebuild();
  }

  // Greedy Poisson-disk sample of face centres in a scrambled order: even coverage at any density.
  #selectFaces() {
    const s = this.surface;
    const r = arrowSpacing(this.options.density, s.radius);
    if (r <= 0) return Int32Array.from({ length: s.nF }, (_, f) => f);
    const cells = new Map();
    const key = (x, y, z) => `${x},${y},${z}`;
    const chosen = [];
    const C = s.centres;
    for (const f of scrambled(s.nF)) {
      const x = C[3 * f], y = C[3 * f + 1], z = C[3 * f + 2];
      const ix = Math.floor(x / r), iy = Math.floor(y / r), iz = Math.floor(z / r);
      let free = true;
      for (let dx = -1; dx <= 1 && free; dx++)
        for (let dy = -1; dy <= 1 && free; dy++)
          for (let dz = -1; dz <= 1 && free; dz++)
            for (const g of cells.get(key(ix + dx, iy + dy, iz + dz)) ?? []) {
              if (Math.hypot(C[3 * g] - x, C[3 * g + 1] - y, C[3 * g + 2] - z) < r) {
                free = false;
                break;
              }
            }
      if (!free) continue;
      chosen.push(f);
      const k = key(ix, iy, iz);
      if (!cells.has(k)) cells.set(k, []);
      cells.get(k).push(f);
    }
    return Int32Array.from(chosen);
  }

  #rebuild() {
    if (!this.mesh) return;
    const V = this.vectors;
    if (!V || !this.options.visible) {
      this.mesh.visible = false;
      return;
    }
    this.faces ??= this.#selectFaces();
    const s = this.surface;
    // Colours and scaled lengths top out at the 98th percentile of the magnitudes (as the colour map does):
    // the spike at a source or vortex would otherwise leave every other arrow at the bottom of the ramp.
    const mags = new Float64Array(s.nF);
    for (let f = 0; f < s.nF; f++) {
      const m = Math.hypot(V[3 * f], V[3 * f + 1], V[3 * f + 2]);
      mags[f] = Number.isFinite(m) ? m : 0;
    }
    const sorted = mags.slice().sort();
    const max = sorted[s.nF - 1] ?? 0;
    const top = sorted[Math.min(s.nF - 1, Math.floor(0.98 * s.nF))] || max;
    const spacing = arrowSpacing(this.options.density, s.radius);
    const len = Math.max(0.6 * s.meanEdge, 0.8 * spacing);
    const lift = ARROW_LIFT * s.meanEdge;
    const m4 = new Matrix4();
    const x = new Vector3(), y = new Vector3(), z = new Vector3(), color = new Color(0xf4f4f5);
    // Faces whose vector is negligible next to the largest get no arrow rather than a noisy direction.
    const floor = max * 1e-6;
    let n = 0;
    for (const f of this.faces) {
      z.set(s.normals[3 * f], s.normals[3 * f + 1], s.normals[3 * f + 2]);
      x.set(V[3 * f], V[3 * f + 1], V[3 * f + 2]);
      x.addScaledVector(z, -x.dot(z)); // in the face plane, whatever rounding the core left
      const mag = x.length();
      if (!(mag > floor)) continue;
      const l = this.options.scaled ? len * Math.min(1, mag / top) : len;
      x.multiplyScalar(l / mag);
      y.crossVectors(z, x);
      m4.makeBasis(x, y, z);
      m4.setPosition(s.centres[3 * f] + lift * z.x, s.centres[3 * f + 1] + lift * z.y, s.centres[3 * f + 2] + lift * z.z);
      this.mesh.setMatrixAt(n, m4);
      if (!this.neutral) rampColor(mag / top, color);
      this.mesh.setColorAt(n, color);
      n++;
    }
    this.mesh.count = n;
    this.mesh.instanceMatrix.needsUpdate = true;
    if (this.mesh.instanceColor) this.mesh.instanceColor.needsUpdate = true;
    this.mesh.visible = n > 0;
    this.max = max;
  }
}

export class StreamlinesView {
  constructor(scene) {
    this.scene = scene;
    this.lines = null;
    this.polylines = [];
  }

  setSurface() {
    this.setLines([]);
  }

  // polylines: Float32Array per line (x, y, z per point).
  setLines(polylines) {
    this.polylines = polylines;
    let segments = 0;
    for (const l of polylines) segments += Math.max(0, l.length / 3 - 1);
    const pos = new Float32Array(6 * segments);
    let o = 0;
    for (const l of polylines) {
      for (let k = 0; k + 3 < l.length; k += 3) {
        pos.set(l.subarray(k, k + 6), o);
        o += 6;
      }
    }
    if (!this.lines) {
      this.lines = new LineSegments(new BufferGeometry(), new LineBasicMaterial({ color: 0x111827 }));
      this.lines.frustumCulled = false;
      this.lines.renderOrder = 1;
      this.scene.add(this.lines);
    }
    this.lines.geometry.dispose();
    const g = new BufferGeometry();
    g.setAttribute('position', new BufferAttribute(pos, 3));
    this.lines.geometry = g;
    this.lines.visible = segments > 0;
  }
}

// Markers with the index written on them, as sprites: always facing the viewer, hidden behind the surface.
const MARKER_PX = 20;

// Disc textures with a label, cached per viewer (textures belong to one renderer; dispose() frees them).
export class LabelTextures {
  constructor() {
    this.cache = new Map();
  }

  get(key, fill, text, options) {
    let tex = this.cache.get(key);
    if (!tex) this.cache.set(key, (tex = discTexture(fill, text, options)));
    return tex;
  }

  dispose() {
    for (const tex of this.cache.values()) tex.dispose();
    this.cache.clear();
  }
}

function discTexture(fill, text, { ring = false, textColor = '#111827' } = {}) {
  const size = 64;
  const c = document.createElement('canvas');
  c.width = c.height = size;
  const g = c.getContext('2d');
  g.beginPath();
  g.arc(size / 2, size / 2, size / 2 - 3, 0, 2 * Math.PI);
  g.fillStyle = fill;
  g.fill();
  g.lineWidth = ring ? 6 : 3;
  g.strokeStyle = ring ? '#ffffff' : 'rgba(17, 24, 39, 0.85)';
  g.stroke();
  g.fillStyle = textColor;
  g.font = `bold ${text.length > 2 ? 24 : 30}px system-ui, sans-serif`;
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillText(text, size / 2, size / 2 + 2);
  const tex = new CanvasTexture(c);
  tex.colorSpace = SRGBColorSpace;
  return tex;
}

export function markerSprite(texture, px = MARKER_PX) {
  const s = new Sprite(new SpriteMaterial({ map: texture, sizeAttenuation: false, depthTest: true, transparent: true }));
  s.userData.px = px;
  s.renderOrder = 3;
  return s;
}

// Keeps sprites at a fixed size in pixels: without size attenuation a sprite's scale is in units of the
// view height times tan(fov/2), see three's sprite shader.
export function fixSpriteScales(group, camera, renderer) {
  const h = renderer.domElement.clientHeight || renderer.domElement.height || 1;
  const k = (2 * Math.tan((camera.fov * Math.PI) / 360)) / h;
  for (const s of group.children) if (s.isSprite) s.scale.setScalar(s.userData.px * k);
}

function indexLabel(index) {
  const r = Math.round(index);
  return r > 0 ? `+${r}` : r < 0 ? `\u2212${-r}` : '0';
}

export class SingularitiesView {
  constructor(scene, labels) {
    this.labels = labels;
    this.group = new Group();
    this.group.visible = false;
    scene.add(this.group);
    this.list = [];
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
    for (const s of this.group.children) s.material.dispose();
    this.group.clear();
    const s = this.surface, list = this.list;
    if (!s || !this.group.visible) return;
    const lift = 0.6 * s.meanEdge;
    // A field that has not settled (or is zero) can report a singularity at almost every vertex; drawing
    // thousands of sprites would only hide the model.
    for (const { vertex, index } of list.slice(0, 400)) {
      const label = indexLabel(index);
      const fill = index > 0 ? '#facc15' : '#c084fc';
      const sprite = markerSprite(this.labels.get(`sing:${label}`, fill, label));
      const p = s.vertex(vertex), n = s.vertexNormals;
      sprite.position.set(p[0] + lift * n[3 * vertex], p[1] + lift * n[3 * vertex + 1], p[2] + lift * n[3 * vertex + 2]);
      sprite.userData.vertex = vertex;
      this.group.add(sprite);
    }
  }

  updateScale(camera, renderer) {
    if (this.group.visible) fixSpriteScales(this.group, camera, renderer);
  }
}


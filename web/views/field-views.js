// Field views drawn over the surface: instanced arrows, streamlines and singularity markers. (The magnitude
// colour map is a vertex-colour mode of the surface itself, in viewer.js.) Each view is handed the Surface
// once per mesh and the field arrays after every change, and only rebuilds what it shows.
import {
  BufferAttribute,
  BufferGeometry,
  CanvasTexture,
  CircleGeometry,
  Color,
  DoubleSide,
  DynamicDrawUsage,
  Group,
  InstancedMesh,
  LineBasicMaterial,
  LineSegments,
  Matrix4,
  Mesh,
  MeshBasicMaterial,
  SRGBColorSpace,
  Sprite,
  SpriteMaterial,
  Vector3,
} from 'three';
import { POISSON_PACKING, sampleSurface, worldPerPixel } from '../geometry/arrow-sampling.js';
import { magnitudeScale, viridis } from './colormap.js';

const ARROW_LIFT = 0.02; // × mean edge length, keeps arrows above the surface they lie on

// Magnitude colours (arrows and the surface map) use viridis (colormap.js); the name stays for callers.
export const rampColor = viridis;

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

// Arrow spacing on screen (pixels) for density level 1..10. Level 6, the default, puts about 1.5 thousand
// arrows on a model framed in a 1024 × 720 view, whatever its resolution.
export function arrowSpacingPx(level) {
  return 33 * 0.82 ** (Math.min(Math.max(level, 1), 10) - 1);
}
export const DEFAULT_ARROW_DENSITY = 6;
const ARROW_LENGTH = 0.8; // × the spacing: neighbours never touch
// Resample when the scale on screen has changed by more than this factor (zooming), not on every frame.
const RESAMPLE_RATIO = 1.25;
// Beyond this many samples over the whole surface (zoomed far in), sample only the faces near the view.
const MAX_SAMPLES = 12_000;

export class ArrowsView {
  constructor(scene) {
    this.scene = scene;
    this.mesh = null;
    this.options = { visible: true, density: DEFAULT_ARROW_DENSITY, scaled: false };
    this.neutral = false;
    this.faceVectors = null;
    this.vertexVectors = null;
    this.samples = null; // {faces, bary, points} at the current spacing
    this.sampledAt = null; // {wpp, position, direction, local} of the view the samples were made for
    this.wpp = 0; // model units per pixel at the pivot, for the current view
    this.top = 0; // magnitude at the top of the colour map
    this.scale = null; // magnitudeScale of the field drawn
  }

  setSurface(surface) {
    this.#dispose();
    this.surface = surface;
    this.faceVectors = this.vertexVectors = null;
    this.samples = this.sampledAt = null;
    this.mesh = new InstancedMesh(arrowGeometry(), new MeshBasicMaterial({ color: 0xffffff, side: DoubleSide }), 1);
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
    if (densityChanged) this.samples = null;
    this.#rebuild();
  }

  setNeutral(neutral) {
    this.neutral = neutral;
    this.#rebuild();
  }

  // faceVectors: 3 per face; vertexVectors (optional): 3 per vertex, interpolated inside each face so the
  // arrows turn smoothly rather than in steps at face edges; scale (optional): magnitudeScale(vertexVectors),
  // when the caller has it already.
  setField(faceVectors, vertexVectors = null, scale = null) {
    this.faceVectors = faceVectors;
    this.vertexVectors = vertexVectors && this.surface && vertexVectors.length === 3 * this.surface.nV ? vertexVectors : null;
    this.scale = this.vertexVectors ? scale : null;
    this.#rebuild();
  }

  // Called before each render: keeps the spacing and the length constant in pixels. A small zoom only
  // rescales the arrows; one that changes the scale by RESAMPLE_RATIO (or moves a local sample set out of
  // view) resamples.
  updateView(camera, pivot, heightPx) {
    if (!this.mesh || !this.surface) return false;
    this.camera = camera;
    const wpp = worldPerPixel(camera, pivot, heightPx);
    if (!(wpp > 0)) return false;
    const prev = this.wpp;
    this.wpp = wpp;
    const at = this.sampledAt;
    if (!at) return this.#resample(camera, heightPx);
    const ratio = wpp / at.wpp;
    let stale = ratio > RESAMPLE_RATIO || ratio < 1 / RESAMPLE_RATIO;
    if (!stale && at.local) {
      const moved = camera.position.distanceTo(at.position) > 0.25 * wpp * heightPx;
      const turned = camera.getWorldDirection(new Vector3()).dot(at.direction) < Math.cos((10 * Math.PI) / 180);
      stale = moved || turned;
    }
    if (stale) return this.#resample(camera, heightPx);
    if (Math.abs(wpp / prev - 1) > 0.01) this.#rebuild();
    return false;
  }

  #resample(camera, heightPx) {
    this.samples = null;
    this.#rebuild(camera, heightPx);
    return true;
  }

  #sample(camera, heightPx) {
    const s = this.surface;
    const spacing = arrowSpacingPx(this.options.density) * this.wpp;
    let area = 0;
    for (let f = 0; f < s.nF; f++) area += s.areas[f];
    let faces = null;
    if ((POISSON_PACKING * area) / (spacing * spacing) > MAX_SAMPLES && camera) faces = facesNearView(s, camera);
    this.samples = sampleSurface(s, spacing, { faces, maxSamples: MAX_SAMPLES });
    this.sampledAt = {
      wpp: this.wpp,
      local: !!faces,
      position: camera ? camera.position.clone() : new Vector3(),
      direction: camera ? camera.getWorldDirection(new Vector3()) : new Vector3(0, 0, -1),
      heightPx,
    };
  }

  #rebuild(camera = this.camera, heightPx = this.sampledAt?.heightPx) {
    if (!this.mesh) return;
    const F = this.faceVectors;
    if (!F || !this.options.visible || !(this.wpp > 0)) {
      this.mesh.visible = false;
      return;
    }
    if (!this.samples) this.#sample(camera, heightPx);
    const s = this.surface, V = this.vertexVectors, T = s.triangles;
    const { faces, bary, points } = this.samples;
    const n = faces.length;
    if (this.mesh.instanceMatrix.count < n) this.#grow(n);
    // Colours and scaled lengths top out at the 98th percentile of the magnitudes (as the colour map does):
    // the spike at a source or vortex would otherwise leave every other arrow at the bottom of the map.
    this.scale ??= magnitudeScale(V ?? F);
    const { max, top } = this.scale;
    this.top = top;
    const len = ARROW_LENGTH * arrowSpacingPx(this.options.density) * this.wpp;
    const lift = ARROW_LIFT * s.meanEdge;
    const m4 = new Matrix4();
    const x = new Vector3(), y = new Vector3(), z = new Vector3(), color = new Color(0xf4f4f5);
    // Samples whose vector is negligible next to the largest get no arrow rather than a noisy direction.
    const floor = max * 1e-6;
    let k = 0;
    for (let i = 0; i < n; i++) {
      const f = faces[i];
      z.set(s.normals[3 * f], s.normals[3 * f + 1], s.normals[3 * f + 2]);
      if (V) {
        x.set(0, 0, 0);
        for (let c = 0; c < 3; c++) {
          const v = T[3 * f + c], b = bary[3 * i + c];
          x.x += b * V[3 * v];
          x.y += b * V[3 * v + 1];
          x.z += b * V[3 * v + 2];
        }
      } else x.set(F[3 * f], F[3 * f + 1], F[3 * f + 2]);
      x.addScaledVector(z, -x.dot(z)); // in the face plane
      const mag = x.length();
      if (!(mag > floor)) continue;
      const l = this.options.scaled ? len * Math.min(1, mag / top) : len;
      x.multiplyScalar(l / mag);
      y.crossVectors(z, x);
      m4.makeBasis(x, y, z);
      m4.setPosition(points[3 * i] + lift * z.x, points[3 * i + 1] + lift * z.y, points[3 * i + 2] + lift * z.z);
      this.mesh.setMatrixAt(k, m4);
      if (!this.neutral) rampColor(mag / top, color);
      this.mesh.setColorAt(k, color);
      k++;
    }
    this.mesh.count = k;
    this.mesh.instanceMatrix.needsUpdate = true;
    if (this.mesh.instanceColor) this.mesh.instanceColor.needsUpdate = true;
    this.mesh.visible = k > 0;
    this.max = max;
  }

  // InstancedMesh buffers have a fixed size: a larger sample set needs a new mesh (same geometry and material).
  #grow(n) {
    const old = this.mesh;
    this.scene.remove(old);
    this.mesh = new InstancedMesh(old.geometry, old.material, Math.ceil(n * 1.25));
    this.mesh.instanceMatrix.setUsage(DynamicDrawUsage);
    this.mesh.frustumCulled = false;
    this.mesh.count = 0;
    this.scene.add(this.mesh);
    old.dispose();
  }

  // The arrows as drawn: for each instance its anchor and its vector (length and direction, model units).
  drawn() {
    const n = this.mesh?.visible ? this.mesh.count : 0;
    const M = this.mesh?.instanceMatrix.array;
    const anchors = new Float64Array(3 * n), vectors = new Float64Array(3 * n);
    for (let i = 0; i < n; i++) {
      for (let c = 0; c < 3; c++) {
        anchors[3 * i + c] = M[16 * i + 12 + c];
        vectors[3 * i + c] = M[16 * i + c];
      }
    }
    return { anchors, vectors };
  }
}

// Faces whose centre projects within twice the view (and in front of the camera): where arrows can be seen
// now or after a small orbit.
function facesNearView(s, camera) {
  const v = new Vector3(), out = [];
  for (let f = 0; f < s.nF; f++) {
    v.set(s.centres[3 * f], s.centres[3 * f + 1], s.centres[3 * f + 2]).project(camera);
    if (Math.abs(v.x) <= 2 && Math.abs(v.y) <= 2 && v.z <= 1 && v.z >= -1) out.push(f);
  }
  return Int32Array.from(out);
}

// Streamlines run along the field (the tracer orders each line's points that way), so each carries chevrons
// pointing downstream: a "V" lying on the surface every CUE_EVERY points.
const CUE_EVERY = 6; // points between chevrons (the tracer takes about 4 per streamline spacing)
const CUE_SIZE = 1.6; // chevron length, × the line's step

export class StreamlinesView {
  constructor(scene) {
    this.scene = scene;
    this.lines = null;
    this.polylines = [];
    this.cues = []; // {tip, back} per chevron, model units
    this.normalAt = null; // (x, y, z) → unit surface normal near that point, set by the viewer
  }

  setSurface() {
    this.setLines([]);
  }

  // polylines: Float32Array per line (x, y, z per point).
  setLines(polylines) {
    this.polylines = polylines;
    this.cues = this.normalAt ? polylines.flatMap((l) => chevrons(l, this.normalAt)) : [];
    let segments = 2 * this.cues.length;
    for (const l of polylines) segments += Math.max(0, l.length / 3 - 1);
    const pos = new Float32Array(6 * segments);
    let o = 0;
    for (const l of polylines) {
      for (let k = 0; k + 3 < l.length; k += 3) {
        pos.set(l.subarray(k, k + 6), o);
        o += 6;
      }
    }
    for (const { tip, wings } of this.cues) {
      for (const w of wings) {
        pos.set(w, o);
        pos.set(tip, o + 3);
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

function chevrons(line, normalAt) {
  const out = [];
  const n = line.length / 3;
  const at = (k) => [line[3 * k], line[3 * k + 1], line[3 * k + 2]];
  for (let k = CUE_EVERY / 2; k + 1 < n; k += CUE_EVERY) {
    const tip = at(k + 1), prev = at(k);
    const t = [tip[0] - prev[0], tip[1] - prev[1], tip[2] - prev[2]];
    const step = Math.hypot(...t);
    if (!(step > 0)) continue;
    const size = CUE_SIZE * step;
    const u = t.map((x) => x / step);
    const nrm = normalAt(tip[0], tip[1], tip[2]);
    // Across the line, in the surface: n × t.
    const side = [nrm[1] * u[2] - nrm[2] * u[1], nrm[2] * u[0] - nrm[0] * u[2], nrm[0] * u[1] - nrm[1] * u[0]];
    const back = tip.map((x, c) => x - size * u[c]);
    const wings = [1, -1].map((sgn) => back.map((x, c) => x + sgn * 0.55 * size * side[c]));
    out.push({ tip, back, wings });
  }
  return out;
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

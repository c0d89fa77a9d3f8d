// Instanced arrows over the surface, spaced and sized on the screen (the same count and length in pixels at
// any mesh resolution and zoom) and coloured by magnitude (viridis). Handed the Surface once per mesh and the
// field arrays after every change; resampled when a zoom changes the scale on screen. An N-field (symmetry
// N ≥ 2) is drawn with N spokes per sample instead of an arrow (a segment for a line field, a cross for a
// cross field), its vertex representatives matched to the face's before they are interpolated.
import { Color, DoubleSide, DynamicDrawUsage, InstancedMesh, Matrix4, MeshBasicMaterial, Vector3 } from 'three';
import { POISSON_PACKING, SurfaceSampler, sampleSurface, worldPerPixel } from '../geometry/arrow-sampling.js';
import { matchedAt, symmetryOf } from '../geometry/nfield.js';
import { viridis } from './colormap.js';
import { magnitudeScale } from '../geometry/magnitudes.js';
import { glyphGeometry } from './markers.js';

const ARROW_LIFT = 0.02; // × mean edge length, keeps arrows above the surface they lie on

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
// When the samples are made ahead (prepare), darts are thrown this many at a time until a task has run this
// long: a fixed 8,000 a task (~10 ms warm) took 150-185 ms of one task as armadillo-sub2 reopened, 39-126 ms
// of it in the darts, the page's thread sharing two cores with a preview worker and software GL.
const DARTS_PER_STEP = 1000;
const TASK_MS = 8;

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
    this.symmetry = 1; // N of the field drawn: the glyph and how vertex vectors are interpolated
    this.prepared = null; // {surface, spacing, samples} made ahead by prepare()
  }

  setSurface(surface) {
    this.#dispose();
    this.surface = surface;
    this.faceVectors = this.vertexVectors = null;
    this.samples = this.sampledAt = null;
    // The previous surface's scale is not this one's: no arrows until the next render's updateView has the
    // scale of this surface in view (sampling at the old one, then again at the new, cost a second sampling).
    this.wpp = 0;
    const material = new MeshBasicMaterial({ color: 0xffffff, side: DoubleSide });
    this.mesh = new InstancedMesh(glyphGeometry(this.symmetry), material, 1);
    this.mesh.instanceMatrix.setUsage(DynamicDrawUsage);
    this.mesh.frustumCulled = false;
    this.mesh.count = 0;
    this.scene.add(this.mesh);
  }

  // The samples of a surface about to be drawn, made ahead at the scale its framed view will have (wpp: model
  // units per pixel at the pivot), a slice of darts per task: at 832k faces the sampling took ~100–190 ms of
  // the task that adopted the model. #sample takes them if the view's scale is the one foreseen. yieldToPage():
  // a promise that resolves in a later task.
  async prepare(surface, wpp, yieldToPage) {
    this.prepared = null;
    const spacing = arrowSpacingPx(this.options.density) * wpp;
    // Too many for the whole surface: the view's own local set, made when it draws.
    if (!(spacing > 0) || (POISSON_PACKING * surface.area) / (spacing * spacing) > MAX_SAMPLES) return;
    const sampler = new SurfaceSampler(surface, spacing, { maxSamples: MAX_SAMPLES });
    for (;;) {
      const end = performance.now() + TASK_MS;
      let done;
      do done = sampler.step(DARTS_PER_STEP);
      while (!done && performance.now() < end);
      if (done) break;
      await yieldToPage();
    }
    this.prepared = { surface, spacing, samples: sampler.result() };
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

  // faceVectors: 3 per face (null for a vector field given by its vertex vectors: a preview's);
  // vertexVectors (optional): 3 per vertex, interpolated inside each face so the arrows turn smoothly rather
  // than in steps at face edges; scale (optional): magnitudeScale(vertexVectors), when the caller has it
  // already; symmetry (optional): the field's N, 1 (arrows) when absent.
  setField(faceVectors, vertexVectors = null, scale = null, symmetry = 1) {
    this.#setSymmetry(symmetryOf(symmetry));
    this.faceVectors = faceVectors;
    const fits = vertexVectors && this.surface && vertexVectors.length === 3 * this.surface.nV;
    this.vertexVectors = fits ? vertexVectors : null;
    this.scale = this.vertexVectors ? scale : null;
    this.#rebuild();
  }

  // Another N takes another glyph; the instances, their matrices and colours stay.
  #setSymmetry(N) {
    if (N === this.symmetry) return;
    this.symmetry = N;
    if (!this.mesh) return;
    this.mesh.geometry.dispose();
    this.mesh.geometry = glyphGeometry(N);
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
    let faces = null;
    if ((POISSON_PACKING * s.area) / (spacing * spacing) > MAX_SAMPLES && camera) faces = facesNearView(s, camera);
    const p = this.prepared;
    this.prepared = null;
    // Made ahead for this surface at this scale (up to the rounding of the camera's placement): the same darts.
    const ready = !faces && p?.surface === s && Math.abs(p.spacing / spacing - 1) < 1e-9;
    this.samples = ready ? p.samples : sampleSurface(s, spacing, { faces, maxSamples: MAX_SAMPLES });
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
    const F = this.faceVectors, V = this.vertexVectors;
    if (!(V || F) || (this.symmetry > 1 && !F) || !this.options.visible || !(this.wpp > 0)) {
      this.mesh.visible = false;
      return;
    }
    if (!this.samples) this.#sample(camera, heightPx);
    const s = this.surface, T = s.triangles;
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
    const x = new Vector3(), y = new Vector3(), z = new Vector3(), color = new Color(0xf4f4f5), nrm = [0, 0, 0];
    // Samples whose vector is negligible next to the largest get no arrow rather than a noisy direction.
    const floor = max * 1e-6;
    const N = this.symmetry, matched = [0, 0, 0];
    let k = 0;
    for (let i = 0; i < n; i++) {
      const f = faces[i];
      z.fromArray(s.normalInto(f, nrm));
      if (V && N > 1) {
        // The face's representative is the reference the three corners are turned to before they mix.
        matchedAt(s, V, f, bary.subarray(3 * i, 3 * i + 3), [F[3 * f], F[3 * f + 1], F[3 * f + 2]], N, matched);
        x.fromArray(matched);
      } else if (V) {
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
      if (!this.neutral) viridis(mag / top, color);
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

  // The arrows as drawn: for each instance its anchor and its vector (length and direction, model units);
  // for an N-field the vector is the glyph's first spoke, the others being it turned by 2πk/N.
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
  const P = s.positions, T = s.triangles;
  for (let f = 0; f < s.nF; f++) {
    const a = 3 * T[3 * f], b = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
    v.set((P[a] + P[b] + P[c]) / 3, (P[a + 1] + P[b + 1] + P[c + 1]) / 3, (P[a + 2] + P[b + 2] + P[c + 2]) / 3);
    v.project(camera);
    if (Math.abs(v.x) <= 2 && Math.abs(v.y) <= 2 && v.z <= 1 && v.z >= -1) out.push(f);
  }
  return Int32Array.from(out);
}

// Evenly spaced streamlines on a triangle mesh (Jobard & Lefer 1997, carried over to surfaces).
// The field traced is the per-vertex field (vertexVectors) interpolated linearly over each face and taken in
// the face's plane: unlike the per-face constant field it is continuous across edges, so lines cross edges
// smoothly and RK2 inside a face is meaningful. Lines cross edges by unfolding the step into the neighbour.
// Distances are 3D Euclidean (a good stand-in for geodesic ones at the spacing used), but only between
// points whose faces face the same way, so the two sides of a thin part do not block each other.
//
// N-symmetric fields (symmetry N ≥ 2: line, cross, …) are traced as unoriented lines: the three vertex
// representatives of a face are matched to the face's reference before they are interpolated, and each step
// takes the representative closest to the heading so far. Through each seed go the field's families of lines
// (N/2 lines both ways for even N, N rays for odd N, nfield.js), and a line keeps its distance only from
// lines of its own family, so that the two families of a cross field cross each other freely.

import { closestRotation2d, familyCosine, lineFamilies, symmetryOf } from './nfield.js';
import { scrambled } from './surface.js';

const MAX_POINTS_PER_LINE = 4000;
const ZERO = Object.freeze([0, 0, 0]);
// N-fields: the interpolated field counts as defined where |Σ bₖcₖ| ≥ this × Σ bₖ|cₖ|
// (corners within ~90°).
const COHERENCE = 0.7;

// Returns polylines as Float32Arrays (x, y, z per point), lifted off the surface by `lift` along face normals.
// symmetry: the field's N (1 when absent); faceVectors (optional, N ≥ 2): the per-face representatives the
// corners are matched to (without them, corners 1 and 2 are matched to corner 0).
export function traceStreamlines(surface, vertexVectors, options = {}) {
  const { spacing, lift = 0, stepsPerSpacing = 4, minLengthFactor = 1.5, symmetry = 1, faceVectors = null } = options;
  const N = symmetryOf(symmetry);
  const dSep = spacing;
  const dTest = 0.5 * dSep;
  const h = dSep / stepsPerSpacing;
  const field = faceCornerField(surface, vertexVectors, N, faceVectors);
  if (!field) return [];
  const grid = new PointGrid(dSep);
  const lines = [];
  const seeds = [];

  const accept = (line) => {
    lines.push(line);
    // Candidate seeds d_sep to either side of every few points, found by walking straight across the surface.
    for (let k = 0; k < line.samples.length; k += 2) {
      const s = line.samples[k];
      const n = Math.hypot(s.dir[0], s.dir[1]);
      if (!n) continue;
      for (const side of [1, -1])
        seeds.push({ face: s.face, p: s.p, dir: [(-side * s.dir[1]) / n, (side * s.dir[0]) / n] });
    }
  };

  let nextId = 0;
  const keep = (line, id) => {
    if (line && line.length >= minLengthFactor * dSep) accept(line);
    else grid.kill(id);
  };
  const families = lineFamilies(N);
  // A step may turn by at most 3/4 of the π/N a closest representative can lie off the heading (60° at
  // least, as the vector field's test): more is a singularity, not a bend.
  const turn = { N, turnCos: Math.max(0.5, Math.cos((0.75 * Math.PI) / N)), familyCos: familyCosine(N) };
  const tryTrace = (face, p) => {
    const x = surface.to3d(face, p);
    if (N > 1) return void tryFamilies(face, p, x);
    if (grid.near(x, surface.normal(face), dSep * 0.99, -1, 0, 0)) return;
    const id = nextId++;
    keep(traceLine(surface, field, face, p, { h, dTest, dSep, grid, id, lift }), id);
  };
  // Each family through the seed that no line of its own family passes near yet.
  const tryFamilies = (face, p, x) => {
    const d0 = direction(surface, field, face, p);
    if (!d0) return;
    const nrm = surface.normal(face);
    for (const a of families.angles) {
      const c = Math.cos(a), s = Math.sin(a), heading = [c * d0[0] - s * d0[1], s * d0[0] + c * d0[1]];
      if (grid.near(x, nrm, dSep * 0.99, -1, 0, 0, surface.vec3d(face, heading), turn.familyCos)) continue;
      const id = nextId++;
      keep(
        traceLineN(surface, field, face, p, heading, {
          h,
          dTest,
          dSep,
          grid,
          id,
          lift,
          bothWays: families.bothWays,
          ...turn,
        }),
        id,
      );
    }
  };

  // Start where the field is strongest; then Jobard–Lefer seeding next to existing lines; then fill the gaps
  // (other components, regions cut off by singularities) from face centres in a fixed scrambled order.
  tryTrace(field.strongestFace, centre2d(surface, field.strongestFace));
  const order = scrambled(surface.nF);
  let next = 0;
  for (;;) {
    while (seeds.length) {
      const s = seeds.pop();
      const w = surface.walk(s.face, s.p, s.dir, dSep);
      if (!w.hitBoundary) tryTrace(w.face, w.p);
    }
    while (next < order.length && !seeds.length) {
      const f = order[next++];
      if (field.weak[f]) continue;
      tryTrace(f, centre2d(surface, f));
    }
    if (!seeds.length) break;
  }
  return lines.map((l) => l.points);
}

function centre2d(surface, f) {
  return surface.to2d(f, surface.centroid(f));
}

// Per face, the three corner vectors in the face's 2D frame; faces where all three are negligible are weak.
// For N ≥ 2 each corner is first turned to the rotation closest to the face's reference (its representative
// in `reference`, or corner 0), so that interpolating them never averages two different choices.
function faceCornerField(surface, V, N = 1, reference = null) {
  const nF = surface.nF, T = surface.triangles;
  const corners = new Float64Array(6 * nF);
  let max = 0;
  for (let v = 0; v < V.length / 3; v++) max = Math.max(max, Math.hypot(V[3 * v], V[3 * v + 1], V[3 * v + 2]));
  if (!(max > 0)) return null;
  const weak = new Uint8Array(nF), lengths = N > 1 ? new Float64Array(3 * nF) : null;
  let strongestFace = 0, strongest = -1;
  for (let f = 0; f < nF; f++) {
    let s = 0, ref = null;
    if (N > 1 && reference) ref = surface.vec2d(f, [reference[3 * f], reference[3 * f + 1], reference[3 * f + 2]]);
    if (ref && ref[0] === 0 && ref[1] === 0) ref = null;
    for (let k = 0; k < 3; k++) {
      const v = T[3 * f + k];
      let c = surface.vec2d(f, [V[3 * v], V[3 * v + 1], V[3 * v + 2]]);
      if (N > 1) c = closestRotation2d(c, (ref ??= c), N);
      corners[6 * f + 2 * k] = c[0];
      corners[6 * f + 2 * k + 1] = c[1];
      s += Math.hypot(c[0], c[1]);
      if (lengths) lengths[3 * f + k] = Math.hypot(c[0], c[1]);
    }
    weak[f] = s < 3e-3 * max ? 1 : 0;
    if (s > strongest) {
      strongest = s;
      strongestFace = f;
    }
  }
  return { corners, lengths, weak, strongestFace, floor: 1e-3 * max };
}

// Unit direction of the interpolated field at 2D point p of face f, or null where it (nearly) vanishes. An
// N-field's corners are unit, so it vanishes where they disagree: next to a singularity, where the matched
// corners fan out and their mean falls below COHERENCE of their mean length.
function direction(surface, field, f, p) {
  const b = surface.bary2d(f, p);
  const C = field.corners, o = 6 * f;
  const x = b[0] * C[o] + b[1] * C[o + 2] + b[2] * C[o + 4];
  const y = b[0] * C[o + 1] + b[1] * C[o + 3] + b[2] * C[o + 5];
  const l = Math.hypot(x, y);
  if (
    field.lengths &&
    !(l > COHERENCE * (b[0] * field.lengths[3 * f] + b[1] * field.lengths[3 * f + 1] + b[2] * field.lengths[3 * f + 2]))
  )
    return null;
  return l > field.floor ? [x / l, y / l] : null;
}

// The line's own points go into the grid as they are traced, tagged with their signed arc length from the
// seed, so that a line closing on itself (around a vortex) stops too; a rejected line is killed in the grid.
function traceLine(surface, field, face, p, opts) {
  opts.grid.add(surface.to3d(face, p), surface.normal(face), opts.id, 0);
  const fwd = traceHalf(surface, field, face, p, 1, opts);
  const bwd = traceHalf(surface, field, face, p, -1, opts);
  const samples = [
    ...bwd.samples.reverse(),
    { face, p, dir: direction(surface, field, face, p) ?? [0, 0] },
    ...fwd.samples,
  ];
  return polyline(surface, samples, bwd.length + fwd.length, opts.lift);
}

function polyline(surface, samples, length, lift) {
  if (samples.length < 2) return null;
  const points = new Float32Array(3 * samples.length);
  samples.forEach((s, k) => {
    const x = surface.to3d(s.face, s.p);
    const n = surface.normal(s.face);
    points.set([x[0] + lift * n[0], x[1] + lift * n[1], x[2] + lift * n[2]], 3 * k);
  });
  return { samples, points, length };
}

// An unoriented line of an N-field from its seed along `heading` (2D, in the seed face's frame), and back
// along −heading where the field holds it (even N). Its points carry the line's direction in the grid.
function traceLineN(surface, field, face, p, heading, opts) {
  opts.grid.add(surface.to3d(face, p), surface.normal(face), opts.id, 0, surface.vec3d(face, heading));
  const fwd = traceHalfN(surface, field, face, p, heading, 1, opts);
  const bwd = opts.bothWays
    ? traceHalfN(surface, field, face, p, [-heading[0], -heading[1]], -1, opts)
    : { samples: [], length: 0 };
  const samples = [...bwd.samples.reverse(), { face, p, dir: heading }, ...fwd.samples];
  return polyline(surface, samples, bwd.length + fwd.length, opts.lift);
}

// The direction of the N-field at p closest to the heading `to` (2D unit), or null where it vanishes.
function along(surface, field, f, p, to, N) {
  const d = direction(surface, field, f, p);
  return d && closestRotation2d(d, to, N);
}

// One way from a seed, as traceHalf, with the heading carried from step to step: each step follows the
// representative closest to it. A turn by most of π/N in one step means the line is at a singularity (or
// runs into converging lines across an edge): it stops there rather than jump to another direction.
function traceHalfN(surface, field, face, p, heading, sign, { h, dTest, dSep, grid, id, N, turnCos, familyCos }) {
  const samples = [];
  let f = face, pos = p, length = 0, dir = heading;
  for (let n = 0; n < MAX_POINTS_PER_LINE; n++) {
    const d1 = along(surface, field, f, pos, dir, N);
    if (!d1) break;
    const d2 = along(surface, field, f, [pos[0] + (h * d1[0]) / 2, pos[1] + (h * d1[1]) / 2], d1, N);
    if (!d2 || d1[0] * d2[0] + d1[1] * d2[1] < turnCos) break;
    const w = surface.walk(f, pos, d2, h);
    if (w.travelled < 1e-6 * h) break;
    const nextDir = along(surface, field, w.face, w.p, w.dir, N);
    if (!nextDir || nextDir[0] * w.dir[0] + nextDir[1] * w.dir[1] < turnCos) break;
    const x = surface.to3d(w.face, w.p), nrm = surface.normal(w.face), t = surface.vec3d(w.face, nextDir);
    if (grid.near(x, nrm, dTest, id, sign * (length + w.travelled), 2 * dSep, t, familyCos)) break;
    f = w.face;
    pos = w.p;
    dir = nextDir;
    length += w.travelled;
    samples.push({ face: f, p: pos, dir: nextDir });
    grid.add(x, nrm, id, sign * length, t);
    if (w.hitBoundary) break;
  }
  return { samples, length };
}

// One direction (sign ±1) from a seed: RK2 steps of arc length h, stopping at boundaries, where the field
// vanishes or turns back (a singularity), or within d_test of another line or of its own earlier part.
function traceHalf(surface, field, face, p, sign, { h, dTest, dSep, grid, id }) {
  const samples = [];
  let f = face, pos = p, length = 0;
  for (let n = 0; n < MAX_POINTS_PER_LINE; n++) {
    const d1 = direction(surface, field, f, pos);
    if (!d1) break;
    const mid = [pos[0] + (sign * h * d1[0]) / 2, pos[1] + (sign * h * d1[1]) / 2];
    const d2 = direction(surface, field, f, mid);
    if (!d2 || d1[0] * d2[0] + d1[1] * d2[1] < 0.5) break; // a sharp turn inside one step: a singularity
    const w = surface.walk(f, pos, [sign * d2[0], sign * d2[1]], h);
    if (w.travelled < 1e-6 * h) break;
    const nextDir = direction(surface, field, w.face, w.p);
    if (!nextDir) break;
    // Across an edge the field may point back into the face we came from (converging flow): stop there.
    if (w.face !== f && sign * (nextDir[0] * w.dir[0] + nextDir[1] * w.dir[1]) < 0) break;
    const x = surface.to3d(w.face, w.p);
    const nrm = surface.normal(w.face);
    // Own points count only once far enough away along the line that they are not its immediate past.
    if (grid.near(x, nrm, dTest, id, sign * (length + w.travelled), 2 * dSep)) break;
    f = w.face;
    pos = w.p;
    length += w.travelled;
    samples.push({ face: f, p: pos, dir: nextDir });
    grid.add(x, nrm, id, sign * length);
    if (w.hitBoundary) break;
  }
  return { samples, length };
}

// Uniform hash grid of line points with the face normal at each, for "is there a line point within r", and
// the line's direction there (N-fields: only lines of one family keep their distance).
const STRIDE = 11;
class PointGrid {
  constructor(cell) {
    this.cell = cell;
    this.cells = new Map();
    this.dead = new Set();
  }

  #key(ix, iy, iz) {
    return ((ix * 73856093) ^ (iy * 19349663) ^ (iz * 83492791)) | 0;
  }

  add(x, n, id, arc, t = ZERO) {
    const c = this.cell;
    const key = this.#key(Math.floor(x[0] / c), Math.floor(x[1] / c), Math.floor(x[2] / c));
    let list = this.cells.get(key);
    if (!list) this.cells.set(key, (list = []));
    list.push(x[0], x[1], x[2], n[0], n[1], n[2], id, arc, t[0], t[1], t[2]);
  }

  kill(id) {
    this.dead.add(id);
  }

  // Any point within r of x (r ≤ cell size) whose normal agrees with n; points of line `self` count only
  // when their arc length differs from `arc` by more than `arcGap`. With a direction t and familyCos > −1,
  // only points whose line runs within that of t (as unoriented lines) count.
  near(x, n, r, self, arc, arcGap, t = null, familyCos = -1) {
    const c = this.cell;
    const ix = Math.floor(x[0] / c), iy = Math.floor(x[1] / c), iz = Math.floor(x[2] / c);
    const r2 = r * r;
    for (let dx = -1; dx <= 1; dx++) {
      for (let dy = -1; dy <= 1; dy++) {
        for (let dz = -1; dz <= 1; dz++) {
          const list = this.cells.get(this.#key(ix + dx, iy + dy, iz + dz));
          if (!list) continue;
          for (let k = 0; k < list.length; k += STRIDE) {
            const id = list[k + 6];
            if (id === self ? Math.abs(list[k + 7] - arc) <= arcGap : this.dead.has(id)) continue;
            const ex = list[k] - x[0], ey = list[k + 1] - x[1], ez = list[k + 2] - x[2];
            if (ex * ex + ey * ey + ez * ez >= r2) continue;
            if (
              t &&
              familyCos > -1 &&
              Math.abs(list[k + 8] * t[0] + list[k + 9] * t[1] + list[k + 10] * t[2]) < familyCos
            )
              continue;
            if (list[k + 3] * n[0] + list[k + 4] * n[1] + list[k + 5] * n[2] > 0) return true;
          }
        }
      }
    }
    return false;
  }
}

// Main-thread geometry and topology of the core's welded mesh, for drawing and for tracing on the surface.
// Face f here is face f of the core; local edge k of a face runs from corner k to corner k+1. Normals, areas
// and the edge→face maps come from mesh-geometry.js.
import { angleDefects, faceNormals, halfEdgeNeighbours, vertexFaceMap, vertexNormals } from './mesh-geometry.js';
import { edgeRows } from './whitney-corners.js';

export class Surface {
  // positions: Float64Array (3 per vertex), triangles: Int32Array (3 per face), edges: Int32Array (2 per edge,
  // the core's canonical order, lower index first).
  // derived: the other arrays of arrays() when another thread already built them (fromArrays()).
  constructor(positions, triangles, edges, derived = null) {
    this.positions = positions;
    this.triangles = triangles;
    this.edges = edges;
    this.nV = positions.length / 3;
    this.nF = triangles.length / 3;
    this.angleDefect = null;
    if (derived) return void Object.assign(this, derived);
    this.#geometry();
    this.vertexNormals = vertexNormals(this.positions, this.triangles); // for lifting markers off the surface
  }

  // The faces' unit normals (tracing, singularities, N-fields), likewise: normal(f) needs none of them.
  #normals = null;
  get normals() {
    this.#normals ??= faceNormals(this.positions, this.triangles);
    return this.#normals;
  }
  set normals(a) {
    this.#normals = a;
  }

  // The edges by their lower vertex (whitney-corners.js edgeRows), built on first use: a vector field's texture
  // reads its 1-form along each face's edges (armadillo-sub2's 1.25M edges: 42-77 ms, node).
  #edgeRows = null;
  get edgeRows() {
    this.#edgeRows ??= edgeRows(this.edges, this.nV);
    return this.#edgeRows;
  }

  // The adjacency (tracing, singularities, N-field combing, texture seams): neighbour, vertexFaceStart and
  // vertexFaces, built on first use, or taken from another thread (a big model's page surface comes without
  // them and receives them, with the picking BVH, after its first field: adoptPicking).
  #adjacent = {};

  // A big model's picking part, built in the worker after the surface was sent (mesh-bvh-transfer.js
  // pickingParts): the adjacency, the face normals, and the serialized BVH the viewer adopts at its first pick.
  adoptPicking({ neighbour, vertexFaceStart, vertexFaces, normals, bvh }) {
    Object.assign(this, { neighbour, vertexFaceStart, vertexFaces, normals, bvh });
    this.pickingFollows = false;
  }

  #geometry() {
    const P = this.positions, T = this.triangles, nF = this.nF;
    const A = (this.areas = new Float64Array(nF));
    // Each face's 2D frame (origin at corner 0, x along edge 0→1, y = n × x) is made when asked for (#frame):
    // two arrays of 6 doubles per face were 80 MB at 832k faces, whose first writes alone took the worker
    // ~0.35 s on the way to a big model's first field (this VM's page faults: ~4 ms per fresh MB).
    let edgeSum = 0;
    const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
    for (let v = 0; v < this.nV; v++) {
      for (let k = 0; k < 3; k++) {
        lo[k] = Math.min(lo[k], P[3 * v + k]);
        hi[k] = Math.max(hi[k], P[3 * v + k]);
      }
    }
    for (let f = 0; f < nF; f++) {
      const a = 3 * T[3 * f], b = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
      const ux = P[b] - P[a], uy = P[b + 1] - P[a + 1], uz = P[b + 2] - P[a + 2];
      const wx = P[c] - P[a], wy = P[c + 1] - P[a + 1], wz = P[c + 2] - P[a + 2];
      const vx = P[c] - P[b], vy = P[c + 1] - P[b + 1], vz = P[c + 2] - P[b + 2];
      edgeSum +=
        Math.sqrt(ux * ux + uy * uy + uz * uz) +
        Math.sqrt(wx * wx + wy * wy + wz * wz) +
        Math.sqrt(vx * vx + vy * vy + vz * vz);
      const nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
      A[f] = Math.sqrt(nx * nx + ny * ny + nz * nz) / 2;
    }
    this.meanEdge = nF ? edgeSum / (3 * nF) : 1;
    // Running sums of the face areas: the arrows draw faces by area (arrow-sampling.js), after every zoom.
    const cdf = (this.areaCdf = new Float64Array(nF));
    let area = 0;
    for (let f = 0; f < nF; f++) cdf[f] = area += A[f];
    this.area = area;
    this.centre = lo.map((x, k) => (x + hi[k]) / 2);
    this.radius = Math.max(1e-12, Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) / 2);
  }

  #adjacency() {
    const a = this.#adjacent;
    a.neighbour = halfEdgeNeighbours(this.triangles, this.nV);
    ({ start: a.vertexFaceStart, faces: a.vertexFaces } = vertexFaceMap(this.triangles, this.nV));
  }

  // The per-mesh arrays, copied (the caller keeps its own Surface): the worker builds the Surface once per mesh
  // and the page takes it over with fromArrays(), so the main thread never recomputes it.
  arrays() {
    const out = { meanEdge: this.meanEdge, centre: this.centre, radius: this.radius, area: this.area };
    for (const key of Surface.ARRAYS) out[key] = this[key].slice();
    return out;
  }

  static ARRAYS = [
    'positions',
    'triangles',
    'edges',
    'normals',
    'areas',
    'neighbour',
    'vertexFaceStart',
    'vertexFaces',
    'vertexNormals',
    'areaCdf',
  ];
  static ADJACENCY = ['neighbour', 'vertexFaceStart', 'vertexFaces'];
  // What a big model's surface sends after its first field (mesh-bvh-transfer.js pickingParts).
  static PICKING = [...Surface.ADJACENCY, 'normals'];
  // The adjacency's accessors (#adjacent above).
  static {
    for (const key of Surface.ADJACENCY)
      Object.defineProperty(Surface.prototype, key, {
        get() {
          if (!this.#adjacent[key]) this.#adjacency();
          return this.#adjacent[key];
        },
        set(array) {
          this.#adjacent[key] = array;
        },
      });
  }


  static fromArrays({ positions, triangles, edges, ...derived }) {
    return new Surface(positions, triangles, edges, derived);
  }


  // 2π less the corner angles per vertex; computed on first use (the singularities need it).
  angleDefects() {
    this.angleDefect ??= angleDefects(this.positions, this.triangles, this.nV);
    return this.angleDefect;
  }

  vertex(v) {
    const P = this.positions;
    return [P[3 * v], P[3 * v + 1], P[3 * v + 2]];
  }

  normal(f) {
    return this.normalInto(f, [0, 0, 0]);
  }

  // normal(f) written into out, allocating nothing (the arrows ask for thousands per field).
  normalInto(f, out) {
    const N = this.#normals;
    if (N) {
      out[0] = N[3 * f];
      out[1] = N[3 * f + 1];
      out[2] = N[3 * f + 2];
      return out;
    }
    const P = this.positions, T = this.triangles, a = 3 * T[3 * f], b = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
    const ux = P[b] - P[a], uy = P[b + 1] - P[a + 1], uz = P[b + 2] - P[a + 2];
    const wx = P[c] - P[a], wy = P[c + 1] - P[a + 1], wz = P[c + 2] - P[a + 2];
    const nx = uy * wz - uz * wy, ny = uz * wx - ux * wz, nz = ux * wy - uy * wx;
    const l = Math.sqrt(nx * nx + ny * ny + nz * nz);
    if (l > 0) {
      out[0] = nx / l;
      out[1] = ny / l;
      out[2] = nz / l;
    } else {
      out[0] = 0;
      out[1] = 0;
      out[2] = 1;
    }
    return out;
  }

  centroid(f) {
    const P = this.positions, T = this.triangles, a = 3 * T[3 * f], b = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
    return [(P[a] + P[b] + P[c]) / 3, (P[a + 1] + P[b + 1] + P[c + 1]) / 3, (P[a + 2] + P[b + 2] + P[c + 2]) / 3];
  }

  facesAround(v) {
    return this.vertexFaces.subarray(this.vertexFaceStart[v], this.vertexFaceStart[v + 1]);
  }

  pointFromBary(f, [u, v, w]) {
    const P = this.positions, T = this.triangles;
    const a = 3 * T[3 * f], b = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
    return [0, 1, 2].map((k) => u * P[a + k] + v * P[b + k] + w * P[c + k]);
  }

  // Face f's frame: e1 (unit, along edge 0→1) and e2 = n × e1 into F[0..5], and its corners' 2D coordinates
  // (0, 0), (bx, 0), (cx, cy) as [bx, cx, cy] into C (scratch arrays, read at once by the callers).
  #frame(f) {
    const P = this.positions, T = this.triangles, N = this.normals;
    const F = (this.frameScratch ??= new Float64Array(6)), C = (this.cornerScratch ??= new Float64Array(3));
    // A walk asks for the same face's frame several times in a row (to2d, then bary2d twice per step).
    if (this.frameFace === f) return F;
    this.frameFace = f;
    const a = 3 * T[3 * f], b = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
    const ux = P[b] - P[a], uy = P[b + 1] - P[a + 1], uz = P[b + 2] - P[a + 2];
    const wx = P[c] - P[a], wy = P[c + 1] - P[a + 1], wz = P[c + 2] - P[a + 2];
    const lu = Math.sqrt(ux * ux + uy * uy + uz * uz);
    const nx = N[3 * f], ny = N[3 * f + 1], nz = N[3 * f + 2];
    const ex = lu > 0 ? ux / lu : 1, ey = lu > 0 ? uy / lu : 0, ez = lu > 0 ? uz / lu : 0;
    const fx = ny * ez - nz * ey, fy = nz * ex - nx * ez, fz = nx * ey - ny * ex;
    F[0] = ex;
    F[1] = ey;
    F[2] = ez;
    F[3] = fx;
    F[4] = fy;
    F[5] = fz;
    C[0] = lu;
    C[1] = wx * ex + wy * ey + wz * ez;
    C[2] = wx * fx + wy * fy + wz * fz;
    return F;
  }

  // 3D point → 2D in face f's frame (no projection check: the caller knows the point is in the plane).
  to2d(f, p) {
    const a = this.vertex(this.triangles[3 * f]);
    const F = this.#frame(f);
    const d = [p[0] - a[0], p[1] - a[1], p[2] - a[2]];
    return [d[0] * F[0] + d[1] * F[1] + d[2] * F[2], d[0] * F[3] + d[1] * F[4] + d[2] * F[5]];
  }

  to3d(f, [x, y]) {
    const a = this.vertex(this.triangles[3 * f]);
    const F = this.#frame(f);
    return [0, 1, 2].map((k) => a[k] + x * F[k] + y * F[3 + k]);
  }

  // 3D vector → 2D components in face f's frame (drops the normal part).
  vec2d(f, v) {
    const F = this.#frame(f);
    return [v[0] * F[0] + v[1] * F[1] + v[2] * F[2], v[0] * F[3] + v[1] * F[4] + v[2] * F[5]];
  }

  vec3d(f, [x, y]) {
    const F = this.#frame(f);
    return [0, 1, 2].map((k) => x * F[k] + y * F[3 + k]);
  }

  // Barycentric coordinates of a 2D point in face f's frame (any point of the plane; may be negative).
  bary2d(f, [x, y]) {
    this.#frame(f);
    const [bx, cx, cy] = this.cornerScratch;
    // Corner 0 at the origin, corner 1 on the x axis: solve p = v·B + w·C directly.
    const w = cy !== 0 ? y / cy : 0;
    const v = bx !== 0 ? (x - w * cx) / bx : 0;
    return [1 - v - w, v, w];
  }

  // Barycentric coordinates of a 3D point (projected into face f's plane), clamped into the face.
  baryOf(f, p) {
    const b = this.bary2d(f, this.to2d(f, p)).map((x) => Math.max(0, x));
    const s = b[0] + b[1] + b[2] || 1;
    return b.map((x) => x / s);
  }

  // Corner of face f nearest to the 3D point p.
  nearestCorner(f, p) {
    let best = -1, bestD = Infinity;
    for (let k = 0; k < 3; k++) {
      const v = this.triangles[3 * f + k];
      const q = this.vertex(v);
      const d = Math.hypot(q[0] - p[0], q[1] - p[1], q[2] - p[2]);
      if (d < bestD) {
        bestD = d;
        best = v;
      }
    }
    return best;
  }

  // Walks straight along the surface from 2D point p of face f in direction dir (2D, unit), for `length`,
  // unfolding the direction across edges. Returns {face, p, dir, hitBoundary, travelled}.
  walk(f, p, dir, length, maxCrossings = 64) {
    let face = f, pos = p, d = dir, left = length;
    for (let n = 0; n < maxCrossings; n++) {
      const exit = this.exitOf(face, pos, [d[0] * left, d[1] * left]);
      if (!exit)
        return { face, p: [pos[0] + d[0] * left, pos[1] + d[1] * left], dir: d, hitBoundary: false, travelled: length };
      const q = [pos[0] + d[0] * left * exit.t, pos[1] + d[1] * left * exit.t];
      left *= 1 - exit.t;
      const next = this.cross(face, exit.edge, q, d);
      if (!next) return { face, p: q, dir: d, hitBoundary: true, travelled: length - left };
      ({ face, p: pos, dir: d } = next);
    }
    return { face, p: pos, dir: d, hitBoundary: true, travelled: length - left };
  }

  // Where the 2D segment p → p + step leaves face f: {t ∈ [0, 1), edge k} or null if it stays inside.
  exitOf(f, p, step) {
    const b0 = this.bary2d(f, p);
    const b1 = this.bary2d(f, [p[0] + step[0], p[1] + step[1]]);
    let tMin = 1, edge = -1;
    for (let k = 0; k < 3; k++) {
      const db = b1[k] - b0[k];
      if (b1[k] < 0 && db < 0) {
        // Barycentric k vanishes on the edge opposite corner k, which is local edge k+1.
        const t = Math.max(0, b0[k] / -db);
        if (t < tMin) {
          tMin = t;
          edge = (k + 1) % 3;
        }
      }
    }
    return edge < 0 ? null : { t: tMin, edge };
  }

  // Carries a point on local edge k of face f, and a 2D direction, into the neighbouring face by unfolding
  // about the shared edge. Returns {face, p, dir} or null on a boundary edge.
  cross(f, k, p, dir) {
    const nb = this.neighbour[3 * f + k];
    if (nb < 0) return null;
    const g = Math.floor(nb / 3);
    const [c, s, tx, ty] = this.#unfolding(f, k);
    const dg = [c * dir[0] - s * dir[1], s * dir[0] + c * dir[1]];
    const l = Math.hypot(dg[0], dg[1]) || 1;
    dg[0] /= l;
    dg[1] /= l;
    // Nudge off the shared edge into g so the next exit test does not see the point as already outside.
    const eps = 1e-9 * this.meanEdge;
    const q = [c * p[0] - s * p[1] + tx + dg[0] * eps, s * p[0] + c * p[1] + ty + dg[1] * eps];
    return { face: g, p: q, dir: dg };
  }

  // Unfolding across local edge k of face f is a rigid motion from f's 2D frame to the neighbour's, fixed by
  // the shared edge (its ends i, j have coordinates in both frames): rotation (c, s), then shift (tx, ty).
  // Cached per half-edge: streamlines cross edges constantly.
  #unfolding(f, k) {
    this.unfold ??= new Float64Array(12 * this.nF).fill(NaN);
    const o = 12 * f + 4 * k;
    if (!Number.isNaN(this.unfold[o])) return this.unfold.subarray(o, o + 4);
    const g = Math.floor(this.neighbour[3 * f + k] / 3);
    const T = this.triangles;
    const i = this.vertex(T[3 * f + k]), j = this.vertex(T[3 * f + ((k + 1) % 3)]);
    const [ifx, ify] = this.to2d(f, i), [jfx, jfy] = this.to2d(f, j);
    const [igx, igy] = this.to2d(g, i), [jgx, jgy] = this.to2d(g, j);
    const ef = [jfx - ifx, jfy - ify], eg = [jgx - igx, jgy - igy];
    const l2 = ef[0] * ef[0] + ef[1] * ef[1] || 1;
    const c = (ef[0] * eg[0] + ef[1] * eg[1]) / l2;
    const s = (ef[0] * eg[1] - ef[1] * eg[0]) / l2;
    const tx = igx - (c * ifx - s * ify), ty = igy - (s * ifx + c * ify);
    this.unfold.set([c, s, tx, ty], o);
    return this.unfold.subarray(o, o + 4);
  }
}

export function dot(a, b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

export function cross(a, b) {
  return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
}

// A deterministic permutation of 0..n-1 (a fixed-seed shuffle): seeds and arrow samples taken in this order
// spread over the whole model instead of sweeping it in face order.
export function scrambled(n) {
  const order = Int32Array.from({ length: n }, (_, i) => i);
  let s = 0x9e3779b9;
  for (let i = n - 1; i > 0; i--) {
    s = (Math.imul(s, 1664525) + 1013904223) >>> 0;
    const j = s % (i + 1);
    [order[i], order[j]] = [order[j], order[i]];
  }
  return order;
}

// An N-field (N ≥ 2: line or cross field) combed for a texture atlas: a per-corner field whose representatives
// agree wherever they can, so that a texture synthesized along "the representative" (which needs a sign, or for
// a cross field one of its families) follows one choice over whole regions. The unavoidable flips (cuts that end
// at the ±1/N singularities) are put where the field turns most and, where possible, along the atlas's chart
// seams: the choice spreads over a spanning tree of the faces grown best-aligned first (Prim over the face
// adjacency, the cost of an edge the angle between its two faces' directions mod 2π/N), every edge inside a chart
// cheaper than every seam edge, so each chart is combed whole before the tree crosses a seam.
import { matchedCorners, rotateAbout } from './nfield.js';

const TWO_PI = 2 * Math.PI;
const STEP = 8192; // faces combed between two yields of combForAtlasSteps

// Per face, one direction of the N-field from the three vertex representatives: their N-th powers averaged in
// the face's frame (symmetric in the three, whatever rotation each came with), as a unit vector in the face's
// plane. Faces whose corners cancel keep corner 0. Float64Array(3 · nF).
export function faceDirections(surface, vertexVectors, N) {
  const { triangles: T, normals: Nm, positions: P, nF } = surface, V = vertexVectors;
  const out = new Float64Array(3 * nF);
  // Math.sqrt, not Math.hypot, and no arrays per face: this runs at every line or cross field's texture update
  // (bunny00: 50 -> 12 ms, node).
  for (let f = 0; f < nF; f++) {
    const nx = Nm[3 * f], ny = Nm[3 * f + 1], nz = Nm[3 * f + 2];
    const a = 3 * T[3 * f], b = 3 * T[3 * f + 1];
    let ax = P[b] - P[a], ay = P[b + 1] - P[a + 1], az = P[b + 2] - P[a + 2];
    const l = Math.sqrt(ax * ax + ay * ay + az * az) || 1;
    ax /= l;
    ay /= l;
    az /= l;
    const bx = ny * az - nz * ay, by = nz * ax - nx * az, bz = nx * ay - ny * ax;
    let re = 0, im = 0, first = null;
    for (let k = 0; k < 3; k++) {
      const v = 3 * T[3 * f + k];
      const x = V[v] * ax + V[v + 1] * ay + V[v + 2] * az;
      const y = V[v] * bx + V[v + 1] * by + V[v + 2] * bz;
      const th = Math.atan2(y, x);
      first ??= th;
      re += Math.cos(N * th);
      im += Math.sin(N * th);
    }
    const th = Math.sqrt(re * re + im * im) > 1e-9 ? Math.atan2(im, re) / N : first;
    const c = Math.cos(th), s = Math.sin(th);
    out[3 * f] = c * ax + s * bx;
    out[3 * f + 1] = c * ay + s * by;
    out[3 * f + 2] = c * az + s * bz;
  }
  return out;
}

// Whether the edge between half-edge h (local edge k of face f) and its twin (local edge kk of face g) is a
// seam of the atlas: its two ends have different UVs in the two faces (cornerUVs: 6 per face).
function isSeam(cornerUVs, f, k, g, kk) {
  const U = cornerUVs;
  const fi = 6 * f + 2 * k;
  const fj = 6 * f + 2 * ((k + 1) % 3);
  const gi = 6 * g + 2 * ((kk + 1) % 3);
  const gj = 6 * g + 2 * kk;
  const d2 = (p, q) => (U[p] - U[q]) ** 2 + (U[p + 1] - U[q + 1]) ** 2;
  return d2(fi, gi) >= 1e-14 || d2(fj, gj) >= 1e-14;
}

// Binary min-heap of (cost, item) pairs in typed arrays of a fixed capacity.
class MinHeap {
  constructor(capacity) {
    this.cost = new Float64Array(capacity);
    this.item = new Int32Array(capacity);
    this.size = 0;
  }
  push(c, x) {
    const C = this.cost, I = this.item;
    let i = this.size++;
    while (i > 0) {
      const p = (i - 1) >> 1;
      if (C[p] <= c) break;
      C[i] = C[p];
      I[i] = I[p];
      i = p;
    }
    C[i] = c;
    I[i] = x;
  }
  pop() {
    const C = this.cost, I = this.item, top = I[0];
    const n = --this.size, c = C[n], x = I[n];
    if (n) {
      let i = 0;
      for (;;) {
        let m = 2 * i + 1;
        if (m >= n) break;
        if (m + 1 < n && C[m + 1] < C[m]) m++;
        if (C[m] >= c) break;
        C[i] = C[m];
        I[i] = I[m];
        i = m;
      }
      C[i] = c;
      I[i] = x;
    }
    return top;
  }
}

// Per connected component of faces (across the half-edge map), its largest face (the lowest index among equals):
// the roots the comb grows from, in no particular order.
function componentRoots(neighbour, areas, nF) {
  const seen = new Uint8Array(nF), stack = new Int32Array(nF), roots = [];
  for (let start = 0; start < nF; start++) {
    if (seen[start]) continue;
    seen[start] = 1;
    let top = 0, best = start;
    stack[top++] = start;
    while (top) {
      const f = stack[--top];
      if (areas && (areas[f] > areas[best] || (areas[f] === areas[best] && f < best))) best = f;
      for (let k = 0; k < 3; k++) {
        const h = neighbour[3 * f + k];
        if (h < 0 || seen[(h / 3) | 0]) continue;
        seen[(h / 3) | 0] = 1;
        stack[top++] = (h / 3) | 0;
      }
    }
    roots.push(areas ? best : start);
  }
  return roots;
}

// The angle in [0, π/N] between two tangent directions u (at ui in U) and w (at wi in W) of the face with unit
// normal n (at ni in Nm), as N-directions.
function misalignment(U, ui, W, wi, Nm, ni, N) {
  const ux = U[ui], uy = U[ui + 1], uz = U[ui + 2], wx = W[wi], wy = W[wi + 1], wz = W[wi + 2];
  const sin = (uy * wz - uz * wy) * Nm[ni] + (uz * wx - ux * wz) * Nm[ni + 1] + (ux * wy - uy * wx) * Nm[ni + 2];
  const r = (Math.abs(Math.atan2(sin, ux * wx + uy * wy + uz * wz)) * N) % TWO_PI;
  return Math.min(r, TWO_PI - r) / N;
}

// Face directions (3 per face, unit, in the faces' planes) turned by multiples of 2π/N to agree across a spanning
// tree of the faces grown cheapest edge first from the largest face of each connected component. An edge costs
// the angle between its faces' directions (mod 2π/N, after transport across it), plus π where cornerUVs (6 per
// face, optional) put a seam on it. Returns {faces: Float64Array(3 · nF), flips: the edges (as [f, g]) across
// which the combed directions still disagree by more than π/2N, i.e. the cuts}. combForAtlasSteps yields every
// STEP faces combed (a caller may give the page its frames there: bunny00's 75k faces took 125 ms, node).
export function combForAtlas(surface, faceDirs, N, cornerUVs = null) {
  return drain(combForAtlasSteps(surface, faceDirs, N, cornerUVs));
}

export function* combForAtlasSteps(surface, faceDirs, N, cornerUVs = null) {
  const out = Float64Array.from(faceDirs);
  const { triangles: T, normals: Nm, positions: P, neighbour, areas, nF } = surface;
  const seen = new Uint8Array(nF);
  const c = new Float64Array(3); // face f's direction carried into g
  // Face f's current direction carried across its local edge k into face g (into c): the rotation about the
  // edge that unfolds f onto g's plane: the discrete parallel transport.
  const carry = (f, k, g) => {
    const a = 3 * T[3 * f + k], b = 3 * T[3 * f + ((k + 1) % 3)];
    let ex = P[b] - P[a], ey = P[b + 1] - P[a + 1], ez = P[b + 2] - P[a + 2];
    const l = Math.sqrt(ex * ex + ey * ey + ez * ez) || 1;
    ex /= l;
    ey /= l;
    ez /= l;
    const ux = out[3 * f], uy = out[3 * f + 1], uz = out[3 * f + 2];
    const fx = Nm[3 * f];
    const fy = Nm[3 * f + 1];
    const fz = Nm[3 * f + 2];
    const gx = Nm[3 * g];
    const gy = Nm[3 * g + 1];
    const gz = Nm[3 * g + 2];
    const along = ux * ex + uy * ey + uz * ez;
    const across = ux * (fy * ez - fz * ey) + uy * (fz * ex - fx * ez) + uz * (fx * ey - fy * ex);
    c[0] = along * ex + across * (gy * ez - gz * ey);
    c[1] = along * ey + across * (gz * ex - gx * ez);
    c[2] = along * ez + across * (gx * ey - gy * ex);
    return c;
  };
  const heap = new MinHeap(3 * nF);
  const push = (f) => {
    for (let k = 0; k < 3; k++) {
      const h = neighbour[3 * f + k];
      if (h < 0) continue;
      const g = (h / 3) | 0;
      if (seen[g]) continue;
      const seam = cornerUVs ? isSeam(cornerUVs, f, k, g, h % 3) : false;
      heap.push(misalignment(carry(f, k, g), 0, out, 3 * g, Nm, 3 * g, N) + (seam ? Math.PI : 0), 3 * f + k);
    }
  };
  // Face g's direction turned by the multiple of 2π/N closest to d (carried into it), in place.
  const turnToward = (g, d) => {
    const u = 3 * g, nx = Nm[u], ny = Nm[u + 1], nz = Nm[u + 2], vx = out[u], vy = out[u + 1], vz = out[u + 2];
    const sin = (vy * d[2] - vz * d[1]) * nx + (vz * d[0] - vx * d[2]) * ny + (vx * d[1] - vy * d[0]) * nz;
    const k = Math.round((N * Math.atan2(sin, vx * d[0] + vy * d[1] + vz * d[2])) / TWO_PI);
    if (k !== 0) out.set(rotateAbout([vx, vy, vz], [nx, ny, nz], (TWO_PI * k) / N), u);
  };
  // Prim's tree grown by up to `count` faces; whether faces are left in the heap.
  const grow = (count) => {
    for (let n = 0; heap.size && n < count; ) {
      const h = heap.pop();
      const f = (h / 3) | 0, k = h % 3, g = (neighbour[h] / 3) | 0;
      if (seen[g]) continue;
      seen[g] = 1;
      n++;
      turnToward(g, carry(f, k, g));
      push(g);
    }
    return heap.size > 0;
  };
  for (const root of componentRoots(neighbour, areas, nF)) {
    seen[root] = 1;
    push(root);
    while (grow(STEP)) yield;
  }
  const flips = [];
  const limit = Math.PI / (2 * N);
  for (let h = 0; h < 3 * nF; h++) {
    const o = neighbour[h];
    if (o < h) continue;
    const f = (h / 3) | 0, g = (o / 3) | 0;
    carry(f, h % 3, g);
    const u = 3 * g, cos = c[0] * out[u] + c[1] * out[u + 1] + c[2] * out[u + 2];
    const sin =
      (c[1] * out[u + 2] - c[2] * out[u + 1]) * Nm[u] +
      (c[2] * out[u] - c[0] * out[u + 2]) * Nm[u + 1] +
      (c[0] * out[u + 1] - c[1] * out[u]) * Nm[u + 2];
    if (Math.abs(Math.atan2(sin, cos)) > limit) flips.push([f, g]);
  }
  return { faces: out, flips };
}

// The per-corner field a texture follows (9 per face, corner k of face f at 9f + 3k, in the face's plane): each
// vertex representative turned to the rotation closest to its face's combed direction. faceVectors: the field's
// own face representatives (3 per face) or null (then made from the vertex ones); cornerUVs: the atlas (6 per
// face) whose seams the cuts should follow, or null. Also returns the combed face directions and the cut edges.
export function atlasCombedCorners(surface, vertexVectors, faceVectors, N, cornerUVs = null) {
  return drain(atlasCombedCornersSteps(surface, vertexVectors, faceVectors, N, cornerUVs));
}

// The same a step at a time (combForAtlasSteps).
export function* atlasCombedCornersSteps(surface, vertexVectors, faceVectors, N, cornerUVs = null) {
  const dirs = faceVectors ? projected(surface, faceVectors) : faceDirections(surface, vertexVectors, N);
  yield;
  const { faces, flips } = yield* combForAtlasSteps(surface, dirs, N, cornerUVs);
  return { corners: matchedCorners(surface, vertexVectors, faces, N), faces, flips };
}

// A generator run to its end: its value.
function drain(steps) {
  for (;;) {
    const r = steps.next();
    if (r.done) return r.value;
  }
}

// Face vectors projected into their faces' planes and normalised (zero ones stay zero).
function projected(surface, F) {
  const { normals: Nm, nF } = surface;
  const out = new Float64Array(3 * nF);
  for (let f = 0; f < nF; f++) {
    const n = [Nm[3 * f], Nm[3 * f + 1], Nm[3 * f + 2]];
    const d = F[3 * f] * n[0] + F[3 * f + 1] * n[1] + F[3 * f + 2] * n[2];
    const t = [F[3 * f] - d * n[0], F[3 * f + 1] - d * n[1], F[3 * f + 2] - d * n[2]];
    const l = Math.hypot(t[0], t[1], t[2]);
    if (l > 0) out.set(t.map((x) => x / l), 3 * f);
  }
  return out;
}

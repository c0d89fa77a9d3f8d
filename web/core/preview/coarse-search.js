// The closest-point search on the coarse surface of a big mesh's preview (coarse-mesh.js), for the map from the
// fine surface onto it (surface-map.js). The closest point is searched near where it must be: the coarse vertices
// are fine vertices, so a breadth-first search over the fine faces' sides from all of them names, for each fine
// vertex, the nearest kept vertex, whose coarse faces are the candidates (a collapse moves a vertex by about one
// coarse edge).
//
// Owns the coarse faces around each coarse vertex, the nearest kept vertex of each fine one and the lists the
// searches reuse; imports closest-point.js.
import { closestOnTriangle } from './closest-point.js';

export class CoarseSearch {
  // fine: {positions, triangles} (Float64Array, Int32Array); coarse: {positions, triangles, fineVertex}
  // (coarse-mesh.js); nearest: the nearest kept vertices found for this mesh before, or undefined.
  constructor(fine, coarse, nearest) {
    this.fine = fine;
    this.coarse = coarse;
    this.#coarseFacesAround();
    this.nearest = nearest ?? nearestKeptVertex(fine.triangles, fine.positions.length / 3, coarse.fineVertex);
    this.stamp = new Int32Array(coarse.triangles.length / 3).fill(-1);
    this.query = -1; // stamps of the queries (candidatesNear) count down from here, below every face index
    // Reused lists and coordinates: the searches run a few million times per model, and an array per call
    // cost about a second of garbage collection at 800k faces.
    this.scratch = [];
    this.descent = [];
    this.b3 = [0, 0, 0];
  }

  #coarseFacesAround() {
    const { triangles } = this.coarse;
    const nC = this.coarse.positions.length / 3;
    const start = new Int32Array(nC + 1);
    for (const v of triangles) start[v + 1]++;
    for (let v = 0; v < nC; v++) start[v + 1] += start[v];
    const list = new Int32Array(triangles.length);
    const fill = start.slice(0, nC);
    for (let k = 0; k < triangles.length; k++) list[fill[triangles[k]]++] = Math.floor(k / 3);
    this.aroundStart = start;
    this.aroundList = list;
  }

  // The coarse faces around coarse vertex c appended to `out` (a plain array, cleared first when `clear`).
  #aroundInto(c, out, clear = true) {
    if (clear) out.length = 0;
    for (let k = this.aroundStart[c], end = this.aroundStart[c + 1]; k < end; k++) out.push(this.aroundList[k]);
    return out;
  }

  // The coarse faces around fine vertex v's nearest kept vertex, in the list the next search reuses.
  aroundFineVertex(v) {
    return this.#aroundInto(this.nearest[v], this.scratch);
  }

  // The coarse faces of fine face f's corners (each once; vertexFace: the fine vertices' coarse faces), in the
  // list the next search reuses.
  facesOfCorners(f, vertexFace) {
    const T = this.fine.triangles;
    const candidates = this.scratch;
    candidates.length = 0;
    for (let k = 0; k < 3; k++) {
      const c = vertexFace[T[3 * f + k]];
      if (!candidates.includes(c)) candidates.push(c);
    }
    return candidates;
  }

  // The coarse faces around the nearest kept vertex of each corner of fine face f (each once), in the list the
  // next search reuses: the face a point of f lies on is among them (with the coarse mesh equal to the fine
  // one, f itself).
  candidatesNear(f) {
    const stamp = --this.query;
    const T = this.fine.triangles;
    const out = this.scratch;
    out.length = 0;
    for (let k = 0; k < 3; k++) {
      const v = this.nearest[T[3 * f + k]];
      for (let i = this.aroundStart[v], end = this.aroundStart[v + 1]; i < end; i++) {
        const c = this.aroundList[i];
        if (this.stamp[c] === stamp) continue;
        this.stamp[c] = stamp;
        out.push(c);
      }
    }
    return out;
  }

  // The closest point of the candidate coarse faces to p, into face[slot] and bary[3 slot..].
  // The nearest kept vertex in hops need not be a corner of the face the point lies over: while the closest
  // point found is on a face's border, the faces around that face's corners are searched too (a descent that
  // stops when the best face no longer changes).
  closest(p, candidates, slot, face, bary) {
    let best = Infinity;
    const b = this.b3;
    const T = this.coarse.triangles;
    for (let round = 0; round < 8; round++) {
      const before = face[slot];
      for (let i = 0, n = candidates.length; i < n; i++) {
        const c = candidates[i];
        const d2 = closestOnTriangle(p, this.coarse.positions, T, c, b);
        if (d2 < best) {
          best = d2;
          face[slot] = c;
          bary[3 * slot] = b[0];
          bary[3 * slot + 1] = b[1];
          bary[3 * slot + 2] = b[2];
        }
      }
      if (best === Infinity) {
        face[slot] = 0;
        return;
      }
      const onBorder = bary[3 * slot] <= 0 || bary[3 * slot + 1] <= 0 || bary[3 * slot + 2] <= 0;
      if (!onBorder || (round > 0 && face[slot] === before)) return;
      const f = face[slot];
      candidates = this.#aroundInto(T[3 * f], this.descent);
      this.#aroundInto(T[3 * f + 1], candidates, false);
      this.#aroundInto(T[3 * f + 2], candidates, false);
    }
  }
}

// Coarse vertex nearest (in edge hops) to each of the nV fine vertices (fineVertex: the fine vertex of each
// coarse one); a fine component the coarse mesh lost falls back to coarse vertex 0's faces (the closest-point
// search still picks the nearest of them).
function nearestKeptVertex(T, nV, fineVertex) {
  // Neighbours through the faces' sides (each interior edge twice: no matter to a breadth-first search), so
  // that the map needs no edge list and is built while the exact core still numbers the edges.
  const deg = new Int32Array(nV + 1);
  for (let k = 0; k < T.length; k++) deg[T[k] + 1] += 2;
  for (let v = 0; v < nV; v++) deg[v + 1] += deg[v];
  const adj = new Int32Array(2 * T.length);
  const fill = deg.slice(0, nV);
  for (let k = 0; k < T.length; k++) {
    const a = T[k];
    const b = T[k - (k % 3) + ((k % 3) + 1) % 3];
    adj[fill[a]++] = b;
    adj[fill[b]++] = a;
  }
  const nearest = new Int32Array(nV).fill(-1);
  const queue = new Int32Array(nV);
  let head = 0;
  let tail = 0;
  fineVertex.forEach((v, c) => {
    nearest[v] = c;
    queue[tail++] = v;
  });
  while (head < tail) {
    const v = queue[head++];
    for (let k = deg[v]; k < deg[v + 1]; k++) {
      const w = adj[k];
      if (nearest[w] < 0) {
        nearest[w] = nearest[v];
        queue[tail++] = w;
      }
    }
  }
  for (let v = 0; v < nV; v++) if (nearest[v] < 0) nearest[v] = 0;
  return nearest;
}

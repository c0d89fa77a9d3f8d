// The correspondence between a big (fine) mesh and its coarse stand-in (coarse-mesh.js), built once per model
// in the preview worker: every fine vertex and face centre gets the closest point of the coarse surface (a
// coarse face and barycentric coordinates). Through it a design made on the fine mesh is posed on the coarse
// one (designOnCoarse, specOnCoarse) and the coarse field is carried back to every fine vertex (and face, for
// an N-field's representatives) (fieldOnFine), so the page draws a preview on the mesh it shows.
//
// The closest point is searched near where it must be: the coarse vertices are fine vertices, so a breadth-first
// search over the fine faces' sides from all of them names, for each fine vertex, the nearest kept vertex, whose
// coarse faces are the candidates (a collapse moves a vertex by about one coarse edge).
//
// Owns the maps; imports geometry/mesh-geometry.js (the fine normals).
import { faceNormals, vertexNormals } from '../../geometry/mesh-geometry.js';

export class SurfaceMap {
  // fine: {positions, triangles} (Float64Array, Int32Array); coarse: {positions, triangles, fineVertex}
  // (coarse-mesh.js).
  constructor(fine, coarse) {
    this.fine = fine;
    this.coarse = coarse;
    this.nV = fine.positions.length / 3;
    this.nF = fine.triangles.length / 3;
    this.#coarseFacesAround();
    const nearest = (this.nearest = this.#nearestKeptVertex());
    this.stamp = new Int32Array(this.coarse.triangles.length / 3).fill(-1);
    this.query = -1; // stamps of later queries (pointOnCoarse) count down from here, below every face index
    // Reused lists and coordinates: the searches run a few million times per model, and an array per call
    // cost about a second of garbage collection at 800k faces.
    this.scratch = [];
    this.descent = [];
    this.b3 = [0, 0, 0];
    this.vertexFace = new Int32Array(this.nV);
    this.vertexBary = new Float64Array(3 * this.nV);
    const p = [0, 0, 0];
    for (let v = 0; v < this.nV; v++) {
      for (let k = 0; k < 3; k++) p[k] = fine.positions[3 * v + k];
      this.#closest(p, this.#aroundInto(nearest[v], this.scratch), v, this.vertexFace, this.vertexBary);
    }
    // The face centres' closest points are found when asked for (faceOnCoarse): a vector field's preview needs
    // a few, for the constraints; all of them took 0.2 s of the first field at 832k faces.
    this.faceFace = new Int32Array(this.nF).fill(-1);
    this.faceBary = new Float64Array(3 * this.nF);
    this.allFaces = false;
    // The planes the carried field is laid into: the area-weighted vertex normals, and the fine faces' unit
    // normals when a line or cross field needs them (faceNormals()).
    this.vertexNormals = vertexNormals(fine.positions, fine.triangles);
    this.faceNormalsCache = null;
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

  // Coarse vertex nearest (in edge hops) to each fine vertex; a fine component the coarse mesh lost falls back
  // to coarse vertex 0's faces (the closest-point search still picks the nearest of them).
  #nearestKeptVertex() {
    // Neighbours through the faces' sides (each interior edge twice: no matter to a breadth-first search), so
    // that the map needs no edge list and is built while the exact core still numbers the edges.
    const T = this.fine.triangles;
    const nV = this.nV;
    const deg = new Int32Array(nV + 1);
    for (let k = 0; k < T.length; k++) deg[T[k] + 1] += 2;
    for (let v = 0; v < nV; v++) deg[v + 1] += deg[v];
    const adj = new Int32Array(2 * T.length);
    const fill = deg.slice(0, nV);
    for (let k = 0; k < T.length; k++) {
      const a = T[k], b = T[k - (k % 3) + ((k % 3) + 1) % 3];
      adj[fill[a]++] = b;
      adj[fill[b]++] = a;
    }
    const nearest = new Int32Array(nV).fill(-1);
    const queue = new Int32Array(nV);
    let head = 0, tail = 0;
    this.coarse.fineVertex.forEach((v, c) => {
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

  #fineCentre(f, out) {
    const { positions: P, triangles: T } = this.fine;
    for (let k = 0; k < 3; k++) out[k] = (P[3 * T[3 * f] + k] + P[3 * T[3 * f + 1] + k] + P[3 * T[3 * f + 2] + k]) / 3;
    return out;
  }

  // Most fine faces lie inside one coarse face, all three corners mapped there: the centre's coordinates are
  // then the mean of the corners' (the map is affine on the coarse face), no search needed.
  #insideOneFace(f) {
    const T = this.fine.triangles;
    const a = T[3 * f], b = T[3 * f + 1], c = T[3 * f + 2];
    const face = this.vertexFace[a];
    if (this.vertexFace[b] !== face || this.vertexFace[c] !== face) return false;
    this.faceFace[f] = face;
    const bary = this.vertexBary;
    for (let k = 0; k < 3; k++) this.faceBary[3 * f + k] = (bary[3 * a + k] + bary[3 * b + k] + bary[3 * c + k]) / 3;
    return true;
  }

  // A fine face across coarse faces: its centre's closest point is searched from its corners' coarse faces,
  // descending to their neighbours while it lies on a border (#closest), rather than from every face around
  // the corners' nearest kept vertices (twice the tests, for the same point).
  #closestOfCorners(f, p) {
    const T = this.fine.triangles, candidates = this.scratch;
    candidates.length = 0;
    for (let k = 0; k < 3; k++) {
      const c = this.vertexFace[T[3 * f + k]];
      if (!candidates.includes(c)) candidates.push(c);
    }
    this.#closest(p, candidates, f, this.faceFace, this.faceBary);
  }

  // The coarse faces around the nearest kept vertex of each corner of fine face f (each once): the face the
  // centre lies on is among them (with the coarse mesh equal to the fine one, f itself).
  #candidatesOfFace(f, stamp = f) {
    const T = this.fine.triangles, out = this.scratch;
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
  #closest(p, candidates, slot, face, bary) {
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
          (bary[3 * slot] = b[0]), (bary[3 * slot + 1] = b[1]), (bary[3 * slot + 2] = b[2]);
        }
      }
      if (best === Infinity) return void (face[slot] = 0);
      const onBorder = bary[3 * slot] <= 0 || bary[3 * slot + 1] <= 0 || bary[3 * slot + 2] <= 0;
      if (!onBorder || (round > 0 && face[slot] === before)) return;
      const f = face[slot];
      candidates = this.#aroundInto(T[3 * f], this.descent);
      this.#aroundInto(T[3 * f + 1], candidates, false);
      this.#aroundInto(T[3 * f + 2], candidates, false);
    }
  }

  // The coarse face under fine face f's centre (its coordinates in faceBary[3f..]), found the first time.
  faceOnCoarse(f) {
    if (this.faceFace[f] < 0 && !this.#insideOneFace(f)) this.#closestOfCorners(f, this.#fineCentre(f, [0, 0, 0]));
    return this.faceFace[f];
  }

  faceNormals() {
    return (this.faceNormalsCache ??= faceNormals(this.fine.positions, this.fine.triangles));
  }

  // ------------------------------------------------------------------------------------------ designs

  // A point of the fine surface ({face, bary}) on the coarse surface.
  pointOnCoarse({ face, bary }) {
    const { positions: P, triangles: T } = this.fine;
    const p = [0, 0, 0];
    for (let j = 0; j < 3; j++) for (let k = 0; k < 3; k++) p[k] += bary[j] * P[3 * T[3 * face + j] + k];
    const candidates = [this.faceOnCoarse(face), ...this.#candidatesOfFace(face, --this.query)];
    const out = { face: 0, bary: [1 / 3, 1 / 3, 1 / 3] };
    const b = [0, 0, 0];
    let best = Infinity;
    for (const c of candidates) {
      const d2 = closestOnTriangle(p, this.coarse.positions, this.coarse.triangles, c, b);
      if (d2 < best) {
        best = d2;
        out.face = c;
        out.bary = [...b];
      }
    }
    return out;
  }

  // A stroke's points on the coarse surface, one per coarse face entered (and the last): several fine points in
  // one coarse face would make steps at the fine scale there, whose headings (a strip of fine faces zig-zags
  // through their centres) say nothing of the stroke's course at the coarse one.
  #polylineOnCoarse(points) {
    const mapped = points.map((q) => this.pointOnCoarse(q));
    const out = [mapped[0]];
    for (let i = 1; i < mapped.length; i++) {
      if (mapped[i].face !== out.at(-1).face) out.push(mapped[i]);
      else if (i === mapped.length - 1 && out.length > 1) out[out.length - 1] = mapped[i];
      else if (i === mapped.length - 1) out.push(mapped[i]);
    }
    return out;
  }

  // A constraint of the design format on the fine mesh, posed on the coarse one. An edge value becomes the
  // vector whose line integral along the edge is that value: the coarse mesh has no such edge.
  specOnCoarse(spec) {
    const out = { ...spec };
    if (spec.points) out.points = this.#polylineOnCoarse(spec.points);
    if (spec.type === 'vector' || spec.type === 'vortex') out.face = this.faceOnCoarse(spec.face);
    if (spec.type === 'source' || spec.type === 'sink') out.vertex = this.#nearestCorner(spec.vertex);
    if (spec.type === 'edge') {
      const P = this.fine.positions, [i, j] = spec.edge;
      const d = [0, 1, 2].map((k) => P[3 * j + k] - P[3 * i + k]);
      const len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] || 1;
      delete out.edge;
      delete out.value;
      Object.assign(out, { type: 'vector', face: this.vertexFace[i], vector: d.map((x) => (x * spec.value) / len2) });
    }
    return out;
  }

  #nearestCorner(v) {
    const c = this.vertexFace[v], b = this.vertexBary.subarray(3 * v, 3 * v + 3);
    const k = b[0] >= b[1] && b[0] >= b[2] ? 0 : b[1] >= b[2] ? 1 : 2;
    return this.coarse.triangles[3 * c + k];
  }

  // A whole design document: its constraints posed on the coarse mesh, without the fine mesh's fingerprint.
  designOnCoarse(doc) {
    const out = { ...doc, constraints: (doc.constraints ?? []).map((s) => this.specOnCoarse(s)) };
    delete out.mesh;
    return out;
  }

  // ------------------------------------------------------------------------------------------ fields

  // The coarse field on the fine mesh: {vertexVectors, faceVectors} (Float64Array, fine sizes). A vector field
  // is interpolated from the coarse vertex vectors and laid into each fine tangent plane; a line or cross field
  // (symmetry > 1: representatives, whose signs do not interpolate) takes the coarse face's. The face vectors
  // only when out.faceVectors is given (an N-field's representatives, which the page cannot derive); the
  // page derives a vector field's face vectors and one-form from its vertex vectors (geometry/vertex-field.js).
  // out: {vertexVectors, faceVectors}: arrays to refill (the page hands old ones back).
  fieldOnFine(coarseFaceVectors, coarseVertexVectors, symmetry, out) {
    const lines = symmetry > 1;
    const { faceVectors, vertexVectors } = out;
    if (faceVectors) {
      if (!this.allFaces) for (let f = 0; f < this.nF; f++) this.faceOnCoarse(f);
      this.allFaces = true;
      sampleInto(
        faceVectors,
        this.faceFace,
        this.faceBary,
        this.faceNormals(),
        this.coarse.triangles,
        coarseFaceVectors,
        coarseVertexVectors,
        lines,
      );
    }
    sampleInto(
      vertexVectors,
      this.vertexFace,
      this.vertexBary,
      this.vertexNormals,
      this.coarse.triangles,
      coarseFaceVectors,
      coarseVertexVectors,
      lines,
    );
    return { faceVectors, vertexVectors };
  }
}

// For each sample k (a fine face or vertex): the coarse field at its closest point (coarse face face[k], bary
// 3k..), laid into the plane of normals 3k..; a line or cross field takes the coarse face's representative,
// as a unit vector.
function sampleInto(out, face, bary, normals, tri, faceVectors, vertexVectors, lines) {
  for (let k = 0, n = face.length; k < n; k++) {
    const f = face[k];
    let x = 0, y = 0, z = 0;
    if (lines) (x = faceVectors[3 * f]), (y = faceVectors[3 * f + 1]), (z = faceVectors[3 * f + 2]);
    else {
      for (let j = 0; j < 3; j++) {
        const c = 3 * tri[3 * f + j], w = bary[3 * k + j];
        x += w * vertexVectors[c];
        y += w * vertexVectors[c + 1];
        z += w * vertexVectors[c + 2];
      }
    }
    const n0 = normals[3 * k], n1 = normals[3 * k + 1], n2 = normals[3 * k + 2];
    const d = x * n0 + y * n1 + z * n2;
    x -= d * n0;
    y -= d * n1;
    z -= d * n2;
    if (lines) {
      const len = Math.hypot(x, y, z) || 1;
      x /= len;
      y /= len;
      z /= len;
    }
    out[3 * k] = x;
    out[3 * k + 1] = y;
    out[3 * k + 2] = z;
  }
}

// Squared distance from p to triangle f of (P, T), and the closest point's barycentric coordinates into b
// (Ericson, Real-Time Collision Detection, 5.1.5). Scalars only: it runs a few million times per model.
export function closestOnTriangle(p, P, T, f, b) {
  const a = 3 * T[3 * f], bb = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
  const ax = P[a], ay = P[a + 1], az = P[a + 2];
  const abx = P[bb] - ax, aby = P[bb + 1] - ay, abz = P[bb + 2] - az;
  const acx = P[c] - ax, acy = P[c + 1] - ay, acz = P[c + 2] - az;
  const apx = p[0] - ax, apy = p[1] - ay, apz = p[2] - az;
  const d1 = abx * apx + aby * apy + abz * apz, d2 = acx * apx + acy * apy + acz * apz;
  let u = 1, v = 0, w = 0;
  if (d1 > 0 || d2 > 0) {
    const bpx = apx - abx, bpy = apy - aby, bpz = apz - abz;
    const d3 = abx * bpx + aby * bpy + abz * bpz, d4 = acx * bpx + acy * bpy + acz * bpz;
    const cpx = apx - acx, cpy = apy - acy, cpz = apz - acz;
    const d5 = abx * cpx + aby * cpy + abz * cpz, d6 = acx * cpx + acy * cpy + acz * cpz;
    const vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d3 >= 0 && d4 <= d3) (u = 0), (v = 1);
    else if (d6 >= 0 && d5 <= d6) (u = 0), (w = 1);
    else if (vc <= 0 && d1 >= 0 && d3 <= 0) (v = d1 / (d1 - d3)), (u = 1 - v);
    else if (vb <= 0 && d2 >= 0 && d6 <= 0) (w = d2 / (d2 - d6)), (u = 1 - w);
    else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) (w = (d4 - d3) / (d4 - d3 + (d5 - d6))), (u = 0), (v = 1 - w);
    else {
      const den = 1 / (va + vb + vc);
      v = vb * den;
      w = vc * den;
      u = 1 - v - w;
    }
  }
  b[0] = u;
  b[1] = v;
  b[2] = w;
  const qx = v * abx + w * acx - apx, qy = v * aby + w * acy - apy, qz = v * abz + w * acz - apz;
  return qx * qx + qy * qy + qz * qz;
}

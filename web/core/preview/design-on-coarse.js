// A design made on a big model's fine mesh, posed on its preview's coarse one through the map of the fine
// surface onto the coarse (surface-map.js): points, strokes, constraints and whole design documents.
// Owns nothing; imports closest-point.js.
import { closestOnTriangle } from './closest-point.js';

// A point of the fine surface ({face, bary}) on the coarse surface. map: the SurfaceMap.
export function pointOnCoarse(map, { face, bary }) {
  const { positions: P, triangles: T } = map.fine;
  const p = [0, 0, 0];
  for (let j = 0; j < 3; j++) for (let k = 0; k < 3; k++) p[k] += bary[j] * P[3 * T[3 * face + j] + k];
  const candidates = [map.faceOnCoarse(face), ...map.search.candidatesNear(face)];
  const out = { face: 0, bary: [1 / 3, 1 / 3, 1 / 3] };
  const b = [0, 0, 0];
  let best = Infinity;
  for (const c of candidates) {
    const d2 = closestOnTriangle(p, map.coarse.positions, map.coarse.triangles, c, b);
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
function polylineOnCoarse(map, points) {
  const mapped = points.map((q) => map.pointOnCoarse(q));
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
export function specOnCoarse(map, spec) {
  const out = { ...spec };
  if (spec.points) out.points = polylineOnCoarse(map, spec.points);
  if (spec.type === 'vector' || spec.type === 'vortex') out.face = map.faceOnCoarse(spec.face);
  if (spec.type === 'source' || spec.type === 'sink' || spec.type === 'singularity')
    out.vertex = nearestCorner(map, spec.vertex);
  if (spec.type === 'edge') {
    const P = map.fine.positions;
    const [i, j] = spec.edge;
    const d = [0, 1, 2].map((k) => P[3 * j + k] - P[3 * i + k]);
    const len2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2] || 1;
    delete out.edge;
    delete out.value;
    out.type = 'vector';
    out.face = map.vertexFace[i];
    out.vector = d.map((x) => (x * spec.value) / len2);
  }
  return out;
}

// The corner of fine vertex v's coarse face nearest to it (the largest barycentric coordinate).
function nearestCorner(map, v) {
  const c = map.vertexFace[v];
  const b = map.vertexBary.subarray(3 * v, 3 * v + 3);
  const k = b[0] >= b[1] && b[0] >= b[2] ? 0 : b[1] >= b[2] ? 1 : 2;
  return map.coarse.triangles[3 * c + k];
}

// A whole design document: its constraints and singularities posed on the coarse mesh, without the fine mesh's
// fingerprint and without features: the coarse mesh has none of the fine edges, and the angle would find the
// decimation's creases (a smooth model's coarse stand-in has many over 35 degrees) rather than the model's.
export function designOnCoarse(map, doc) {
  const out = { ...doc, constraints: (doc.constraints ?? []).map((s) => map.specOnCoarse(s)) };
  if (doc.singularities)
    out.singularities = doc.singularities.map((s) => ({ ...s, vertex: nearestCorner(map, s.vertex) }));
  delete out.mesh;
  delete out.featureEdges;
  delete out.featureAngle; // none: 0
  return out;
}

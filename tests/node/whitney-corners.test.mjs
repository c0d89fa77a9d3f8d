// The Whitney reconstruction per corner (web/geometry/whitney-corners.js), which the texture of a vector field
// follows per texel, against what defines it: the field linear over each face whose line integral along every
// edge is the 1-form's value, exact for a constant field, continuous along an edge from both its faces, and at
// the barycentre the face vector the core's Eq. 4 gives (the mean of the three corners).
import assert from 'node:assert/strict';
import test from 'node:test';
import { grid, icosphere } from './fakes.mjs';
import { edgeRows, signedEdge, whitneyCorners } from '../../web/geometry/whitney-corners.js';

// Every face's corners, 9 per face (corner k of face f at 9f + 3k).
function whitneyCornerVectors(positions, triangles, rows, oneForm) {
  const out = new Float64Array(3 * triangles.length);
  whitneyCorners(positions, triangles, rows, oneForm, 0, triangles.length / 3, out, 9);
  return out;
}
import { Surface } from '../../web/geometry/surface.js';

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const at = (a, i) => [a[3 * i], a[3 * i + 1], a[3 * i + 2]];

// A 1-form with no structure: a different value on every edge.
function scrambledOneForm(nE) {
  const w = new Float64Array(nE);
  let s = 12345;
  for (let e = 0; e < nE; e++) w[e] = ((s = (s * 1103515245 + 12345) % 2147483648) / 2147483648 - 0.5) * 3;
  return w;
}

// The edges (2 each) reordered by key (lower vertex, then upper), or reversed.
function reorderedEdges(edges, how) {
  const order = Array.from({ length: edges.length / 2 }, (_, e) => e);
  if (how === 'sorted') order.sort((p, q) => edges[2 * p] - edges[2 * q] || edges[2 * p + 1] - edges[2 * q + 1]);
  else order.reverse();
  return Int32Array.from(order.flatMap((e) => [edges[2 * e], edges[2 * e + 1]]));
}

test('edge rows: each face edge is the mesh edge joining its corners, signed by direction', () => {
  const m = icosphere(2);
  // Listed by lower vertex (the core's order), the rows are the list itself; in any other order, they are sorted.
  for (const how of ['sorted', 'reversed']) {
    const edges = reorderedEdges(m.edges, how);
    const rows = edgeRows(edges, m.positions.length / 3);
    assert.equal(rows.id === null, how === 'sorted', how);
    for (let f = 0; f < m.triangles.length / 3; f++)
      for (let k = 0; k < 3; k++) {
        const a = m.triangles[3 * f + k], b = m.triangles[3 * f + ((k + 1) % 3)];
        const s = signedEdge(rows, a, b), e = Math.abs(s) - 1;
        assert.deepEqual([edges[2 * e], edges[2 * e + 1]], s > 0 ? [a, b] : [b, a], how);
      }
    assert.equal(signedEdge(rows, 0, m.positions.length - 1), 0, 'two vertices far apart share no edge');
  }
  const missing = edgeRows(m.edges.slice(0, -2), m.positions.length / 3);
  assert.throws(() => whitneyCornerVectors(m.positions, m.triangles, missing, new Float64Array(m.edges.length / 2)), /not among/);
});

test('Whitney corners: the integral of the linear field along each edge is the 1-form, from both faces', () => {
  const m = icosphere(2);
  const S = new Surface(m.positions, m.triangles, m.edges);
  const w = scrambledOneForm(m.edges.length / 2);
  const C = whitneyCornerVectors(m.positions, m.triangles, S.edgeRows, w);
  const seen = new Float64Array(w.length);
  let worst = 0;
  for (let f = 0; f < m.triangles.length / 3; f++)
    for (let k = 0; k < 3; k++) {
      const a = m.triangles[3 * f + k], b = m.triangles[3 * f + ((k + 1) % 3)];
      const d = sub(at(m.positions, b), at(m.positions, a));
      // The field is linear along the edge: the trapezoid rule is exact.
      const integral = 0.5 * dot(at(C, 3 * f + k), d) + 0.5 * dot(at(C, 3 * f + ((k + 1) % 3)), d);
      const s = signedEdge(S.edgeRows, a, b), e = Math.abs(s) - 1;
      worst = Math.max(worst, Math.abs(integral - (s > 0 ? w[e] : -w[e])));
      seen[e]++;
    }
  assert.ok(worst < 1e-12, `largest edge integral error ${worst}`);
  assert.ok(seen.every((n) => n === 2), 'every edge of the closed sphere is read from its two faces');
});

test('Whitney corners: a constant field on a flat mesh comes back at every corner', () => {
  const m = grid(6, 2, -1);
  const c = [0.3, -1.7, 0];
  const w = new Float64Array(m.edges.length / 2);
  for (let e = 0; e < w.length; e++) w[e] = dot(c, sub(at(m.positions, m.edges[2 * e + 1]), at(m.positions, m.edges[2 * e])));
  const S = new Surface(m.positions, m.triangles, m.edges);
  const C = whitneyCornerVectors(m.positions, m.triangles, S.edgeRows, w);
  for (let i = 0; i < C.length / 3; i++)
    for (let d = 0; d < 3; d++) assert.ok(Math.abs(C[3 * i + d] - c[d]) < 1e-12, `corner ${i}: ${at(C, i)}`);
});

test('Whitney corners: tangential along each edge from both faces, the face mean tangent to the face', () => {
  const m = icosphere(1);
  const S = new Surface(m.positions, m.triangles, m.edges);
  const C = whitneyCornerVectors(m.positions, m.triangles, S.edgeRows, scrambledOneForm(m.edges.length / 2));
  const cornerOf = new Map(); // "face,vertex" -> the corner's vector
  for (let f = 0; f < m.triangles.length / 3; f++)
    for (let k = 0; k < 3; k++) cornerOf.set(`${f},${m.triangles[3 * f + k]}`, at(C, 3 * f + k));
  let worst = 0;
  for (let h = 0; h < m.triangles.length; h++) {
    const f = Math.floor(h / 3), g = Math.floor(S.neighbour[h] / 3);
    const a = m.triangles[h], b = m.triangles[3 * f + ((h + 1) % 3)];
    const d = sub(at(m.positions, b), at(m.positions, a));
    // The component along the edge, at each of its ends, is the same from either face (H(curl) conformity).
    for (const v of [a, b]) worst = Math.max(worst, Math.abs(dot(cornerOf.get(`${f},${v}`), d) - dot(cornerOf.get(`${g},${v}`), d)));
  }
  assert.ok(worst < 1e-12, `tangential jump ${worst}`);
  for (let f = 0; f < m.triangles.length / 3; f++) {
    const mean = [0, 1, 2].map((d) => (C[9 * f + d] + C[9 * f + 3 + d] + C[9 * f + 6 + d]) / 3);
    assert.ok(Math.abs(dot(mean, at(S.normals, f))) < 1e-12, 'in the face plane');
  }
});

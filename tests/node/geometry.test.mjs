// Mesh computations of web/geometry/ against geometric truth: the mesh's own geometry (Gauss–Bonnet),
// Poisson-disc properties of the arrow samples, integral curves of fields whose streamlines are known in closed
// form (straight lines, circles, latitude circles), and singularity indices known from complex analysis and
// the Poincaré–Hopf theorem.
import assert from 'node:assert/strict';
import test from 'node:test';
import { grid, icosphere } from './fakes.mjs';
import { Surface } from '../../web/geometry/surface.js';
import { halfEdgeNeighbours, vertexNormals } from '../../web/geometry/mesh-geometry.js';
import { torus } from '../../web/core/preview/warm-up.js';
import { POISSON_PACKING, SurfaceSampler, sampleSurface } from '../../web/geometry/arrow-sampling.js';
import { traceStreamlines } from '../../web/geometry/streamlines.js';
import { findSingularities } from '../../web/geometry/singularities.js';
import { faceVectorsOfVertexField, oneFormOfVertexField } from '../../web/geometry/vertex-field.js';

const surfaceOf = (m) => new Surface(m.positions, m.triangles, m.edges);
const vertexOf = (m, v) => [m.positions[3 * v], m.positions[3 * v + 1], m.positions[3 * v + 2]];
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.hypot(a[0], a[1], a[2]);
const dist = (a, b) => norm(sub(a, b));

// Per-vertex and per-face fields from a function of the position.
function vertexField(m, fn) {
  const out = new Float64Array(m.positions.length);
  for (let v = 0; v < m.positions.length / 3; v++) out.set(fn(vertexOf(m, v)), 3 * v);
  return out;
}

function faceField(m, fn) {
  const nF = m.triangles.length / 3;
  const out = new Float64Array(3 * nF);
  for (let f = 0; f < nF; f++) {
    const [a, b, c] = [0, 1, 2].map((k) => vertexOf(m, m.triangles[3 * f + k]));
    out.set(fn([0, 1, 2].map((k) => (a[k] + b[k] + c[k]) / 3)), 3 * f);
  }
  return out;
}

// ------------------------------------------------------------------------------------------ Surface

test('surface: areas, normals and angle defects of a closed sphere obey Gauss–Bonnet', () => {
  const m = icosphere(2);
  const s = surfaceOf(m);
  let area = 0;
  for (let f = 0; f < s.nF; f++) {
    const [a, b, c] = [0, 1, 2].map((k) => vertexOf(m, m.triangles[3 * f + k]));
    const n = cross(sub(b, a), sub(c, a));
    area += norm(n) / 2;
    assert.ok(Math.abs(s.areas[f] - norm(n) / 2) < 1e-15);
    assert.ok(dot(s.normal(f), s.centroid(f)) > 0, 'outward normals on the icosphere');
  }
  assert.ok(Math.abs(s.areas.reduce((x, y) => x + y) - area) < 1e-12);
  assert.ok(area < 4 * Math.PI && area > 0.98 * 4 * Math.PI, 'an inscribed polyhedron has a little less area than the sphere');
  const totalDefect = s.angleDefects().reduce((x, y) => x + y);
  assert.ok(Math.abs(totalDefect - 2 * Math.PI * 2) < 1e-9, `Σ defects = 2πχ = 4π (got ${totalDefect})`);
  assert.ok(s.neighbour.every((h) => h >= 0), 'closed: every half-edge has a twin');
});

// Twins found the slow, obvious way: every other half-edge compared (pairing in face order, as the map does).
function twinsByScan(T) {
  const out = new Int32Array(T.length).fill(-1);
  const ends = (h) => [T[h], T[h - (h % 3) + ((h % 3) + 1) % 3]];
  for (let h = 0; h < T.length; h++) {
    if (out[h] !== -1) continue;
    const [a, b] = ends(h);
    for (let g = h + 1; g < T.length; g++) {
      const [c, d] = ends(g);
      if (out[g] === -1 && ((a === c && b === d) || (a === d && b === c))) {
        out[h] = g;
        out[g] = h;
        break;
      }
    }
  }
  return out;
}

test('vertex normals are the area-weighted sums of the face normals around them: radial on a sphere', () => {
  const { positions, triangles } = icosphere(3);
  const nV = positions.length / 3;
  // Area times unit normal: half the cross product of two edges.
  const byFaces = new Float64Array(3 * nV);
  for (let t = 0; t < triangles.length; t++) {
    const f = Math.floor(t / 3);
    const [a, b, c] = [0, 1, 2].map((k) => Array.from(positions.subarray(3 * triangles[3 * f + k], 3 * triangles[3 * f + k] + 3)));
    const u = [0, 1, 2].map((k) => b[k] - a[k]), w = [0, 1, 2].map((k) => c[k] - a[k]);
    const n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
    for (let k = 0; k < 3; k++) byFaces[3 * triangles[t] + k] += n[k] / 2;
  }
  for (let v = 0; v < nV; v++) {
    const l = Math.hypot(byFaces[3 * v], byFaces[3 * v + 1], byFaces[3 * v + 2]);
    for (let k = 0; k < 3; k++) byFaces[3 * v + k] /= l;
  }
  const direct = vertexNormals(positions, triangles);
  let worst = 0, radial = 1;
  for (let v = 0; v < nV; v++) {
    const n = direct.subarray(3 * v, 3 * v + 3), p = positions.subarray(3 * v, 3 * v + 3);
    for (let k = 0; k < 3; k++) worst = Math.max(worst, Math.abs(n[k] - byFaces[3 * v + k]));
    radial = Math.min(radial, (n[0] * p[0] + n[1] * p[1] + n[2] * p[2]) / Math.hypot(...p));
  }
  assert.ok(worst < 1e-12, `differ by ${worst}`);
  assert.ok(radial > 0.999, `a vertex normal ${Math.acos(radial)} rad off the radius`);
});

test('half-edge twins: reversed on closed meshes, none on a boundary, pairs in face order on a non-manifold edge', () => {
  for (const m of [icosphere(1), torus(12, 6), grid(5)]) {
    const nV = m.positions.length / 3, T = m.triangles;
    const twins = halfEdgeNeighbours(T, nV);
    assert.deepEqual(twins, twinsByScan(T));
    for (let h = 0; h < T.length; h++) {
      const g = twins[h];
      if (g < 0) continue;
      assert.equal(twins[g], h);
      assert.equal(T[h], T[g - (g % 3) + ((g % 3) + 1) % 3], 'a twin runs the other way');
    }
  }
  assert.ok(halfEdgeNeighbours(torus(12, 6).triangles, 72).every((h) => h >= 0), 'a torus is closed');
  const boundary = halfEdgeNeighbours(grid(5).triangles, 36).filter((h) => h < 0).length;
  assert.equal(boundary, 4 * 5, 'a 5 × 5 grid has 20 boundary half-edges');
  // Four faces on edge 0–1 (a book of pages) and a fifth page: 1st with 2nd, 3rd with 4th, the 5th alone.
  const book = Int32Array.from([0, 1, 2, 1, 0, 3, 0, 1, 4, 1, 0, 5, 0, 1, 6]);
  const twins = halfEdgeNeighbours(book, 7);
  assert.deepEqual([twins[0], twins[3], twins[6], twins[9], twins[12]], [3, 0, 9, 6, -1]);
  assert.deepEqual(twins, twinsByScan(book));
});

test('the warm-up torus is a closed genus-1 surface: V − E + F = 0, each edge once, on two faces', () => {
  const m = torus(16, 8);
  const nV = m.positions.length / 3, nE = m.edges.length / 2, nF = m.triangles.length / 3;
  assert.equal(nV - nE + nF, 0);
  const key = (a, b) => Math.min(a, b) * nV + Math.max(a, b);
  const listed = new Set();
  for (let e = 0; e < nE; e++) {
    assert.ok(m.edges[2 * e] < m.edges[2 * e + 1], 'lower vertex first');
    listed.add(key(m.edges[2 * e], m.edges[2 * e + 1]));
  }
  assert.equal(listed.size, nE, 'no edge twice');
  const faces = new Map();
  for (let h = 0; h < 3 * nF; h++) {
    const k = key(m.triangles[h], m.triangles[h - (h % 3) + ((h % 3) + 1) % 3]);
    assert.ok(listed.has(k), 'every face edge is listed');
    faces.set(k, (faces.get(k) ?? 0) + 1);
  }
  assert.ok([...faces.values()].every((n) => n === 2));
});

test('surface: walking straight on a flat grid goes in a straight line, and stops at the boundary', () => {
  const m = grid(10, 1);
  const s = surfaceOf(m);
  const f = 0;
  const start = s.to2d(f, s.centroid(f));
  const dir3 = [Math.cos(0.3), Math.sin(0.3), 0];
  const d2 = s.vec2d(f, dir3);
  const w = s.walk(f, start, d2, 0.5);
  assert.equal(w.hitBoundary, false);
  const end = s.to3d(w.face, w.p);
  const expected = s.centroid(f).map((x, k) => x + 0.5 * dir3[k]);
  // Each edge crossing nudges the point 1e-9 mean edges into the next face.
  assert.ok(dist(end, expected) < 1e-7, `ended at ${end}, expected ${expected}`);
  const out = s.walk(f, start, d2, 5);
  assert.equal(out.hitBoundary, true);
  const p = s.to3d(out.face, out.p);
  assert.ok(Math.abs(Math.max(p[0], p[1]) - 1) < 1e-9, 'stopped on the far side of the square');
});

// ------------------------------------------------------------------------------------------ arrow sampling

function samplesOf(result) {
  return Array.from({ length: result.faces.length }, (_, i) => ({
    face: result.faces[i],
    bary: Array.from(result.bary.subarray(3 * i, 3 * i + 3)),
    point: Array.from(result.points.subarray(3 * i, 3 * i + 3)),
  }));
}

test('arrow samples lie on the surface: inside their face, at its barycentric coordinates', () => {
  const m = icosphere(3);
  const s = surfaceOf(m);
  // The largest distance from the unit sphere to a face: at most the sagitta of its longest edge's arc.
  let maxEdge = 0;
  for (let i = 0; i < m.edges.length; i += 2) maxEdge = Math.max(maxEdge, dist(vertexOf(m, m.edges[i]), vertexOf(m, m.edges[i + 1])));
  const sag = 1 - Math.sqrt(1 - (maxEdge / Math.sqrt(3)) ** 2); // circumradius of the face, at most edge/√3
  for (const { face, bary, point } of samplesOf(sampleSurface(s, 0.1))) {
    assert.ok(bary.every((b) => b >= 0 && b <= 1) && Math.abs(bary[0] + bary[1] + bary[2] - 1) < 1e-12);
    const corners = [0, 1, 2].map((k) => vertexOf(m, m.triangles[3 * face + k]));
    const fromBary = [0, 1, 2].map((k) => bary[0] * corners[0][k] + bary[1] * corners[1][k] + bary[2] * corners[2][k]);
    assert.ok(dist(point, fromBary) < 1e-12);
    const r = norm(point);
    assert.ok(r <= 1 + 1e-12 && r >= 1 - sag, `|p| = ${r} is off the sphere by more than the chordal error ${sag}`);
  }
});

function minPairDistance(points) {
  let min = Infinity;
  for (let i = 0; i < points.length; i++) for (let j = i + 1; j < points.length; j++) min = Math.min(min, dist(points[i], points[j]));
  return min;
}

test('arrow samples are a Poisson-disc set: no two closer than the spacing, no hole wider than twice it', () => {
  const m = icosphere(3);
  const s = surfaceOf(m);
  for (const spacing of [0.25, 0.1]) {
    const points = samplesOf(sampleSurface(s, spacing)).map((x) => x.point);
    assert.ok(minPairDistance(points) >= spacing, `spacing ${spacing}`);
    // Any surface point with no sample within 2·spacing would have a free disc of radius `spacing` around
    // it, which dart throwing at this density leaves empty with negligible probability: every vertex and
    // face centre has a sample nearby.
    const probes = [...Array.from({ length: s.nV }, (_, v) => vertexOf(m, v)), ...Array.from({ length: s.nF }, (_, f) => s.centroid(f))];
    for (const q of probes) assert.ok(points.some((p) => dist(p, q) < 2 * spacing), `a hole around ${q}`);
  }
});

test('arrow sampling in steps gives exactly the samples of one call, on the whole surface and on a region', () => {
  const s = surfaceOf(icosphere(3));
  const region = Int32Array.from({ length: 200 }, (_, k) => (k * 7) % s.nF);
  for (const [spacing, options] of [[0.05, {}], [0.1, { seed: 9 }], [0.02, { faces: region, maxSamples: 300 }]]) {
    const whole = sampleSurface(s, spacing, options);
    const sampler = new SurfaceSampler(s, spacing, options);
    let steps = 0;
    while (!sampler.step(37)) steps++;
    assert.ok(steps > 3, `${steps} steps`);
    assert.deepEqual(sampler.result(), whole);
    assert.ok(whole.faces.length > 50);
  }
});

test('arrow sample counts follow area / spacing², bounded by the densest packing, spread evenly', () => {
  const m = icosphere(3);
  const s = surfaceOf(m);
  const area = s.areas.reduce((x, y) => x + y);
  const count = (spacing) => sampleSurface(s, spacing).faces.length;
  const n1 = count(0.1), n2 = count(0.05);
  assert.ok(Math.abs(n2 / n1 - 4) < 0.4, `halving the spacing: ${n1} → ${n2} samples`);
  for (const [n, spacing] of [[n1, 0.1], [n2, 0.05]]) {
    const density = (n * spacing * spacing) / area;
    // Discs of diameter `spacing` pack at most 2/√3 per spacing² (hexagonal packing); random sequential
    // adsorption jams near 0.7 (POISSON_PACKING), and a greedy pass with few candidates lands somewhat below.
    assert.ok(density <= 2 / Math.sqrt(3), `density ${density}`);
    assert.ok(density >= 0.6 * POISSON_PACKING && density <= POISSON_PACKING * 1.05, `density ${density}`);
  }
  const points = samplesOf(sampleSurface(s, 0.05)).map((x) => x.point);
  for (let axis = 0; axis < 3; axis++) {
    const upper = points.filter((p) => p[axis] > 0).length / points.length;
    assert.ok(Math.abs(upper - 0.5) < 0.05, `axis ${axis}: ${upper} of the samples in one hemisphere`);
  }
});

test('arrow sample candidates are uniform by area: across faces and inside each face', () => {
  // Two faces of areas 1/2 and 3/2. At a spacing far below the mesh's scale, with the count capped, every
  // candidate is kept, so the samples show the candidates' distribution itself.
  const s = new Surface(Float64Array.of(0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 3, 0), Int32Array.of(0, 1, 2, 0, 2, 3), Int32Array.of(0, 1, 0, 2, 0, 3, 1, 2, 2, 3));
  const { faces, bary } = sampleSurface(s, 1e-6, { maxSamples: 4000 });
  assert.equal(faces.length, 4000);
  const share = (pick) => faces.filter((_, i) => pick(i)).length / faces.length;
  assert.ok(Math.abs(share((i) => faces[i] === 0) - 0.25) < 0.03, 'a face gets samples in proportion to its area');
  // The corner sub-triangle where one barycentric coordinate exceeds 1/2 holds a quarter of a face's area.
  for (let k = 0; k < 3; k++) assert.ok(Math.abs(share((i) => bary[3 * i + k] > 0.5) - 0.25) < 0.03, `corner ${k}`);
});

test('arrow sampling is deterministic for a seed, differs between seeds, and honours faces and the cap', () => {
  const s = surfaceOf(icosphere(2));
  assert.deepEqual(sampleSurface(s, 0.15, { seed: 3 }), sampleSurface(s, 0.15, { seed: 3 }));
  assert.notDeepEqual(sampleSurface(s, 0.15, { seed: 3 }).points, sampleSurface(s, 0.15, { seed: 4 }).points);
  const faces = Int32Array.from({ length: 40 }, (_, k) => 2 * k);
  const some = sampleSurface(s, 0.05, { faces });
  assert.ok(some.faces.length > 0 && [...some.faces].every((f) => faces.includes(f)));
  assert.equal(sampleSurface(s, 0.01, { maxSamples: 100 }).faces.length, 100);
  assert.equal(sampleSurface(s, 0).faces.length, 0);
  assert.equal(sampleSurface(s, -1).faces.length, 0);
  assert.equal(sampleSurface(s, 0.1, { faces: new Int32Array(0) }).faces.length, 0);
});

// ------------------------------------------------------------------------------------------ streamlines

const pointsOf = (line) => Array.from({ length: line.length / 3 }, (_, k) => [line[3 * k], line[3 * k + 1], line[3 * k + 2]]);

function minDistanceBetweenLines(lines) {
  const pts = lines.map(pointsOf);
  let min = Infinity;
  for (let a = 0; a < pts.length; a++)
    for (let b = a + 1; b < pts.length; b++) for (const p of pts[a]) for (const q of pts[b]) min = Math.min(min, dist(p, q));
  return min;
}

test('streamlines of a constant field on a flat square: straight, parallel to it, evenly spaced, wall to wall', () => {
  const m = grid(20, 1);
  const spacing = 0.1;
  const d = [2, 1, 0].map((x) => x / Math.sqrt(5));
  const lines = traceStreamlines(surfaceOf(m), vertexField(m, () => [2, 1, 0]), { spacing });
  assert.ok(lines.length >= 8);
  const offsets = [];
  for (const line of lines) {
    const pts = pointsOf(line);
    assert.ok(pts.length >= 2);
    const offset = pts[0][0] * d[1] - pts[0][1] * d[0]; // signed distance across the field
    for (const p of pts) assert.ok(Math.abs(p[0] * d[1] - p[1] * d[0] - offset) < 1e-6, 'straight and parallel to the field');
    for (let k = 1; k < pts.length; k++) {
      const step = sub(pts[k], pts[k - 1]);
      assert.ok(dot(step, d) > 0, 'in the direction of the field');
    }
    const toWall = (p) => Math.min(p[0], 1 - p[0], p[1], 1 - p[1]);
    assert.ok(toWall(pts[0]) < 1e-6 && toWall(pts.at(-1)) < 1e-6, 'nothing stops a line but the boundary');
    assert.ok(pts.every((p) => p[2] === 0));
    offsets.push(offset);
  }
  offsets.sort((a, b) => a - b);
  for (let k = 1; k < offsets.length; k++) {
    const gap = offsets[k] - offsets[k - 1];
    assert.ok(gap >= 0.99 * spacing && gap <= 1.5 * spacing, `lines ${gap} apart at spacing ${spacing}`);
  }
  // The square's extent across the field, from corner (0, 1) to corner (1, 0).
  const [lo, hi] = [0 * d[1] - 1 * d[0], 1 * d[1] - 0 * d[0]];
  assert.ok(offsets[0] - lo < 2 * spacing && hi - offsets.at(-1) < 2 * spacing, 'the whole square is covered');
});

test('streamlines of a source are rays from it, stopped before they come closer than d_sep / 2', () => {
  const m = grid(40, 2, -1);
  const spacing = 0.15;
  const lines = traceStreamlines(surfaceOf(m), vertexField(m, ([x, y]) => [x, y, 0]), { spacing });
  assert.ok(lines.length > 20);
  for (const line of lines) {
    const pts = pointsOf(line);
    const ray = pts.at(-1).map((x) => x / norm(pts.at(-1)));
    for (const p of pts) assert.ok(Math.abs(cross(p, ray)[2]) < 1e-6, 'on a ray through the source');
    for (let k = 1; k < pts.length; k++) assert.ok(norm(pts[k]) > norm(pts[k - 1]), 'outward');
  }
  // Rays converge at the source: Jobard–Lefer stops a line within d_test = d_sep / 2 of another one.
  assert.ok(minDistanceBetweenLines(lines) >= 0.5 * spacing * (1 - 1e-6));
});

test('streamlines of a rotation about the origin are circles, spaced by the spacing', () => {
  const m = grid(40, 2, -1);
  const spacing = 0.15;
  const lines = traceStreamlines(surfaceOf(m), vertexField(m, ([x, y]) => [-y, x, 0]), { spacing });
  assert.ok(minDistanceBetweenLines(lines) >= 0.5 * spacing, 'no two lines closer than d_test = d_sep / 2');
  const closed = [];
  for (const line of lines) {
    const pts = pointsOf(line);
    const radii = pts.map((p) => Math.hypot(p[0], p[1]));
    const mean = radii.reduce((x, y) => x + y) / radii.length;
    if (mean < spacing) continue; // the last, tiny loop round the centre: a few steps per turn
    for (const r of radii) assert.ok(Math.abs(r - mean) < 0.01 * mean, `radius ${r} on a circle of ${mean}`);
    // Counter-clockwise, as (−y, x) turns.
    for (let k = 1; k < pts.length; k++) assert.ok(cross(pts[k - 1], pts[k])[2] > 0);
    if (mean < 1 - spacing) {
      // Inside the square the circle closes on itself.
      assert.ok(dist(pts[0], pts.at(-1)) <= spacing, 'a full circle');
      closed.push(mean);
    }
  }
  closed.sort((a, b) => a - b);
  assert.ok(closed.length >= 5);
  for (let k = 1; k < closed.length; k++) {
    const gap = closed[k] - closed[k - 1];
    assert.ok(gap >= 0.9 * spacing && gap <= 1.1 * spacing, `circles ${gap} apart`);
  }
});

test('streamlines of a rotation about the axis of a sphere follow the latitudes, pole to pole', () => {
  const m = icosphere(3);
  const spacing = 0.2;
  const lines = traceStreamlines(surfaceOf(m), vertexField(m, ([x, y]) => [-y, x, 0]), { spacing });
  const latitudes = [];
  for (const line of lines) {
    const pts = pointsOf(line);
    const zs = pts.map((p) => p[2]);
    const mean = zs.reduce((x, y) => x + y) / zs.length;
    for (const z of zs) assert.ok(Math.abs(z - mean) < 0.01, `z = ${z} on the latitude ${mean}`);
    for (const p of pts) assert.ok(norm(p) <= 1 + 1e-6 && norm(p) > 0.99, 'on the surface');
    assert.ok(dist(pts[0], pts.at(-1)) <= spacing, 'a closed latitude circle');
    latitudes.push(Math.asin(mean));
  }
  latitudes.sort((a, b) => a - b);
  for (let k = 1; k < latitudes.length; k++) {
    const gap = latitudes[k] - latitudes[k - 1]; // geodesic distance between latitude circles on the unit sphere
    assert.ok(gap >= 0.9 * spacing && gap <= 1.2 * spacing, `latitudes ${gap} apart`);
  }
  assert.ok(Math.PI / 2 - latitudes.at(-1) < spacing && latitudes[0] + Math.PI / 2 < spacing, 'up to the poles');
});

test('streamlines: lifted along the normal, deterministic, none for a zero field', () => {
  const m = grid(10, 1);
  const s = surfaceOf(m);
  const V = vertexField(m, ([x, y]) => [1, 0.3 * x, 0]);
  const lifted = traceStreamlines(s, V, { spacing: 0.1, lift: 0.01 });
  assert.ok(lifted.every((l) => pointsOf(l).every((p) => Math.abs(p[2] - 0.01) < 1e-7)));
  assert.deepEqual(traceStreamlines(s, V, { spacing: 0.1 }), traceStreamlines(s, V, { spacing: 0.1 }));
  assert.deepEqual(traceStreamlines(s, new Float64Array(V.length), { spacing: 0.1 }), []);
});

// ------------------------------------------------------------------------------------------ singularities

const sumOfIndices = (list) => list.reduce((n, x) => n + x.index, 0);

test('singularities: a rotation about an axis through a vertex of the sphere has +1 at both ends of the axis', () => {
  const m = icosphere(3);
  const s = surfaceOf(m);
  const axis = vertexOf(m, 0);
  let antipode = -1;
  for (let v = 0; v < s.nV; v++) if (dist(vertexOf(m, v), axis.map((x) => -x)) < 1e-9) antipode = v;
  assert.ok(antipode > 0, 'the icosphere is symmetric');
  const expected = [
    { vertex: 0, index: 1 },
    { vertex: antipode, index: 1 },
  ].sort((a, b) => a.vertex - b.vertex);
  assert.deepEqual(findSingularities(s, faceField(m, (c) => cross(axis, c))), expected, 'vortices');
  // The gradient of the height along the axis: a source at one end and a sink at the other, each index +1.
  assert.deepEqual(findSingularities(s, faceField(m, (c) => sub(axis, c.map((x) => x * dot(axis, c))))), expected, 'source and sink');
});

test('singularities on the sphere sum to its Euler characteristic (Poincaré–Hopf)', () => {
  const m = icosphere(3);
  const s = surfaceOf(m);
  const fields = [
    (c) => cross([0, 0, 1], c), // axis through no vertex: the ±z poles lie inside faces or on edges
    (c) => cross([0.3, -0.5, 0.81], c),
    (c) => [c[1] * c[2], 1 - c[0], c[0] * c[1] + 0.5], // projected into each face by the index itself
    (c) => [Math.sin(3 * c[0]), Math.cos(2 * c[1] + c[2]), c[0] - c[2]],
  ];
  for (const field of fields) {
    const found = findSingularities(s, faceField(m, field));
    assert.ok(found.length > 0);
    assert.equal(sumOfIndices(found), 2);
  }
});

// A flat grid whose vertex `centre` has eight faces round it (so turnings up to ±3 per circuit stay under π
// per face), with a field f(z) of z = (x − x₀) + i(y − y₀) at the face centres.
function complexFieldOnGrid(fn) {
  const m = grid(12, 2, -1);
  const s = surfaceOf(m);
  let centre = -1, best = Infinity;
  for (let v = 0; v < s.nV; v++) {
    const p = vertexOf(m, v);
    if (s.facesAround(v).length === 8 && norm(p) < best) (best = norm(p)), (centre = v);
  }
  const [x0, y0] = vertexOf(m, centre);
  const F = faceField(m, ([x, y]) => {
    const [re, im] = fn(x - x0, y - y0);
    return [re, im, 0];
  });
  return { m, s, centre, F };
}

const cmul = ([a, b], [c, d]) => [a * c - b * d, a * d + b * c];
const cpow = (z, k) => (k === 0 ? [1, 0] : cmul(z, cpow(z, k - 1)));

test('singularities: the field zᵏ has index k at its zero, conj(z)ᵏ index −k, and no others inside', () => {
  for (const k of [1, 2, 3]) {
    const { s, centre, F } = complexFieldOnGrid((x, y) => cpow([x, y], k));
    assert.deepEqual(findSingularities(s, F), [{ vertex: centre, index: k }], `z^${k}`);
    const conj = complexFieldOnGrid((x, y) => cpow([x, -y], k));
    assert.deepEqual(findSingularities(conj.s, conj.F), [{ vertex: conj.centre, index: -k }], `conj(z)^${k}`);
  }
  // A source and a vortex are both +1; a dipole-free constant field has none.
  const vortex = complexFieldOnGrid((x, y) => [-y, x]);
  assert.deepEqual(findSingularities(vortex.s, vortex.F), [{ vertex: vortex.centre, index: 1 }]);
  const constant = complexFieldOnGrid(() => [1, 2]);
  assert.deepEqual(findSingularities(constant.s, constant.F), []);
});

test('singularities: none on the boundary, none next to a vanishing vector, none for a zero field', () => {
  const { m, s, centre, F } = complexFieldOnGrid((x, y) => [x, y]);
  // The same source, placed on a boundary vertex: boundary vertices carry no index.
  const [x0, y0] = vertexOf(m, 0);
  assert.deepEqual(findSingularities(s, faceField(m, ([x, y]) => [x - x0, y - y0, 0])), []);
  const holed = F.slice();
  holed.fill(0, 3 * s.facesAround(centre)[0], 3 * s.facesAround(centre)[0] + 3);
  assert.deepEqual(findSingularities(s, holed), [], 'an undefined index is not reported');
  assert.deepEqual(findSingularities(s, new Float64Array(F.length)), []);
});

// The page takes over the worker's Surface (core-worker.js loadMesh): the copy must trace exactly as the original.
test('surface: one rebuilt from another thread\'s arrays walks and traces exactly as the original', () => {
  const m = icosphere(2);
  const original = surfaceOf(m);
  const copy = Surface.fromArrays(original.arrays());
  assert.equal(copy.nF, original.nF);
  assert.equal(copy.meanEdge, original.meanEdge);
  assert.deepEqual(copy.walk(5, [0.01, 0.01], [1, 0], 0.7), original.walk(5, [0.01, 0.01], [1, 0], 0.7));
  const rotation = new Float64Array(m.positions.length);
  for (let v = 0; v < m.positions.length / 3; v++) rotation.set([-m.positions[3 * v + 1], m.positions[3 * v], 0], 3 * v);
  const opts = { spacing: 0.2 };
  assert.deepEqual(traceStreamlines(copy, rotation, opts), traceStreamlines(original, rotation, opts));
  assert.deepEqual(copy.angleDefects(), original.angleDefects());
});

test("a preview's face vectors and one-form, derived from its vertex vectors, are exact for a linear field", () => {
  // V(p) = A p on a plane (A a rotation plus a stretch): linear, so a face's corner mean is V at its barycentre
  // and the trapezoid rule along an edge is the exact line integral of V · dp.
  const m = grid(7, 1.5), s = surfaceOf(m);
  const V = vertexField(m, ([x, y]) => [0.3 * x - 1.2 * y, 0.9 * x + 0.5 * y, 0]);
  const faces = faceVectorsOfVertexField(s, V);
  for (let f = 0; f < s.nF; f++) {
    const [cx, cy] = s.centroid(f);
    const want = [0.3 * cx - 1.2 * cy, 0.9 * cx + 0.5 * cy, 0];
    assert.ok(dist(Array.from(faces.subarray(3 * f, 3 * f + 3)), want) < 1e-12, `face ${f}`);
  }
  const oneForm = oneFormOfVertexField(s, V);
  assert.equal(oneForm.length, m.edges.length / 2);
  for (let e = 0; e < m.edges.length / 2; e++) {
    // ∫₀¹ A(p + t d) · d dt = (A p) · d + ½ dᵀ A d along the segment from p to q = p + d.
    const [px, py] = vertexOf(m, m.edges[2 * e]), [qx, qy] = vertexOf(m, m.edges[2 * e + 1]);
    const A = (x, y) => [0.3 * x - 1.2 * y, 0.9 * x + 0.5 * y];
    const [dx, dy] = [qx - px, qy - py], Ap = A(px, py), Ad = A(dx, dy);
    const want = Ap[0] * dx + Ap[1] * dy + 0.5 * (dx * Ad[0] + dy * Ad[1]);
    assert.ok(Math.abs(oneForm[e] - want) < 1e-12, `edge ${e}: ${oneForm[e]} vs ${want}`);
  }
  // On a curved surface the face vectors lie in the faces' planes; an N-field has no one-form.
  const sphere = icosphere(2), ss = surfaceOf(sphere);
  const W = vertexField(sphere, ([x, y, z]) => [-y, x, 0.4 * z]);
  const onSphere = faceVectorsOfVertexField(ss, W);
  for (let f = 0; f < ss.nF; f++) assert.ok(Math.abs(dot(Array.from(onSphere.subarray(3 * f, 3 * f + 3)), Array.from(ss.normals.subarray(3 * f, 3 * f + 3)))) < 1e-12);
  assert.ok(oneFormOfVertexField(ss, W, 2).every((x) => x === 0));
});

// The preview's coarse stand-in and its map (web/core/preview/), against independent truth: the coarse mesh is a
// manifold, consistently oriented surface on the fine mesh's own vertices (checked here edge by edge and fan by
// fan, not with the module's own repair code); on a plane the map puts every fine vertex exactly where it is; a
// constant field on the coarse mesh comes back constant on every fine face and vertex, and its 1-form is the
// field's line integral along every fine edge; a stroke's points land on the coarse surface where they were.
import assert from 'node:assert/strict';
import test from 'node:test';
import { COARSE_FACES, coarseMesh } from '../../web/core/preview/coarse-mesh.js';
import { torus } from '../../web/core/preview/warm-up.js';
import { SurfaceMap } from '../../web/core/preview/surface-map.js';

// An n × n grid of squares on z = 0, jittered inside, split into triangles along alternating diagonals.
function jitteredPlane(n, seed = 7) {
  let s = seed;
  const rand = () => ((s = (s * 1103515245 + 12345) % 2147483648) / 2147483648) - 0.5;
  const P = [], T = [];
  for (let j = 0; j <= n; j++)
    for (let i = 0; i <= n; i++) {
      const inner = i > 0 && j > 0 && i < n && j < n;
      P.push(i + (inner ? 0.3 * rand() : 0), j + (inner ? 0.3 * rand() : 0), 0);
    }
  const v = (i, j) => j * (n + 1) + i;
  for (let j = 0; j < n; j++)
    for (let i = 0; i < n; i++) {
      if ((i + j) % 2) T.push(v(i, j), v(i + 1, j), v(i + 1, j + 1), v(i, j), v(i + 1, j + 1), v(i, j + 1));
      else T.push(v(i, j), v(i + 1, j), v(i, j + 1), v(i + 1, j), v(i + 1, j + 1), v(i, j + 1));
    }
  return { positions: Float64Array.from(P), triangles: Int32Array.from(T) };
}

function edgesOf(triangles) {
  const seen = new Set(), E = [];
  for (let f = 0; f < triangles.length / 3; f++)
    for (let k = 0; k < 3; k++) {
      const a = triangles[3 * f + k], b = triangles[3 * f + ((k + 1) % 3)];
      const key = `${Math.min(a, b)},${Math.max(a, b)}`;
      if (!seen.has(key)) seen.add(key), E.push(Math.min(a, b), Math.max(a, b));
    }
  return Int32Array.from(E);
}

// Every undirected edge has one or two faces, traversed in opposite directions; every vertex's faces form one fan.
function assertManifold(triangles) {
  const directed = new Map();
  for (let f = 0; f < triangles.length / 3; f++)
    for (let k = 0; k < 3; k++) {
      const key = `${triangles[3 * f + k]},${triangles[3 * f + ((k + 1) % 3)]}`;
      assert.ok(!directed.has(key), `directed edge ${key} twice`);
      directed.set(key, f);
    }
  const around = new Map();
  for (let f = 0; f < triangles.length / 3; f++)
    for (let k = 0; k < 3; k++) around.set(triangles[3 * f + k], [...(around.get(triangles[3 * f + k]) ?? []), f]);
  for (const [v, faces] of around) {
    // Walk the fan through shared edges at v: it must reach every face of v.
    const reached = new Set([faces[0]]), queue = [faces[0]];
    while (queue.length) {
      const f = queue.pop();
      const others = [0, 1, 2].map((k) => triangles[3 * f + k]).filter((w) => w !== v);
      for (const g of faces)
        if (!reached.has(g) && [0, 1, 2].some((k) => others.includes(triangles[3 * g + k]))) reached.add(g), queue.push(g);
    }
    assert.equal(reached.size, faces.length, `vertex ${v} pinches ${faces.length} faces into more than one fan`);
  }
}

const point = (P, T, face, bary) => [0, 1, 2].map((c) => bary[0] * P[3 * T[3 * face] + c] + bary[1] * P[3 * T[3 * face + 1] + c] + bary[2] * P[3 * T[3 * face + 2] + c]);

test('preview: the coarse mesh is a manifold on the fine vertices; the map is exact on a plane', async () => {
  const fine = jitteredPlane(60);
  fine.edges = edgesOf(fine.triangles);
  const coarse = await coarseMesh(fine.positions, fine.triangles);
  const nF = fine.triangles.length / 3, nC = coarse.triangles.length / 3;
  assert.ok(nC <= Math.ceil(nF / 4) && nC > nF / 20, `${nC} coarse faces of ${nF}`);
  assertManifold(coarse.triangles);
  coarse.fineVertex.forEach((v, c) => assert.deepEqual([...coarse.positions.subarray(3 * c, 3 * c + 3)], [...fine.positions.subarray(3 * v, 3 * v + 3)]));

  const map = new SurfaceMap(fine, coarse);
  let worst = 0;
  for (let v = 0; v < map.nV; v++) {
    const q = point(coarse.positions, coarse.triangles, map.vertexFace[v], map.vertexBary.subarray(3 * v, 3 * v + 3));
    worst = Math.max(worst, Math.hypot(...q.map((x, k) => x - fine.positions[3 * v + k])));
  }
  assert.ok(worst < 1e-9, `a fine vertex mapped ${worst} away from itself`);
  // Face centres: on the plane exactly where a face lies in one coarse face, else on the closest of its
  // corners' coarse faces, within a fine edge of the centre.
  let exact = 0, far = 0;
  for (let f = 0; f < nF; f++) {
    const q = point(coarse.positions, coarse.triangles, map.faceOnCoarse(f), map.faceBary.subarray(3 * f, 3 * f + 3));
    const c = point(fine.positions, fine.triangles, f, [1 / 3, 1 / 3, 1 / 3]);
    const d = Math.hypot(...q.map((x, k) => x - c[k]));
    if (d < 1e-9) exact++;
    far = Math.max(far, d);
  }
  assert.ok(exact > 0.95 * nF, `${exact} of ${nF} face centres mapped exactly`);
  assert.ok(far < 1, `a face centre mapped ${far} away (the fine edges are about 1 long)`);

  // A constant field on the coarse mesh comes back constant, at the vertices and, when asked, at the faces.
  const u = [0.6, -0.8, 0];
  const cv = new Float64Array(coarse.positions.length).map((_, i) => u[i % 3]);
  const cf = new Float64Array(3 * nC).map((_, i) => u[i % 3]);
  const out = { vertexVectors: new Float64Array(fine.positions.length), faceVectors: new Float64Array(3 * nF) };
  const field = map.fieldOnFine(cf, cv, 1, out);
  for (const arr of [field.faceVectors, field.vertexVectors]) for (let i = 0; i < arr.length; i++) assert.ok(Math.abs(arr[i] - u[i % 3]) < 1e-12);
  const vertexOnly = map.fieldOnFine(cf, cv, 1, { vertexVectors: new Float64Array(fine.positions.length), faceVectors: null });
  assert.equal(vertexOnly.faceVectors, null, 'no face vectors unless asked');
  assert.deepEqual(vertexOnly.vertexVectors, field.vertexVectors);

  // A stroke's points stay where they were (the plane has no distance to lose); the polyline keeps one point per
  // coarse face entered, its first and its last.
  const points = [100, 161, 222, 283, 344, 405].map((face) => ({ face, bary: [0.2, 0.3, 0.5] }));
  const spec = map.specOnCoarse({ type: 'stroke', points, strength: 1, weight: 1e4 });
  for (const q of spec.points) {
    const there = point(coarse.positions, coarse.triangles, q.face, q.bary);
    const near = points.some((p) => Math.hypot(...point(fine.positions, fine.triangles, p.face, p.bary).map((x, k) => x - there[k])) < 1e-9);
    assert.ok(near, 'a coarse stroke point is not one of the fine points');
  }
  assert.deepEqual(spec.points[0], map.pointOnCoarse(points[0]));
  assert.deepEqual(spec.points.at(-1), map.pointOnCoarse(points.at(-1)));
  for (let i = 1; i < spec.points.length; i++) assert.notEqual(spec.points[i].face, spec.points[i - 1].face);
});

test('preview: a prescribed singularity goes to the coarse vertex it stands on; feature edits stay fine', async () => {
  const fine = jitteredPlane(40);
  fine.edges = edgesOf(fine.triangles);
  const coarse = await coarseMesh(fine.positions, fine.triangles);
  const map = new SurfaceMap(fine, coarse);
  // A fine vertex the coarse mesh kept is that coarse vertex (the map is exact on a plane).
  const kept = [...coarse.fineVertex].slice(0, 20);
  for (const [c, v] of kept.entries()) {
    assert.equal(map.specOnCoarse({ type: 'singularity', vertex: v, index: 1 }).vertex, c, `fine vertex ${v}`);
  }
  // Any other: a corner of the coarse face it lies in.
  const other = [...Array(map.nV).keys()].find((v) => !coarse.fineVertex.includes(v));
  const corner = map.specOnCoarse({ type: 'singularity', vertex: other, index: -1 }).vertex;
  const face = map.vertexFace[other];
  assert.ok([0, 1, 2].some((k) => coarse.triangles[3 * face + k] === corner), 'a corner of its coarse face');
  const doc = {
    constraints: [],
    singularities: [{ vertex: kept[0], index: 1 }, { vertex: kept[1], index: -1 }],
    featureAngle: 30,
    featureEdges: { add: [[fine.edges[0], fine.edges[1]]], remove: [] },
    mesh: { vertices: map.nV },
  };
  const onCoarse = map.designOnCoarse(doc);
  assert.deepEqual(onCoarse.singularities, [{ vertex: 0, index: 1 }, { vertex: 1, index: -1 }]);
  assert.equal('featureAngle' in onCoarse, false, "no features on the coarse mesh: its creases are the decimation's");
  assert.equal('featureEdges' in onCoarse, false, 'the fine edges are no edges of the coarse mesh');
  assert.equal('mesh' in onCoarse, false);
});

// Edges, edges with one face, and the loops those form.
function boundaryOf(triangles) {
  const count = new Map();
  for (let f = 0; f < triangles.length / 3; f++)
    for (let k = 0; k < 3; k++) {
      const a = triangles[3 * f + k], b = triangles[3 * f + ((k + 1) % 3)];
      const key = `${Math.min(a, b)},${Math.max(a, b)}`;
      count.set(key, (count.get(key) ?? 0) + 1);
    }
  const parent = new Map();
  const find = (v) => (parent.get(v) === v ? v : (parent.set(v, find(parent.get(v))), parent.get(v)));
  let boundaryEdges = 0;
  for (const [key, n] of count) {
    if (n !== 1) continue;
    boundaryEdges++;
    const [a, b] = key.split(',').map(Number);
    for (const v of [a, b]) if (!parent.has(v)) parent.set(v, v);
    parent.set(find(a), find(b));
  }
  const boundaryLoops = new Set([...parent.keys()].map(find)).size;
  return { edges: count.size, boundaryEdges, boundaryLoops };
}

// A scan-sized mesh is clustered before the collapses (coarse-mesh.js): the result must still be a manifold on
// the fine vertices, of the fine surface's genus (pinched faces dropped leave small holes), near the target size, and on the
// surface: every coarse face centre within a small distance of the exact torus.
test('preview: a mesh past five times the target is clustered first, and stays a manifold torus on the surface', async () => {
  const R = 1, r = 0.4;
  const fine = torus(480, 240, R, r); // 230,400 faces
  const coarse = await coarseMesh(fine.positions, fine.triangles);
  const nC = coarse.triangles.length / 3;
  assert.ok(nC <= COARSE_FACES && nC > 0.8 * COARSE_FACES, `${nC} coarse faces`);
  assertManifold(coarse.triangles);
  coarse.fineVertex.forEach((v, c) => assert.deepEqual([...coarse.positions.subarray(3 * c, 3 * c + 3)], [...fine.positions.subarray(3 * v, 3 * v + 3)]));
  // Clustering can pinch a few faces, which the repairs drop: small holes, never a change of genus.
  const { edges, boundaryEdges, boundaryLoops } = boundaryOf(coarse.triangles);
  const chi = coarse.positions.length / 3 - edges + nC;
  assert.equal((2 - chi - boundaryLoops) / 2, 1, `genus 1 (χ ${chi}, ${boundaryLoops} holes)`);
  assert.ok(boundaryEdges <= 1e-3 * edges, `${boundaryEdges} of ${edges} edges on holes`);
  let worst = 0;
  for (let f = 0; f < nC; f++) {
    const [x, y, z] = point(coarse.positions, coarse.triangles, f, [1 / 3, 1 / 3, 1 / 3]);
    worst = Math.max(worst, Math.abs(Math.hypot(Math.hypot(x, y) - R, z) - r));
  }
  assert.ok(worst < 0.02, `a coarse face centre ${worst} off the torus (its tube's radius is ${r})`);
});

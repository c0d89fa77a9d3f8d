#!/usr/bin/env node
// SPDX-License-Identifier: GPL-2.0-or-later
// Smoke test of the wasm core under node: node wasm/test-node.mjs [path/to/tvf_core.mjs]
// Loads build-wasm/tvf_core.mjs (build it with `npm run build:wasm`), designs on an icosphere made here, and
// checks the binding's contract (error strings instead of exceptions, ids, views, JSON read-outs, a stroke
// whose removal restores the field). Prints "N passed, M failed"; exits 1 on any failure.
import { execFileSync } from 'node:child_process';
import { mkdtempSync, readFileSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { dirname, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { icosphereOff as icosphere } from '../tests/icosphere.mjs';
import { faceNormals, halfEdgeNeighbours, vertexFaceMap } from '../web/geometry/mesh-geometry.js';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const modulePath = resolve(process.argv[2] ?? resolve(ROOT, 'build-wasm/tvf_core.mjs'));

let passed = 0;
let failed = 0;
function check(name, condition, detail = '') {
  if (condition) {
    passed++;
    console.log(`ok   ${name}`);
  } else {
    failed++;
    console.log(`FAIL ${name}${detail ? `: ${detail}` : ''}`);
  }
}
function finish() {
  console.log(`${passed} passed, ${failed} failed`);
  process.exit(failed ? 1 : 0);
}

// A strip of adjacent faces (barycentres) starting at `start`, crossing up to `crossings` edges.
function faceStrip(triangles, start, crossings) {
  const edgeFaces = new Map();
  const key = (a, b) => (a < b ? `${a},${b}` : `${b},${a}`);
  for (let g = 0; g < triangles.length / 3; ++g)
    for (let k = 0; k < 3; ++k) {
      const e = key(triangles[3 * g + k], triangles[3 * g + ((k + 1) % 3)]);
      if (!edgeFaces.has(e)) edgeFaces.set(e, []);
      edgeFaces.get(e).push(g);
    }
  const visited = [start];
  const seen = new Set(visited);
  let f = start;
  for (let s = 0; s < crossings; ++s) {
    let next = -1;
    for (let k = 0; k < 3 && next < 0; ++k)
      for (const g of edgeFaces.get(key(triangles[3 * f + k], triangles[3 * f + ((k + 1) % 3)])))
        if (!seen.has(g)) { next = g; break; }
    if (next < 0) break;
    visited.push(next);
    seen.add(next);
    f = next;
  }
  const flat = new Float64Array(4 * visited.length);
  visited.forEach((g, k) => flat.set([g, 1 / 3, 1 / 3, 1 / 3], 4 * k));
  return flat;
}

function maxAbsDiff(a, b) {
  let m = 0;
  for (let i = 0; i < a.length; ++i) m = Math.max(m, Math.abs(a[i] - b[i]));
  return m;
}
function maxAbs(a) {
  return a.reduce((m, x) => Math.max(m, Math.abs(x)), 0);
}

// ------------------------------------------------------------------ load the module
let createTvfCore;
try {
  createTvfCore = (await import(pathToFileURL(modulePath).href)).default;
} catch (err) {
  check(`import ${modulePath}`, false, `${err.message} (run npm run build:wasm first)`);
  finish();
}
let Module;
try {
  Module = await createTvfCore();
  check('module instantiates by itself under node', true);
} catch (err) {
  // Fallback that works on any node: hand the binary over.
  check('module instantiates by itself under node', false, String(err));
  Module = await createTvfCore({ wasmBinary: readFileSync(modulePath.replace(/\.mjs$/, '.wasm')) });
}
check('module instantiates with wasmBinary', !!(await createTvfCore({
  wasmBinary: readFileSync(modulePath.replace(/\.mjs$/, '.wasm')),
})).Designer);

const warm = Module.warmUp(3, 1);
check('warmUp runs', warm > 0, `returned ${warm}`);

const d = new Module.Designer();
check('no mesh: solve reports an error string', d.solve() === 'no mesh loaded', d.solve());
check('no mesh: addSource gives -1 and lastError', d.addSource(0, 1) === -1 && d.lastError() === 'no mesh loaded');
check('no mesh: empty views', d.positions().length === 0 && d.triangles().length === 0);
check('no mesh: infoJson is an unusable report', JSON.parse(d.infoJson()).usable === false);

const bad = d.loadMesh(new TextEncoder().encode('OFF\n3 1 0\n0 0 0\n1 0 0\n'), 'off');
check('truncated OFF: error string', typeof bad === 'string' && bad.length > 0, bad);
check('unknown format: error string', d.loadMesh(new Uint8Array([1, 2]), 'stl').includes('unknown mesh format'));

const levels = 3;
const off = icosphere(levels);
const loaded = d.loadMesh(new TextEncoder().encode(off), 'off');
check('loadMesh(off) succeeds', loaded === '', loaded);
const info = JSON.parse(d.infoJson());
const nV = 10 * 4 ** levels + 2, nF = 20 * 4 ** levels, nE = 30 * 4 ** levels;
check('infoJson counts', info.vertices === nV && info.faces === nF && info.edges === nE && info.genus === 0,
  JSON.stringify(info));
check('positions view', d.positions() instanceof Float64Array && d.positions().length === 3 * nV);
check('triangles view', d.triangles() instanceof Int32Array && d.triangles().length === 3 * nF);
check('edges view', d.edges() instanceof Int32Array && d.edges().length === 2 * nE);
check('cornerUVs view (empty for OFF)', d.cornerUVs() instanceof Float32Array && d.cornerUVs().length === 0);

// A failed load keeps the current mesh.
const keep = d.loadMesh(new TextEncoder().encode('OFF\n1 1 0\n0 0 0\n3 0 0 0\n'), '');
check('failed load keeps the previous mesh', keep !== '' && d.positions().length === 3 * nV, keep);

// A load in steps (big meshes, web/core/worker/load-ops.js): read, then open (checks, settings), then commit; the
// mesh read is the mesh opened, vertex for vertex, and every step's failure keeps the current model.
{
  const before = Float64Array.from(d.oneForm());
  const other = new TextEncoder().encode(icosphere(2));
  const read = JSON.parse(d.readModel(other, 'off'));
  check('readModel: counts of the mesh read', read.ok && read.vertices === 162 && read.faces === 320, JSON.stringify(read));
  const parsedP = Float64Array.from(d.parsedPositions()), parsedT = Int32Array.from(d.parsedTriangles());
  check('readModel: the mesh read is viewable', parsedP.length === 3 * 162 && parsedT.length === 3 * 320);
  const opened = JSON.parse(d.openParsed('{"gamma": 0.5}', ''));
  check('openParsed succeeds', opened.ok && opened.settingsError === null, JSON.stringify(opened));
  check('openParsed: the mesh opened is the mesh read',
    d.pendingPositions().every((x, k) => x === parsedP[k]) && d.pendingTriangles().every((x, k) => x === parsedT[k]));
  check('openParsed: the mesh read is consumed', d.parsedPositions().length === 0);
  // The picking's adjacency from the core's topology is what the page derived from the triangles itself; the
  // normals to the last bit or one unit in it (the core's length sums the squares in another order).
  const adjacency = d.pendingFaceAdjacency(), round = vertexFaceMap(parsedT, 162);
  const near = (a, b, tol = 0) => a.length === b.length && a.every((x, k) => Math.abs(x - b[k]) <= tol);
  check('pendingFaceAdjacency: the page\'s half-edge pairs, faces round vertices and face normals',
    near(adjacency.neighbour, halfEdgeNeighbours(parsedT, 162)) && near(adjacency.vertexFaceStart, round.start) &&
    near(adjacency.vertexFaces, round.faces) && near(adjacency.normals, faceNormals(parsedP, parsedT), 2.3e-16) &&
    adjacency.neighbour instanceof Int32Array && adjacency.normals instanceof Float64Array);
  check('openParsed: the current model is untouched until the commit', d.positions().length === 3 * nV &&
    d.oneForm().every((x, k) => x === before[k]));
  const committed = JSON.parse(d.commitModel());
  check('commitModel after openParsed', committed.ok && d.positions().length === 3 * 162 && d.gamma() === 0.5, JSON.stringify(committed));
  const badRead = JSON.parse(d.readModel(new TextEncoder().encode('OFF\n3 1 0\n0 0 0\n'), 'off'));
  check('readModel of a broken file: error, model kept', !badRead.ok && badRead.error.length > 0 && d.positions().length === 3 * 162, JSON.stringify(badRead));
  const nothing = JSON.parse(d.openParsed('', ''));
  check('openParsed with nothing read: error', !nothing.ok && /no model has been read/.test(nothing.error), JSON.stringify(nothing));
  // Non-manifold: read fine, refused when opened, by name.
  JSON.parse(d.readModel(new TextEncoder().encode('OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n'), 'off'));
  const refused = JSON.parse(d.openParsed('', ''));
  check('openParsed of a non-manifold mesh: refused by name, model kept', !refused.ok && /non-manifold/.test(refused.error) &&
    d.positions().length === 3 * 162, JSON.stringify(refused));
  check('back to the icosphere', d.loadMesh(new TextEncoder().encode(off), 'off') === '' && d.positions().length === 3 * nV);
}

// The field's ordering kept per mesh (web/core/worker/ordering-cache.js): read out of one designer after its
// commit and adopted by another before its own, on the same mesh: the analysis reused and the same field; a
// permutation that is not one is refused, and another mesh's key differs.
{
  const mesh = new TextEncoder().encode(icosphere(3));
  const open = (designer, adopt) => {
    designer.readModel(mesh, 'off');
    designer.openParsed('', '');
    const key = designer.pendingOrderingKey();
    const adopted = adopt ? adopt(designer) : false;
    designer.commitModel();
    designer.addSource(0, 1);
    designer.addSink(100, 1);
    designer.solve();
    return { key, adopted, reused: JSON.parse(designer.statsJson()).analysisReused, oneForm: Float64Array.from(designer.oneForm()) };
  };
  const a = new Module.Designer();
  const first = open(a);
  const kept = JSON.parse(a.keptOrderingJson());
  const perm = Int32Array.from(a.keptOrderingPerm());
  check('keptOrderingJson: the permutation of every edge, METIS, not reused', kept.n === first.oneForm.length &&
    perm.length === kept.n && kept.metis === true && kept.reused === false && /^[0-9a-f]{16}$/.test(kept.pattern), JSON.stringify(kept));
  const b = new Module.Designer();
  const again = open(b, (x) => x.adoptPendingOrdering(perm, kept.pattern, kept.metis, kept.dissection, null));
  check('adoptPendingOrdering: adopted, the analysis reused, the same key', again.adopted && again.reused && again.key === first.key,
    JSON.stringify({ adopted: again.adopted, reused: again.reused }));
  check('adoptPendingOrdering: the same field', maxAbsDiff(again.oneForm, first.oneForm) <= 1e-12 * maxAbs(first.oneForm));
  const c = new Module.Designer();
  const bad = Int32Array.from(perm);
  bad[1] = bad[0];
  const refused = open(c, (x) => x.adoptPendingOrdering(bad, kept.pattern, kept.metis, kept.dissection, null));
  check('adoptPendingOrdering: not a permutation, refused; ordered anew', !refused.adopted && !refused.reused &&
    maxAbsDiff(refused.oneForm, first.oneForm) <= 1e-12 * maxAbs(first.oneForm));
  c.readModel(new TextEncoder().encode(icosphere(2)), 'off');
  c.openParsed('', '');
  check('pendingOrderingKey: another mesh, another key', c.pendingOrderingKey() !== first.key, c.pendingOrderingKey());
  for (const x of [a, b, c]) x.delete();
}

// The symbolic factor kept with the ordering (solver/kept_symbolic.h): asked for before a commit, read out after
// it and adopted with the ordering, the next opening analyzes nothing and solves the same field; one that does
// not fit the matrix (a row out of range) is refused and the analysis runs.
{
  const mesh = new TextEncoder().encode(icosphere(5)); // big enough to factor by supernodes
  const open = (designer, adopt) => {
    designer.readModel(mesh, 'off');
    designer.openParsed('', '');
    const adopted = adopt(designer);
    designer.keepPendingSymbolic(true);
    designer.commitModel();
    designer.addSource(0, 1);
    designer.solve();
    const stats = JSON.parse(designer.statsJson());
    return { adopted, stats, oneForm: Float64Array.from(designer.oneForm()) };
  };
  const a = new Module.Designer();
  const first = open(a, () => false);
  const kept = JSON.parse(a.keptOrderingJson());
  const perm = Int32Array.from(a.keptOrderingPerm());
  const bytes = Uint8Array.from(a.keptSymbolicBytes());
  a.releaseKeptOrdering();
  check('keptOrderingJson: a symbolic factor kept, its bytes let go with releaseKeptOrdering', kept.symbolic === true &&
    bytes.length > 0 && a.keptSymbolicBytes().length === 0,
    JSON.stringify({ kept, bytes: bytes.length }));
  const adopt = (symbolic) => (x) => x.adoptPendingOrdering(perm, kept.pattern, kept.metis, kept.dissection, symbolic);
  const b = new Module.Designer();
  const again = open(b, adopt(bytes));
  check('adoptPendingOrdering with it: no analysis, the same field', again.adopted && again.stats.analysisReused &&
    again.stats.symbolicReused && maxAbsDiff(again.oneForm, first.oneForm) <= 1e-12 * maxAbs(first.oneForm),
    JSON.stringify({ adopted: again.adopted, symbolic: again.stats.symbolicReused }));
  check('keptOrderingJson after it: nothing new to store (n = 0)', JSON.parse(b.keptOrderingJson()).n === 0);
  const bad = bytes.subarray(0, bytes.length - 1); // cut short
  const c = new Module.Designer();
  const refused = open(c, adopt(bad));
  check('a symbolic factor that does not fit: refused, analyzed anew, the same field', refused.adopted &&
    refused.stats.analysisReused && !refused.stats.symbolicReused &&
    maxAbsDiff(refused.oneForm, first.oneForm) <= 1e-12 * maxAbs(first.oneForm));
  const replaced = JSON.parse(c.keptOrderingJson());
  check('keptOrderingJson after it: the new analysis to store', replaced.n === kept.n && replaced.symbolic === true &&
    Uint8Array.from(c.keptSymbolicBytes()).every((x, i) => x === bytes[i]));
  for (const x of [a, b, c]) x.delete();
}

// Source at vertex 0, sink at the antipodal vertex.
const pos = Float64Array.from(d.positions());
let far = 0, best = Infinity;
for (let v = 0; v < nV; ++v) {
  const dot = pos[0] * pos[3 * v] + pos[1] * pos[3 * v + 1] + pos[2] * pos[3 * v + 2];
  if (dot < best) { best = dot; far = v; }
}
check('setBoundaryJson("free")', d.setBoundaryJson('"free"') === '');
check('setBoundaryJson(bogus) reports', d.setBoundaryJson('"bogus"') !== '');
check('setBoundaryJson(invalid JSON) reports', d.setBoundaryJson('{') !== '');
check('setGamma(-1) reports', d.setGamma(-1) !== '');
check('setGamma(0)', d.setGamma(0) === '');
check('factor', d.factor() === '');
const src = d.addSource(0, 1);
const snk = d.addSink(far, 1);
check('addSource/addSink ids', src > 0 && snk > 0 && snk !== src, `${src} ${snk}`);
check('solve', d.solve() === '');
const sing = JSON.parse(d.singularitiesJson());
const at = (v) => sing.find((s) => s.vertex === v);
check('two singularities, at the source and the sink, index +1 each',
  sing.length === 2 && at(0) && at(far) && Math.abs(at(0).index - 1) < 1e-9 && Math.abs(at(far).index - 1) < 1e-9,
  JSON.stringify(sing));
check('oneForm view', d.oneForm() instanceof Float64Array && d.oneForm().length === nE && maxAbs(d.oneForm()) > 0);
check('faceVectors view', d.faceVectors().length === 3 * nF);
check('vertexVectors view', d.vertexVectors().length === 3 * nV);
const stats = JSON.parse(d.statsJson());
check('statsJson', typeof stats === 'object' && stats !== null && Object.keys(stats).length > 0, d.statsJson());
const field = JSON.parse(d.fieldJson());
check('fieldJson', field && Array.isArray(field.oneForm) && field.oneForm.length === nE);

// A stroke changes the field; removing it (a downdate) restores it.
const before = Float64Array.from(d.oneForm());
const strip = faceStrip(d.triangles(), 5, 20);
const stroke = d.addStroke(strip, 2.0, 1.0);
check('addStroke id', stroke > 0, d.lastError());
check('solve with stroke', d.solve() === '');
const withStroke = Float64Array.from(d.oneForm());
check('stroke changes the field', maxAbsDiff(withStroke, before) > 1e-3 * maxAbs(before));
check('setWeight', d.setWeight(stroke, 3.0) === true, d.lastError());
check('setStrength', d.setStrength(stroke, 1.5) === true, d.lastError());
check('remove(stroke)', d.remove(stroke) === true, d.lastError());
check('solve after removal', d.solve() === '');
const diff = maxAbsDiff(d.oneForm(), before);
check('removing the stroke restores the field', diff <= 1e-8 * maxAbs(before), `max diff ${diff}`);
check('singularities back to two', JSON.parse(d.singularitiesJson()).length === 2);

// Error paths: -1 / false plus lastError, never a throw.
check('addSource(bad vertex) = -1', d.addSource(nV + 5, 1) === -1 && d.lastError().includes('vertex'), d.lastError());
check('addVector(bad face) = -1', d.addVector(-1, 1, 0, 0, 1) === -1 && d.lastError() !== '');
check('addVortex(1.5) = -1', d.addVortex(1.5, 1) === -1 && d.lastError().includes('integer'), d.lastError());
check('addEdge(non-edge) = -1', d.addEdge(0, far, 1, 1) === -1 && d.lastError() !== '');
check('addStroke(bad length) = -1', d.addStroke(new Float64Array(3), 1, 1) === -1 && d.lastError() !== '');
check('addStroke(bad face) = -1', d.addStroke(new Float64Array([nF, 0.3, 0.3, 0.4, 0, 0.3, 0.3, 0.4]), 1, 1) === -1);
check('remove(unknown) = false', d.remove(9999) === false && d.lastError().includes('9999'), d.lastError());
check('setWeight on a source = false', d.setWeight(src, 2) === false && d.lastError() !== '');
check('applyDesignJson(invalid) reports', d.applyDesignJson('{') !== '');

// The other constraint kinds, and a design round trip.
const tri = d.triangles();
const vec = d.addVector(7, 1, 0, 0, 1);
const edge = d.addEdge(tri[0], tri[1], 0.2, 1);
const vort = d.addVortex(11, 0.5);
check('addVector/addEdge/addVortex ids', vec > 0 && edge > 0 && vort > 0, d.lastError());
check('solve with all kinds', d.solve() === '');
check('constraintIdsJson in design order', JSON.stringify(JSON.parse(d.constraintIdsJson())) ===
  JSON.stringify([src, snk, vec, edge, vort]), d.constraintIdsJson());
const design = d.designJson();
const solved = Float64Array.from(d.oneForm());
const d2 = new Module.Designer();
check('second designer loads (format sniffed, ArrayBuffer)', d2.loadMesh(new TextEncoder().encode(off).buffer, '') === '');
check('setMetisOrdering(false) selects AMD', d2.setMetisOrdering(false) === '', d2.lastError());
check('applyDesignJson round trip', d2.applyDesignJson(design) === '' && d2.solve() === '', d2.lastError());
check('replayed design gives the same field', maxAbsDiff(d2.oneForm(), solved) <= 1e-8 * maxAbs(solved));
check('designJson is JSON', (() => { try { JSON.parse(design); return true; } catch { return false; } })());
d2.delete();
d.delete();

// METIS in wasm: the nested dissection of the mesh's vertex graph (parts of at most 1000 edges) and AMD give
// different factors and the same field; the ordering is reused while the pattern does not change.
{
  const big = new TextEncoder().encode(icosphere(5)); // 30720 edges
  const fields = {}, stats = {};
  for (const metis of [true, false]) {
    const e = new Module.Designer();
    check(`icosphere(5) loads (${metis ? 'METIS' : 'AMD'})`, e.loadMesh(big, 'off') === '', e.lastError());
    e.setMetisOrdering(metis);
    const t = e.triangles();
    e.addStroke(faceStrip(t, 100, 30), 1, 1);
    e.addSource(t[0], 1);
    e.addVortex(5000, -0.5);
    check(`solve (${metis ? 'METIS' : 'AMD'})`, e.solve() === '', e.lastError());
    fields[metis] = Float64Array.from(e.oneForm());
    stats[metis] = JSON.parse(e.statsJson());
    if (metis) {
      // A boundary condition cannot change a closed surface's matrix: refactored with the same ordering.
      check('setBoundary on a closed surface keeps the ordering',
        e.setBoundaryJson('"tangential"') === '' && e.factor() === '' && JSON.parse(e.statsJson()).analysisReused === true,
        e.statsJson());
      e.setGamma(0.01);
      e.factor();
      check('gamma > 0 changes the pattern: a new ordering', JSON.parse(e.statsJson()).analysisReused === false);
    }
    e.delete();
  }
  check('default ordering is METIS nested dissection of the vertex graph', /METIS nested dissection of the mesh's vertex graph/.test(stats[true].factorKind), stats[true].factorKind);
  check('AMD selectable', /AMD/.test(stats[false].factorKind), stats[false].factorKind);
  // wasm's backward substitution goes by supernodes (native tests compare it with CHOLMOD's by columns).
  check('backward substitution by supernodes, both orderings',
    [true, false].every((m) => /backward substitution by supernodes/.test(stats[m].factorKind)), stats[false].factorKind);
  check('METIS and AMD factors differ in fill', stats[true].nnzPerRowL !== stats[false].nnzPerRowL,
    `${stats[true].nnzPerRowL} vs ${stats[false].nnzPerRowL}`);
  const diff = maxAbsDiff(fields[true], fields[false]) / maxAbs(fields[false]);
  check('METIS and AMD give the same field (1e-9)', diff <= 1e-9, `relative max difference ${diff}`);
}
// The update kernel (cholmod_updown, patched to update pairs of rows in simd128 lanes: wasm/patches): strokes
// crossing 1 to 50 edges take every rank from 1 to 8 and several passes; after each update and each downdate
// the solve's backward-error check passes without refactoring (a wrong downdate would make it refactor, which
// hides the error from the field), and the fields equal fresh factorizations'.
{
  const e = new Module.Designer();
  e.loadMesh(new TextEncoder().encode(icosphere(5)), 'off'); // 30720 edges
  const t = e.triangles();
  e.addSource(t[0], 1);
  e.solve();
  const freshField = () => {
    const f = new Module.Designer();
    f.loadModel(new TextEncoder().encode(icosphere(5)), 'off', '', e.designJson());
    const x = Float64Array.from(f.oneForm());
    f.delete();
    return x;
  };
  const ids = [];
  const incrementalBefore = JSON.parse(e.statsJson()).incrementalSolves;
  const supernodalBefore = JSON.parse(e.statsJson()).supernodalSolves;
  let refactors = 0, worst = 0, solveErrors = '';
  const solveAndCompare = () => {
    solveErrors += e.solve();
    refactors = Math.max(refactors, JSON.parse(e.statsJson()).precisionRefactors);
    const x = freshField();
    worst = Math.max(worst, maxAbsDiff(e.oneForm(), x) / maxAbs(x));
  };
  [1, 2, 3, 4, 5, 6, 7, 8, 9, 13, 50].forEach((crossings, k) => {
    ids.push(e.addStroke(faceStrip(t, 211 * k + 17, crossings), 1, 0.5 + k));
    solveAndCompare();
  });
  while (ids.length) {
    e.remove(ids.pop());
    solveAndCompare();
  }
  check('strokes of 1 to 50 edges and their removal solve', solveErrors === '', solveErrors);
  check('... and no solve refactored', refactors === 0, `${refactors}`);
  // Each edit's solve redid the forward substitution only on the paths it changed.
  const incremental = JSON.parse(e.statsJson()).incrementalSolves - incrementalBefore;
  check('... each incrementally', incremental === 2 * 11, `${incremental} incremental solves of ${2 * 11}`);
  const supernodal = JSON.parse(e.statsJson()).supernodalSolves - supernodalBefore;
  check('... and substituting backward by supernodes', supernodal === 2 * 11, `${supernodal} of ${2 * 11}`);
  check('... and every field equals a fresh factorization\'s (1e-9)', worst <= 1e-9, `relative max difference ${worst}`);
  e.delete();
}
// The page's workers hold a stroke's update beside the factor and solve through it (Designer::setDeferredUpdates,
// solver/woodbury_correction.h), putting it into the factor after their reply. Strokes of 1 to 50 edges, the
// update put in after every other one (the rest go in when the next edit comes), then their removal: every
// field equals a fresh factorization's, with no solve refactored, and the held updates were put in later.
{
  const e = new Module.Designer();
  e.loadMesh(new TextEncoder().encode(icosphere(5)), 'off');
  check('setDeferredUpdates', e.setDeferredUpdates(true) === '');
  const t = e.triangles().slice(); // a copy: a view of the heap goes when the heap grows
  e.addSource(t[0], 1);
  e.solve();
  const fresh = new Module.Designer();
  let worst = 0, errors = '', applied = 0, lastApplied = -1;
  const ids = [];
  const compare = () => {
    errors += e.solve();
    fresh.loadModel(new TextEncoder().encode(icosphere(5)), 'off', '', e.designJson());
    worst = Math.max(worst, maxAbsDiff(e.oneForm(), fresh.oneForm()) / maxAbs(fresh.oneForm()));
  };
  [1, 2, 3, 5, 8, 13, 21, 34, 50].forEach((crossings, k) => {
    ids.push(e.addStroke(faceStrip(t, 173 * k + 29, crossings), 1, 0.5 + k));
    compare();
    if (k % 2 === 0) {
      errors += e.applyDeferredUpdates();
      const ms = JSON.parse(e.statsJson()).deferredUpdateMs;
      if (ms !== lastApplied && ms > 0) applied++;
      lastApplied = ms;
    }
  });
  while (ids.length) {
    e.remove(ids.pop());
    compare();
  }
  check('deferred stroke updates: every solve succeeds', errors === '', errors);
  check('... held updates were put into the factor after their solve', applied >= 3, `${applied} of 5`);
  check('... no solve refactored', JSON.parse(e.statsJson()).precisionRefactors === 0);
  check('... and every field equals a fresh factorization\'s (1e-9)', worst <= 1e-9, `relative max difference ${worst}`);
  e.delete();
  fresh.delete();
}
// Threads: the plain module has one, the one built with pthreads (tvf_core_threads.mjs, run here too by
// npm test) one more than the helpers its pool started with (wasm/node-pre.js: the cores less one, at most 7).
// On two threads the factorization's subtrees go side by side (supernodal_cholesky.h), and the field is one
// thread's bit for bit, after the factorization and after strokes; a number of threads the build lacks is cut
// to what it has.
{
  const available = Module.solverThreadsAvailable();
  const threaded = /_threads\.mjs$/.test(modulePath);
  const cores = Math.min(8, Math.max(1, (await import('node:os')).availableParallelism()));
  check(`${threaded ? 'the pthread build' : 'the plain build'} has ${threaded ? cores : 1} thread(s)`,
    available === (threaded ? cores : 1), `${available}`);
  const run = (threads) => {
    const e = new Module.Designer();
    e.loadMesh(new TextEncoder().encode(icosphere(6)), 'off');
    const set = e.setSolverThreads(threads);
    const t = Int32Array.from(e.triangles());  // a view of the heap, which the solves may grow
    e.addSource(t[0], 1);
    e.solve();
    const fields = [Float64Array.from(e.oneForm())];
    for (let k = 0; k < 3; ++k) {
      e.addStroke(faceStrip(t, 97 * k + 5, 30), 1, 1);
      e.solve();
      fields.push(Float64Array.from(e.oneForm()));
    }
    const stats = JSON.parse(e.statsJson());
    const out = { set, threads: e.solverThreads(), kind: stats.factorKind, factorThreads: stats.factorThreads, fields };
    e.delete();
    return out;
  };
  const one = run(1), two = run(2);
  check('setSolverThreads(1) and (2) are accepted', one.set === '' && two.set === '', `${one.set} ${two.set}`);
  check('... and cut to what the build has', one.threads === 1 && two.threads === Math.min(2, available),
    `${one.threads}, ${two.threads}`);
  check('one thread: no threads named in the factor kind', !/threads/.test(one.kind), one.kind);
  check('one thread: the factorization ran on one', one.factorThreads === 1, `${one.factorThreads}`);
  if (available > 1) {
    check('two threads: the backward substitution splits in two', /by supernodes on 2 threads/.test(two.kind), two.kind);
    check('... and the factorization ran on two', two.factorThreads === 2 && /LL' on 2 threads/.test(two.kind),
      two.kind);
  }
  let worst = 0;
  one.fields.forEach((f, k) => {
    const g = two.fields[k];
    let diff = f.length === g.length ? 0 : Infinity, scale = 0;
    for (let i = 0; i < f.length && diff !== Infinity; ++i) {
      diff = Math.max(diff, Math.abs(f[i] - g[i]));
      scale = Math.max(scale, Math.abs(f[i]));
    }
    worst = Math.max(worst, diff / scale);
  });
  check('... and the fields are one thread\'s bit for bit', worst === 0, `${worst}`);
}
// Line and cross fields (symmetry N): the binding's contract, the index invariants, and the page's field against
// the native CLI's (tvf design, built before these tests by npm test) on the same mesh and design: the same
// representative per face to 1e-6 in angle, modulo 2 pi / N.
{
  const e = new Module.Designer();
  e.loadMesh(new TextEncoder().encode(icosphere(3)), 'off');
  e.addSource(0, 1);
  const refused = e.setSymmetry(2);
  check('setSymmetry(2) with a source: refused by name', /1 source/.test(refused) && e.symmetry() === 1, refused);
  e.clearConstraints();
  check('setSymmetry(7): refused', e.setSymmetry(7) !== '' && e.symmetry() === 1);
  for (const n of [2, 4]) {
    check(`setSymmetry(${n})`, e.setSymmetry(n) === '' && e.symmetry() === n);
    check(`N = ${n}: a sink is refused`, e.addSink(3, 1) === -1 && /vector-field notion/.test(e.lastError()), e.lastError());
    e.clearConstraints();
    const id = e.addStroke(faceStrip(Int32Array.from(e.triangles()), 5, 12), 1, 100);
    check(`N = ${n}: stroke id`, id > 0, e.lastError());
    check(`N = ${n}: solve`, e.solve() === '', e.lastError());
    const fv = e.faceVectors();
    let unit = true;
    for (let f = 0; f < fv.length / 3; ++f) unit &&= Math.abs(Math.hypot(fv[3 * f], fv[3 * f + 1], fv[3 * f + 2]) - 1) < 1e-9;
    check(`N = ${n}: unit representatives`, unit);
    const singular = JSON.parse(e.singularitiesJson());
    const sum = singular.reduce((a, s) => a + s.index, 0);
    check(`N = ${n}: indices are multiples of 1/${n} summing to 2`, Math.abs(sum - 2) < 1e-9 &&
      singular.every((s) => Math.abs(s.index * n - Math.round(s.index * n)) < 1e-9), JSON.stringify(singular));
    const dir = mkdtempSync(resolve(tmpdir(), 'tvf-sym-'));
    writeFileSync(resolve(dir, 'mesh.off'), icosphere(3));
    writeFileSync(resolve(dir, 'design.json'), e.designJson());
    const cli = resolve(ROOT, 'build/tvf');
    let agree = false, detail = '';
    try {
      const out = JSON.parse(execFileSync(cli, ['design', resolve(dir, 'mesh.off'), resolve(dir, 'design.json')],
        { maxBuffer: 1 << 28 }).toString());
      let worst = 0;
      const tri = e.triangles(), p = e.positions();
      out.faceDirections.forEach((w, f) => {
        const c = [0, 1, 2].map((k) => tri[3 * f + k]);
        const a = [0, 1, 2].map((k) => p[3 * c[1] + k] - p[3 * c[0] + k]);
        const b = [0, 1, 2].map((k) => p[3 * c[2] + k] - p[3 * c[0] + k]);
        const nrm = [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
        const v = [fv[3 * f], fv[3 * f + 1], fv[3 * f + 2]];
        const cross = [v[1] * w[2] - v[2] * w[1], v[2] * w[0] - v[0] * w[2], v[0] * w[1] - v[1] * w[0]];
        const angle = Math.atan2(cross[0] * nrm[0] + cross[1] * nrm[1] + cross[2] * nrm[2],
          Math.hypot(...nrm) * (v[0] * w[0] + v[1] * w[1] + v[2] * w[2]));
        const reduced = Math.atan2(Math.sin(n * angle), Math.cos(n * angle)) / n;
        worst = Math.max(worst, Math.abs(reduced));
      });
      agree = out.faceDirections.length === fv.length / 3 && worst < 1e-6;
      detail = `worst ${worst}`;
    } catch (err) {
      detail = String(err.message ?? err);
    }
    check(`N = ${n}: page and tvf design agree to 1e-6 rad (mod 2pi/${n})`, agree, detail);
    rmSync(dir, { recursive: true, force: true });
  }
  check('back to N = 1', e.setSymmetry(1) === '' && e.solve() === '' && e.oneForm().length === 30 * 4 ** 3);
  e.delete();
}
// ------------------------------------------------------------------ transactional loads, safe updates
// The model is replaced only when read, checked, factored and solved; any failure leaves the previous one
// fully working (finite field, a stroke can be added).
const t = new Module.Designer();
const ico = (l) => new TextEncoder().encode(icosphere(l));
const finiteField = (des) => des.oneForm().length > 0 && des.oneForm().every(Number.isFinite) &&
  des.faceVectors().every(Number.isFinite);
const strokeWorks = (des) => {
  const id = des.addStroke(faceStrip(des.triangles(), 3, 12), 1.0, 1.0);
  const ok = id > 0 && des.solve() === '' && finiteField(des);
  if (id > 0) des.remove(id);
  return ok && des.solve() === '';
};
let r = JSON.parse(t.loadModel(ico(2), 'off', '', ''));
check('loadModel(icosphere) succeeds', r.ok === true, JSON.stringify(r));
check('loadModel solved the new model', finiteField(t) && t.oneForm().length === 30 * 16);
const src2 = t.addSource(0, 1);
check('a source on the loaded model', src2 > 0 && t.solve() === '', t.lastError());
const beforeLoads = Float64Array.from(t.oneForm());

// A tetrahedron scaled by 1e100: it parses and passes the mesh checks, but cannot be factored.
const hugeTet = 'OFF\n4 4 0\n0 0 0\n1e100 0 0\n0 1e100 0\n0 0 1e100\n3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n';
r = JSON.parse(t.loadModel(new TextEncoder().encode(hugeTet), 'off', '', ''));
check('tetrahedron scaled by 1e100 is refused', r.ok === false && r.error.length > 0, JSON.stringify(r));
check('... the previous model is still loaded', t.oneForm().length === 30 * 16 &&
  JSON.parse(t.designJson()).constraints.length === 1);
check('... its field is finite and unchanged', t.solve() === '' && maxAbsDiff(t.oneForm(), beforeLoads) === 0);
check('... and a stroke works on it', strokeWorks(t), t.lastError());
// The same through the old entry point.
check('loadMesh of the tetrahedron is refused too', t.loadMesh(new TextEncoder().encode(hugeTet), 'off') !== '' &&
  t.oneForm().length === 30 * 16 && strokeWorks(t));

// A mesh whose factor does not fit: the limit is scaled down through the explicit option instead of building
// a 5M-edge mesh; the refusal comes from the symbolic analysis and names the size.
check('setFactorMemoryLimit(2e5)', t.setFactorMemoryLimit(2e5) === '');
r = JSON.parse(t.loadModel(ico(4), 'off', '', ''));
check('a mesh whose factor exceeds the limit is refused', r.ok === false && /too large/.test(r.error) &&
  /GB/.test(r.error), JSON.stringify(r));
check('... the previous model keeps working', t.oneForm().length === 30 * 16 && strokeWorks(t), t.lastError());
check('setFactorMemoryLimit(0) (the address space left)', t.setFactorMemoryLimit(0) === '');
r = JSON.parse(t.loadModel(ico(4), 'off', JSON.stringify({ boundary: 'free', gamma: 0.5 }),
  JSON.stringify({ gamma: 0.01, constraints: [{ type: 'source', vertex: 0, strength: 1 }] })));
check('with the limit back, the larger mesh loads with settings and design', r.ok === true &&
  t.oneForm().length === 30 * 256 && t.gamma() === 0.01 && JSON.parse(t.designJson()).constraints.length === 1,
  JSON.stringify(r));
r = JSON.parse(t.loadModel(ico(2), 'off', JSON.stringify({ gamma: 1e300 }),
  JSON.stringify({ constraints: [{ type: 'source', vertex: 99999, strength: 1 }] })));
check('bad settings and design are dropped and reported, the mesh loads', r.ok === true && /gamma/.test(r.settingsError) &&
  /99999/.test(r.restoreError) && t.gamma() === 0 && finiteField(t), JSON.stringify(r));

// Numeric ranges: extreme values are refused, the largest accepted ones undo exactly.
const fresh = (des) => {
  const f = new Module.Designer();
  f.loadModel(ico(2), 'off', '', des.designJson());
  const x = Float64Array.from(f.oneForm());
  f.delete();
  return x;
};
const relDiff = (a, b) => {
  let num = 0, den = 0;
  for (let i = 0; i < a.length; ++i) { num += (a[i] - b[i]) ** 2; den += b[i] ** 2; }
  return Math.sqrt(num / Math.max(den, 1e-300));
};
t.addSource(0, 1);
t.solve();
const stripT = faceStrip(t.triangles(), 3, 12);
check('stroke weight 1e20 is refused', t.addStroke(stripT, 1, 1e20) === -1 && /weight/.test(t.lastError()), t.lastError());
const heavy = t.addStroke(stripT, 1, 1e8);
check('stroke weight 1e8 (the largest) is accepted', heavy > 0 && t.solve() === '', t.lastError());
t.remove(heavy);
check('undo of it leaves a finite field', t.solve() === '' && finiteField(t));
let rd = relDiff(t.oneForm(), fresh(t));
check('... equal to a fresh solve within 1e-9', rd < 1e-9, `relative difference ${rd}`);
check('vector weight 1e16 is refused', t.addVector(5, 1, 0, 0, 1e16) === -1, t.lastError());
const heavyVec = t.addVector(5, 1, 0, 0, 1e8);
t.solve();
t.remove(heavyVec);
t.solve();
rd = relDiff(t.oneForm(), fresh(t));
check('undo of a vector with weight 1e8 equals a fresh solve within 1e-9', finiteField(t) && rd < 1e-9, `${rd}`);
check('gamma 1e300 is refused', t.setGamma(1e300) !== '' && t.gamma() === 0);
check('vector [1e308, 1e308, 0] is refused', t.addVector(5, 1e308, 1e308, 0, 1) === -1 && /out of range/.test(t.lastError()));
check('source strength 1e308 is refused', t.addSource(3, 1e308) === -1 && /out of range/.test(t.lastError()));
check('setStrength 1e308 is refused', t.setStrength(JSON.parse(t.constraintIdsJson())[0], 1e308) === false);
const tri2 = t.triangles();
check('addEdge(3, 3) is refused', t.addEdge(3, 3, 1, 1) === -1 && /two different vertices/.test(t.lastError()), t.lastError());
check('a stroke point with bary [0, 0, 0] is refused',
  t.addStroke(new Float64Array([0, 0, 0, 0, 1, 0.3, 0.3, 0.4]), 1, 1) === -1 && /sum to/.test(t.lastError()), t.lastError());
check('face 1e12 is named unwrapped', t.addVector(1e12, 1, 0, 0, 1) === -1 &&
  t.lastError().includes('1000000000000') && !t.lastError().includes('-727379968'), t.lastError());
check('face 1e12 in a constraint document is named unwrapped',
  t.addConstraintJson(JSON.stringify({ type: 'vortex', face: 1e12, strength: 1 })) === -1 &&
  t.lastError().includes('1000000000000'), t.lastError());
check('after all refusals the field is finite and the design unchanged', t.solve() === '' && finiteField(t) &&
  JSON.parse(t.designJson()).constraints.length === 1 && tri2.length > 0);

// The page's client: constraints go in as design-format JSON, where null or a missing number is refused by the
// core's parser (never read as 0); the remaining typed calls check their numbers before embind converts them.
const { CoreClient } = await import(pathToFileURL(resolve(ROOT, 'web/core/core-client.js')).href);
const client = new CoreClient(Module);
client.loadModel(ico(1), 'off');
const refused = (f) => { try { f(); return ''; } catch (err) { return err.message; } };
check('client: null face is refused', /face/.test(refused(() => client.addConstraintJson({ type: 'vector', face: null, vector: [1, 0, 0] }))));
check('client: null stroke bary is refused', /bary/.test(refused(() => client.addConstraintJson({ type: 'stroke',
  points: [{ face: 0, bary: null }, { face: 1, bary: [0.3, 0.3, 0.4] }] }))));
check('client: null stroke face is refused', /face/.test(refused(() => client.addConstraintJson({ type: 'stroke',
  points: [{ face: null, bary: [1, 0, 0] }, { face: 1, bary: [0.3, 0.3, 0.4] }] }))));
check('client: null strength is refused', /strength/.test(refused(() => client.addConstraintJson({ type: 'source', vertex: 0, strength: null }))));
check('client: edge [3, 3] is refused', /two different vertices/.test(refused(() => client.addConstraintJson({ type: 'edge', edge: [3, 3], value: 1 }))));
check('client: setWeight(null) is refused', /weight must be a number \(got null\)/.test(refused(() => client.setWeight(1, null))));
check('client: setGamma(undefined) is refused', /gamma must be a number/.test(refused(() => client.setGamma(undefined))));
check('client: a failed loadModel keeps the model', /load:/.test(refused(() => client.loadModel(new TextEncoder().encode(hugeTet), 'off'))) &&
  client.oneForm().length === 30 * 4);
t.delete();

// ------------------------------------------------------------------ prescribed singularities, sharp features
// On a closed sphere (chi = 2) prescribed indices summing to 2 are the field's singularities exactly; a move
// moves that one only; a removal leaves the others and the field places the index it left. Features on a box
// made here: exactly its 12 creases, n edges each.
{
  const e = new Module.Designer();
  check('topology: sphere loads', e.loadMesh(ico(2), 'off') === '' && e.setSymmetry(4) === '');
  const P = e.positions();
  const nV = P.length / 3;
  // Eight vertices far apart (greedy farthest points), so that every singularity has room of its own.
  const far = [0];
  while (far.length < 8) {
    let best = -1, bestD = -1;
    for (let v = 0; v < nV; v++) {
      const dmin = Math.min(...far.map((w) => (P[3 * v] - P[3 * w]) ** 2 + (P[3 * v + 1] - P[3 * w + 1]) ** 2 +
        (P[3 * v + 2] - P[3 * w + 2]) ** 2));
      if (dmin > bestD) [best, bestD] = [v, dmin];
    }
    far.push(best);
  }
  const ids = far.map((v) => e.addSingularity(v, 0.25));
  // [vertex, index, prescribed] in vertex order (the core writes an object's keys sorted).
  const bySorted = (list) => list.map((x) => [x.vertex, x.index, x.prescribed]).sort((a, b) => a[0] - b[0]);
  const prescribedSet = (vertices) => bySorted(vertices.map((vertex) => ({ vertex, index: 0.25, prescribed: true })));
  check('topology: 8 x +1/4 placed', ids.every((id) => id > 0) && e.solve() === '', e.lastError());
  check('topology: the field has exactly the prescribed singularities, flagged',
    JSON.stringify(bySorted(JSON.parse(e.singularitiesJson()))) === JSON.stringify(prescribedSet(far)),
    e.singularitiesJson());
  let stats = JSON.parse(e.statsJson());
  check('topology: stats say exact, chi 2, nothing free', stats.singularityMode === 'exact' &&
    stats.eulerCharacteristic === 2 && stats.prescribedIndex === 2 && stats.freeIndex === 0, JSON.stringify(stats));
  const specs = JSON.parse(e.constraintsJson());
  check('topology: constraintsJson lines up with the ids, singularities as specs',
    JSON.stringify(JSON.parse(e.constraintIdsJson())) === JSON.stringify(ids) &&
    specs.every((c, k) => c.type === 'singularity' && c.vertex === far[k] && c.index === 0.25), e.constraintsJson());
  check('topology: constraintJson(id) gives the spec', JSON.parse(e.constraintJson(ids[2])).vertex === far[2]);
  const doc = JSON.parse(e.designJson());
  check('topology: the design lists them apart', doc.constraints.length === 0 &&
    JSON.stringify(doc.singularities.map((x) => [x.vertex, x.index])) === JSON.stringify(far.map((v) => [v, 0.25])),
    JSON.stringify(doc.singularities));

  // A move to a neighbour of the first one's vertex.
  const E = e.edges();
  let target = -1;
  for (let k = 0; k < E.length && target < 0; k += 2) {
    if (E[k] === far[0] && !far.includes(E[k + 1])) target = E[k + 1];
    else if (E[k + 1] === far[0] && !far.includes(E[k])) target = E[k];
  }
  const moved = [target, ...far.slice(1)];
  check('topology: move keeps the id', e.moveSingularity(ids[0], target) === true && e.solve() === '' &&
    JSON.stringify(JSON.parse(e.constraintIdsJson())) === JSON.stringify(ids), e.lastError());
  check('topology: the move moved exactly that one',
    JSON.stringify(bySorted(JSON.parse(e.singularitiesJson()))) === JSON.stringify(prescribedSet(moved)),
    e.singularitiesJson());

  // Refusals: the design stays as it was.
  const before = e.designJson();
  check('topology: a second one on a vertex is refused', e.addSingularity(far[1], -0.25) === -1, e.lastError());
  check('topology: an index that is not a multiple of 1/4 is refused', e.addSingularity(far[1] + 1, 1 / 3) === -1 &&
    e.lastError().length > 0, e.lastError());
  check('topology: a vertex that does not exist is refused', e.addSingularity(nV + 5, 0.25) === -1);
  check('topology: a move onto a taken vertex is refused', e.moveSingularity(ids[0], far[1]) === false);
  check('topology: a fractional vertex is named', e.addSingularity(1.5, 0.25) === -1 &&
    /integer index/.test(e.lastError()), e.lastError());
  check('topology: after the refusals the design is unchanged', e.designJson() === before);

  // Removal: the other seven stay, and the field places the +1/4 left over itself.
  check('topology: remove one', e.remove(ids[3]) === true && e.solve() === '', e.lastError());
  const after = JSON.parse(e.singularitiesJson());
  const kept = moved.filter((v, k) => k !== 3);
  check('topology: the others stay, prescribed',
    JSON.stringify(bySorted(after.filter((x) => x.prescribed))) === JSON.stringify(prescribedSet(kept)),
    e.singularitiesJson());
  stats = JSON.parse(e.statsJson());
  check('topology: stats say free, +1/4 left to the field', stats.singularityMode === 'free' &&
    Math.abs(stats.freeIndex - 0.25) < 1e-12, JSON.stringify(stats));
  const free = after.filter((x) => !x.prescribed);
  check('topology: the field placed the index left over', Math.abs(free.reduce((a, x) => a + x.index, 0) - 0.25) < 1e-9,
    JSON.stringify(free));
  check('topology: undo of a removal through the design format', e.addConstraintJson(JSON.stringify(
    { type: 'singularity', vertex: moved[3], index: 0.25 })) > 0 && e.solve() === '' &&
    JSON.parse(e.statsJson()).singularityMode === 'exact', e.lastError());
  e.delete();
}
{
  // A box [-1, 1]^3 with n edges along each crease, faces outward.
  const n = 4;
  const index = new Map(), positions = [], triangles = [];
  const vertex = (p) => {
    const key = p.map((x) => x.toFixed(6)).join(',');
    if (!index.has(key)) {
      index.set(key, positions.length);
      positions.push(p);
    }
    return index.get(key);
  };
  for (let axis = 0; axis < 3; axis++)
    for (const sign of [-1, 1]) {
      const [u, w] = [(axis + 1) % 3, (axis + 2) % 3]; // u x w = +axis: counter-clockwise seen from outside
      const at = (i, j) => {
        const p = [0, 0, 0];
        p[axis] = sign;
        p[u] = -1 + (2 * i) / n;
        p[w] = -1 + (2 * j) / n;
        return vertex(p);
      };
      for (let i = 0; i < n; i++)
        for (let j = 0; j < n; j++) {
          const [a, b, c, dd] = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
          triangles.push(...(sign > 0 ? [a, b, c, a, c, dd] : [a, c, b, a, dd, c]));
        }
    }
  const off = `OFF\n${positions.length} ${triangles.length / 3} 0\n${positions.map((p) => p.join(' ')).join('\n')}\n` +
    `${Array.from({ length: triangles.length / 3 }, (_, f) => `3 ${triangles.slice(3 * f, 3 * f + 3).join(' ')}`).join('\n')}\n`;
  const b = new Module.Designer();
  check('features: box loads as a cross field', b.loadMesh(new TextEncoder().encode(off), 'off') === '' &&
    b.setSymmetry(4) === '', b.lastError());
  check('features: none by default', b.featureAngle() === 0 && b.featureEdges().length === 0 && b.solve() === '');
  check('features: 35 degrees', b.setFeatures(35, [], []) === '' && b.solve() === '', b.lastError());
  const used = Int32Array.from(b.featureEdges());
  const E = Int32Array.from(b.edges());
  const P = b.positions();
  // An edge along a crease: its ends share two coordinates at the same +-1 (a face's diagonal does not).
  const creaseEdge = (e) => [0, 1, 2].filter((k) => Math.abs(Math.abs(P[3 * E[2 * e] + k]) - 1) < 1e-9 &&
    P[3 * E[2 * e] + k] === P[3 * E[2 * e + 1] + k]).length >= 2;
  check('features: exactly the 12 creases, n edges each', used.length === 12 * n && [...used].every(creaseEdge),
    `${used.length} edges`);
  check('features: the stats count them', JSON.parse(b.statsJson()).featureEdges === 12 * n);
  // An edge across a face (not a crease) added, a crease edge removed.
  let flat = -1;
  for (let k = 0; k < E.length / 2 && flat < 0; k++) if (!creaseEdge(k)) flat = k;
  const crease = used[0];
  const add = [E[2 * flat], E[2 * flat + 1]], remove = [E[2 * crease], E[2 * crease + 1]];
  check('features: add and remove by vertex pairs', b.setFeatures(35, add, remove) === '' && b.solve() === '' &&
    b.featureEdges().length === 12 * n && Int32Array.from(b.featureEdges()).includes(flat) &&
    !Int32Array.from(b.featureEdges()).includes(crease), b.lastError());
  const features = JSON.parse(b.featuresJson());
  check('features: featuresJson as set', features.angle === 35 && JSON.stringify(features.add) === JSON.stringify([add]) &&
    JSON.stringify(features.remove) === JSON.stringify([remove]), b.featuresJson());
  const doc = JSON.parse(b.designJson());
  check('features: the design carries them', doc.featureAngle === 35 &&
    JSON.stringify(doc.featureEdges) === JSON.stringify({ add: [add], remove: [remove] }), b.designJson());
  const before = b.featuresJson();
  check('features: a pair that is not an edge is refused, unchanged',
    b.setFeatures(10, [0, positions.length - 1], []) !== '' && b.featuresJson() === before, b.lastError());
  check('features: an odd number of vertices is refused', /2 vertices per edge/.test(b.setFeatures(10, [0], [])));
  check('features: an angle of 200 is refused, unchanged', b.setFeatures(200, [], []) !== '' &&
    b.featuresJson() === before);
  check('features: 0 turns detection off', b.setFeatures(0, [], []) === '' && b.solve() === '' &&
    b.featureEdges().length === 0);
  b.delete();
}
// Only the prescribed singularities: a torus (chi = 0) made here, N = 4, asked for exactly its prescribed ones
// with none prescribed, has no singularity at all (the smoothest field is free to place +/- pairs).
{
  const [n, m, R, r] = [24, 12, 2, 0.7];
  const verts = [], faces = [];
  for (let i = 0; i < n; i++)
    for (let j = 0; j < m; j++) {
      const [u, v] = [(2 * Math.PI * i) / n, (2 * Math.PI * j) / m];
      verts.push([(R + r * Math.cos(v)) * Math.cos(u), (R + r * Math.cos(v)) * Math.sin(u), r * Math.sin(v)]);
      const at = (a, b) => ((a + n) % n) * m + ((b + m) % m);
      faces.push([at(i, j), at(i + 1, j), at(i + 1, j + 1)], [at(i, j), at(i + 1, j + 1), at(i, j + 1)]);
    }
  const off = `OFF\n${verts.length} ${faces.length} 0\n${verts.map((p) => p.join(' ')).join('\n')}\n` +
    `${faces.map((f) => `3 ${f.join(' ')}`).join('\n')}\n`;
  const t = new Module.Designer();
  check('exact: torus loads as a cross field', t.loadMesh(new TextEncoder().encode(off), 'off') === '' &&
    t.setSymmetry(4) === '' && t.solve() === '', t.lastError());
  check('exact: off by default, not in the design', t.exactSingularities() === false &&
    !('exactSingularities' in JSON.parse(t.designJson())));
  check('exact: set', t.setExactSingularities(true) === '' && t.exactSingularities() === true && t.solve() === '',
    t.lastError());
  const stats = JSON.parse(t.statsJson());
  check('exact: the torus has no singularity', JSON.parse(t.singularitiesJson()).length === 0, t.singularitiesJson());
  check('exact: stats say exact, chi 0', stats.singularityMode === 'exact' && stats.eulerCharacteristic === 0,
    JSON.stringify(stats));
  const doc = JSON.parse(t.designJson());
  check('exact: the design carries it', doc.exactSingularities === true, t.designJson());
  check('exact: off again, and the design loses it', t.setExactSingularities(false) === '' && t.solve() === '' &&
    !('exactSingularities' in JSON.parse(t.designJson())));
  check('exact: applyDesignJson brings it back', t.applyDesignJson(JSON.stringify(doc)) === '' &&
    t.exactSingularities() === true && t.solve() === '' && JSON.parse(t.singularitiesJson()).length === 0,
    t.lastError());

  // The quad meshers' files by the exporter over the Designer's mesh, and a .sing read back: a +/- pair
  // prescribed is what the file holds (N = 4, k = +1 and -1).
  const pair = [[30, 0.25], [150, -0.25]];
  pair.forEach(([v, k]) => t.addSingularity(v, k));
  check('exact: a +/- pair is all the field has', t.solve() === '' &&
    JSON.stringify(JSON.parse(t.singularitiesJson()).map((x) => [x.vertex, x.index]).sort((a, b) => a[0] - b[0])) ===
    JSON.stringify(pair), t.singularitiesJson());
  const x = new Module.FieldExporter();
  check('exporter: takes the mesh', x.setMesh(t.positions().slice(), t.triangles().slice(), t.cornerUVs().slice(),
    t.sourceToWelded().slice()) === '', x.lastError());
  const sing = x.singFile(4, t.singularitiesJson());
  check('exporter: .sing is "N count" and the pair as vertex k', sing === '4 2\n30 1\n150 -1\n', JSON.stringify(sing));
  const read = JSON.parse(Module.readSingJson(sing));
  check('exporter: .sing read back', read.symmetry === 4 && JSON.stringify(read.singularities) ===
    JSON.stringify(pair.map(([vertex, index]) => ({ index, vertex }))), JSON.stringify(read));
  check('exporter: a bad .sing is refused naming the line', /line 2/.test(JSON.parse(Module.readSingJson('4 1\nx\n')).error ?? ''),
    Module.readSingJson('4 1\nx\n'));
  const rosy = x.rosyFile(t.faceVectors().slice(), 4).split('\n');
  check('exporter: .rosy has numF, 4 and a direction per face', rosy[0] === String(faces.length) && rosy[1] === '4' &&
    rosy.slice(2, 2 + faces.length).every((l) => l.split(' ').length === 3));
  check('exporter: .rosy of a line field is refused', x.rosyFile(t.faceVectors().slice(), 2) === '' &&
    /symmetry/.test(x.lastError()), x.lastError());
  check('exporter: .sharp without features: the count 0 of a closed mesh', x.sharpFile([]) === '0\n',
    JSON.stringify(x.sharpFile([])));
  check('exporter: .sharp refuses an edge that is not there', x.sharpFile([1e6]) === '' && /no edge/.test(x.lastError()));

  // The same bytes as tvf export --sing/--rosy/--sharp for the same model and design.
  const cli = resolve(ROOT, 'build/tvf');
  const dir = mkdtempSync(resolve(tmpdir(), 'tvf-quad-'));
  let same = false, detail = '';
  try {
    // A short feature curve away from the pair (vertices 0, 1, 2: along one ring of the tube).
    if (t.setFeatures(0, [0, 1, 1, 2], []) !== '' || t.solve() !== '') throw new Error(t.lastError());
    writeFileSync(resolve(dir, 'torus.off'), off);
    writeFileSync(resolve(dir, 'design.json'), t.designJson());
    execFileSync(cli, ['export', resolve(dir, 'torus.off'), resolve(dir, 'design.json'), '--sing',
      resolve(dir, 'a.sing'), '--rosy', resolve(dir, 'a.rosy'), '--sharp', resolve(dir, 'a.sharp')]);
    const files = ['sing', 'rosy', 'sharp'].map((e) => readFileSync(resolve(dir, `a.${e}`), 'utf8'));
    const page = [x.singFile(4, t.singularitiesJson()), x.rosyFile(t.faceVectors().slice(), 4),
      x.sharpFile(Int32Array.from(t.featureEdges()))];
    same = files.every((f, k) => f === page[k]) && t.featureEdges().length > 0;
    detail = `${t.featureEdges().length} feature edges; ` + files.map((f, k) => `${f.length}/${page[k].length}`).join(', ');
  } catch (err) {
    detail = String(err.message ?? err);
  }
  check('exporter: the same bytes as tvf export --sing --rosy --sharp', same, detail);
  rmSync(dir, { recursive: true, force: true });
  x.delete();
  t.delete();
}

// Stripe patterns (Designer.computeStripes, core/design/design_stripes.h): on a flat square whose line field is
// one vector's (a constant field), straight stripes across it at exactly the asked frequency (the gradient of
// each face's interpolated phase); a second compute on the same model reuses the factor's analysis from the
// pattern before, in no more steps; a symmetry without stripes is refused by name.
{
  const n = 12, rows = [], faces = [];
  for (let j = 0; j <= n; j++) for (let i = 0; i <= n; i++) rows.push(`${i / n} ${j / n} 0`);
  const id = (i, j) => j * (n + 1) + i;
  for (let j = 0; j < n; j++)
    for (let i = 0; i < n; i++) faces.push(`3 ${id(i, j)} ${id(i + 1, j)} ${id(i + 1, j + 1)}`, `3 ${id(i, j)} ${id(i + 1, j + 1)} ${id(i, j + 1)}`);
  const s = new Module.Designer();
  const loadedSquare = s.loadMesh(new TextEncoder().encode(`OFF\n${rows.length} ${faces.length} 0\n${rows.join('\n')}\n${faces.join('\n')}\n`), 'off');
  const dir = [0.6, 0.8, 0];
  const designed = loadedSquare || s.applyDesignJson(JSON.stringify({ symmetry: 2, constraints: [
    { type: 'vector', face: 0, vector: dir }] })) || s.solve();
  check('stripes: a square with a constant line field', designed === '', designed);
  const frequency = 4;
  const err = s.computeStripes(null, JSON.stringify({ frequency }), null);
  check('stripes: computed', err === '', err);
  const positions = s.positions().slice(), triangles = s.triangles().slice(), phase = s.stripeCornerPhase().slice();
  let worstRate = 0, worstAngle = 0;
  for (let f = 0; f < triangles.length / 3; f++) {
    const p = [0, 1, 2].map((k) => positions.slice(3 * triangles[3 * f + k], 3 * triangles[3 * f + k] + 2));
    const g = phase.slice(3 * f, 3 * f + 3);
    // Solve grad . (p1 - p0) = g1 - g0, grad . (p2 - p0) = g2 - g0 in the plane.
    const [ax, ay] = [p[1][0] - p[0][0], p[1][1] - p[0][1]], [bx, by] = [p[2][0] - p[0][0], p[2][1] - p[0][1]];
    const det = ax * by - ay * bx, da = g[1] - g[0], db = g[2] - g[0];
    const gx = (da * by - db * ay) / det, gy = (ax * db - bx * da) / det;
    const rate = Math.hypot(gx, gy);
    worstRate = Math.max(worstRate, Math.abs(rate / (2 * Math.PI * frequency) - 1));
    // The phase grows across the field: the gradient is perpendicular to it.
    worstAngle = Math.max(worstAngle, Math.abs((gx * dir[0] + gy * dir[1]) / rate));
  }
  check('stripes: the asked frequency, across the field', worstRate < 1e-4 && worstAngle < 1e-4,
    `rate ${worstRate}, cos ${worstAngle}`);
  const first = JSON.parse(s.stripeStatsJson());
  // A square has no loop to fit the frequency to (core/direction/stripe_loop_fit.h): the asked one, no time spent.
  check('stripes: no loop, no fit', first.loopFit === 1 && first.fitMs === 0, JSON.stringify(first));
  // The same field again: nothing changed, so the local update keeps the pattern as it was.
  const kept = s.computeStripes(null, JSON.stringify({ frequency }), null);
  const keptStats = JSON.parse(s.stripeStatsJson());
  const samePhase = s.stripeCornerPhase().every((x, i) => x === phase[i]);
  check('stripes: an unchanged field keeps its pattern', kept === '' && keptStats.localUpdate === true &&
    keptStats.localVertices === 0 && samePhase, JSON.stringify(keptStats));
  // The whole pattern asked for (as the page does when the edits pause): it starts from the first.
  const again = s.computeStripes(null, JSON.stringify({ frequency, localUpdate: false }), null);
  const second = JSON.parse(s.stripeStatsJson());
  check('stripes: a second compute starts from the first', again === '' && second.analysisReused === true &&
    second.localUpdate === false && second.iterations <= first.iterations, JSON.stringify(second));
  const turned = s.setSymmetry(3) || s.solve();
  const refused = turned || s.computeStripes(null, JSON.stringify({ frequency }), null);
  check('stripes: symmetry 3 is refused by name', /symmetry 1, 2 or 4/.test(refused), refused);
  s.delete();
}
{
  // The quad remesher (wasm/quad_bindings.cpp): a sphere's smoothest cross field has eight +1/4 singularities,
  // and its quad mesh eight valence-3 vertices, closed (V - E + F = 2), as many vertices as the arrays say.
  const q = new Module.Designer();
  const ready = q.loadMesh(new TextEncoder().encode(icosphere(4)), 'off') || q.setSymmetry(4) || q.solve();
  check('quad: a cross field on a sphere', ready === '', ready);
  const args = [q.positions().slice(), Int32Array.from(q.triangles()), q.faceVectors().slice()];
  const stages = [];
  const r = Module.quadRemesh(...args, JSON.stringify({ edgeLength: 0.15, symmetry: 4 }),
    (stage) => { stages.push(stage); return true; });
  check('quad: remeshed', !r.error, r.error);
  if (!r.error) {
    const stats = JSON.parse(r.statsJson);
    check('quad: eight valence-3 vertices, closed, all quads', stats.valence3 === 8 && stats.irregularVertices === 8 &&
      stats.eulerCharacteristic === 2 && stats.quads === stats.faces, r.statsJson);
    check('quad: the arrays are the mesh the statistics describe', r.positions.length === 3 * stats.vertices &&
      r.faceStart.length === stats.faces + 1 && r.faceVertices.length === r.faceStart[stats.faces] &&
      r.irregular.length === 8, `${r.positions.length} ${r.faceStart.length}`);
    check('quad: progress through every stage', stages.includes('parametrizing') && stages.at(-1) === 'done',
      stages.join());
  }
  const cancelled = Module.quadRemesh(...args, JSON.stringify({ edgeLength: 0.15, symmetry: 4 }), () => false);
  check('quad: a progress answering false cancels', /cancelled/.test(cancelled.error ?? ''), cancelled.error);
  const line = Module.quadRemesh(...args, JSON.stringify({ edgeLength: 0.15, symmetry: 2 }), null);
  check('quad: a line field is refused by name', /Quad meshes need a cross field/.test(line.error ?? ''), line.error);
  q.delete();
}
{
  // The cube's sharp edges as features: the quads' edges follow them, so every quad lies in one side.
  const n = 6, index = new Map(), verts = [], tris = [];
  const vertex = (p) => {
    const key = p.map((x) => Math.round(x * n)).join();
    if (!index.has(key)) index.set(key, verts.push(p) - 1);
    return index.get(key);
  };
  for (let axis = 0; axis < 3; axis++) {
    for (const side of [0, 1]) {
      const a = (axis + 1) % 3, b = (axis + 2) % 3;
      for (let i = 0; i < n; i++) {
        for (let j = 0; j < n; j++) {
          const q = [[0, 0], [1, 0], [1, 1], [0, 1]].map(([di, dj]) => {
            const p = [0, 0, 0];
            p[axis] = side, p[a] = (i + di) / n, p[b] = (j + dj) / n;
            return vertex(p);
          });
          if (side === 0) [q[1], q[3]] = [q[3], q[1]];
          tris.push([q[0], q[1], q[2]], [q[0], q[2], q[3]]);
        }
      }
    }
  }
  const off = `OFF\n${verts.length} ${tris.length} 0\n${verts.map((p) => p.join(' ')).join('\n')}\n` +
    `${tris.map((t) => `3 ${t.join(' ')}`).join('\n')}\n`;
  const c = new Module.Designer();
  const ready = c.loadMesh(new TextEncoder().encode(off), 'off') || c.setSymmetry(4) ||
    c.setFeatures(35, [], []) || c.solve();
  check('quad features: a cross field on a cube with its edges as features', ready === '', ready);
  const edges = c.edges(), pairs = [];
  for (const e of c.featureEdges()) pairs.push(edges[2 * e], edges[2 * e + 1]);
  const r = Module.quadRemesh(c.positions().slice(), Int32Array.from(c.triangles()), c.faceVectors().slice(),
    JSON.stringify({ edgeLength: 0.3, symmetry: 4, featureEdges: pairs }), null);
  check('quad features: remeshed', !r.error, r.error);
  if (!r.error) {
    const stats = JSON.parse(r.statsJson);
    check('quad features: 12 curves followed, 3 x 3 quads a side', stats.featureCurves === 12 &&
      stats.releasedFeatureCurves === 0 && stats.quads === 54 && stats.faces === 54, r.statsJson);
    let straddling = 0;
    for (let f = 0; f + 1 < r.faceStart.length; f++) {
      const corners = Array.from(r.faceVertices.subarray(r.faceStart[f], r.faceStart[f + 1]));
      const inOneSide = [0, 1, 2].some((axis) => [0, 1].some((side) =>
        corners.every((v) => Math.abs(r.positions[3 * v + axis] - side) < 1e-9)));
      if (!inOneSide) straddling++;
    }
    check('quad features: no quad folds over a sharp edge', straddling === 0, `${straddling} quads`);
  }
  const bad = Module.quadRemesh(c.positions().slice(), Int32Array.from(c.triangles()), c.faceVectors().slice(),
    JSON.stringify({ edgeLength: 0.3, symmetry: 4, featureEdges: [0, 0] }), null);
  check('quad features: a pair that is no edge is refused by name', /is not an edge/.test(bad.error ?? ''), bad.error);
  c.delete();
}
finish();

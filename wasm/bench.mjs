#!/usr/bin/env node
// SPDX-License-Identifier: GPL-2.0-or-later
// npm run bench:wasm [-- [options] [MESH ...]]     the ladder: native vs wasm side by side
// npm run bench:wasm -- --json MESH                one JSON object {edges, native: {...}, wasm: {...}}
//
// The wasm core (build-wasm/tvf_core.mjs, `npm run build:wasm`) is driven through the same embind Designer
// the page uses, with the same sequence as `tvf bench` (cli/bench.cpp): per repeat, clear + factor, a source +
// solve, a second solve + vertexVectors() (reconstruction), one single-edge addEdge (a rank-1 update) and its
// removal, and a ~50-edge stroke (barycentres of a strip of faces heading away from its start) + solve. Keys
// match `tvf bench --json`: analyzeMs, factorMs, solveMs, updateMs, strokeUpdateMs are the core's own timings
// (DesignStats, so wasm and native time the same code); reconstructMs and strokeUpdateSolveMs are wall times
// less the core's solve/reconstruct times, as in cli/bench.cpp. The wasm object adds the JS-side wall time of
// the calls (factorCallMs = d.factor() incl. assembly and analysis, solveCallMs = d.solve() incl. the
// right-hand side and face vectors, updateCallMs = d.addEdge()), and the FIRST factorization (d.factor() wall
// time) of a freshly instantiated module, which V8 runs in its baseline tier (Liftoff) with no on-stack
// replacement into optimized code:
//   firstFactorMs         first d.factor() after Module.warmUp() (what the page should do at start-up)
//   firstFactorNoWarmUpMs first d.factor() in a fresh process without warm-up (measured in a child process)
//   warmUpMs              the warm-up's own time
// Warm numbers are medians over the repeats that follow the first factorization. Every mesh is measured in
// fresh node processes, since V8 shares tiered-up code between instances of the same module in one process.
//
// Ordering: METIS nested dissection by default, as in the page and `tvf bench`; --amd for AMD; --compare for
// both, interleaved repeat by repeat in one process (wasm) and in one `tvf bench --compare` run (native), with
// the ratios the acceptance criteria name (METIS/AMD analysis and stroke + solve, wasm/native stroke + solve).
// The native CLI is built (cmake, -j2) when build/tvf is missing.
// Options: --repeat N (5), --big-repeat N (2, for the 1.25M-edge mesh), --no-big, --tvf PATH (build/tvf),
//   --native FILE (reuse bench-data/bench-native.json-style results instead of running tvf), --no-native,
//   --no-warmup, --warmup LEVELS,ROUNDS (icosphere subdivisions and rounds; default 3,1), --settle MS (wait
//   after the warm-up so background compilation can finish; default 100), --node-flags "FLAGS" (for the child
//   processes, e.g. "--no-liftoff" to compare V8 tiering strategies), --module PATH (tvf_core.mjs),
//   --symmetry N (1: a vector field; 2 a line, 4 a cross field: their power-field system, a direction constraint
//   as the single update, smoothestMs for the unconstrained field; the native side with tvf bench --symmetry N),
//   --quads N (instead of all else: the quad remesher at about N quads, wasm/quad-bench.mjs; JSON).
//   --scaling (what scripts/bench-cores.sh tabulates: no singularity edits, no cold first factorization in a
//   child process, and the native side with tvf bench --scaling).
// Every repeat ends with prescribed singularities' edits, as tvf bench times them (timeSingularityEdits):
// singularityEditMs (the median of placing a pair and moving one, with every index the surface needs
// prescribed), singularityPlaceMs, singularityMoveMs, singularityFactorizations (expected 0), singularityMode
// (expected 'exact') and singularityFreeMoveMs (a move with the field placing the rest itself).
// Threads: the module is build-wasm/tvf_core_threads.mjs when it was built (what a cross-origin-isolated page,
// the app's own, runs), with as many backward-substitution threads as it has (2) where the machine has the
// cores; --threads 1 takes the plain tvf_core.mjs (what any other page runs). The native side runs with the
// same number of threads as the wasm side (tvf bench --threads), like with like.
import { execFileSync } from 'node:child_process';
import { existsSync, mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { dirname, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';
import { measureQuadNative, measureQuadWasm } from './quad-bench.mjs';
import {
  ROOT, ensureMeshes, fmt, median, meshName, meshPath, nativeTable, parseArgs, repeatFor, runNative,
} from '../scripts/bench.mjs';

const SELF = fileURLToPath(import.meta.url);

// For each face corner k, the face across edge (k, k+1), or -1 on a boundary (sorted edge keys: no per-edge
// allocation on 1M-edge meshes).
function faceNeighbours(triangles) {
  const nF = triangles.length / 3;
  const V = 2 ** 26; // > vertex count
  const keys = new Float64Array(3 * nF);
  for (let g = 0; g < nF; ++g)
    for (let k = 0; k < 3; ++k) {
      const a = triangles[3 * g + k], b = triangles[3 * g + ((k + 1) % 3)];
      keys[3 * g + k] = a < b ? a * V + b : b * V + a;
    }
  const order = Int32Array.from({ length: 3 * nF }, (_, i) => i).sort((i, j) => keys[i] - keys[j]);
  const nb = new Int32Array(3 * nF).fill(-1);
  for (let p = 0; p + 1 < order.length; ++p)
    if (keys[order[p]] === keys[order[p + 1]]) {
      nb[order[p]] = Math.floor(order[p + 1] / 3);
      nb[order[p + 1]] = Math.floor(order[p] / 3);
    }
  return nb;
}

// Barycentres of a strip of adjacent faces heading away from the start: a stroke crossing ~`crossings` edges
// (the same walk as stripStroke in cli/bench.cpp).
function faceStrip(positions, triangles, nb, start, crossings) {
  const centre = (f) => [0, 1, 2].map((c) =>
    (positions[3 * triangles[3 * f] + c] + positions[3 * triangles[3 * f + 1] + c] +
      positions[3 * triangles[3 * f + 2] + c]) / 3);
  const origin = centre(start);
  const points = [start];
  let f = start;
  for (let step = 0; step < crossings; ++step) {
    let next = -1, farthest = -1;
    for (let c = 0; c < 3; ++c) {
      const g = nb[3 * f + c];
      if (g < 0) continue;
      const d = Math.hypot(...centre(g).map((x, i) => x - origin[i]));
      if (d > farthest) { farthest = d; next = g; }
    }
    if (next < 0) break;
    points.push(next);
    f = next;
  }
  const flat = new Float64Array(4 * points.length);
  points.forEach((g, k) => flat.set([g, 1 / 3, 1 / 3, 1 / 3], 4 * k));
  return flat;
}

// Each vertex's neighbours and whether it can carry a prescribed singularity (used by a face, not on a
// boundary: an edge with one face), from the core's edges and triangles.
function vertexRing(triangles, edges, nV) {
  const faceCount = new Map(), key = (a, b) => (a < b ? a * nV + b : b * nV + a);
  for (let t = 0; t < triangles.length; t += 3)
    for (let k = 0; k < 3; k++) {
      const e = key(triangles[t + k], triangles[t + ((k + 1) % 3)]);
      faceCount.set(e, (faceCount.get(e) ?? 0) + 1);
    }
  const interior = new Uint8Array(nV);
  for (let t = 0; t < triangles.length; t++) interior[triangles[t]] = 1;
  const neighbours = Array.from({ length: nV }, () => []);
  for (let k = 0; k < edges.length; k += 2) {
    const [a, b] = [edges[k], edges[k + 1]];
    neighbours[a].push(b);
    neighbours[b].push(a);
    if (faceCount.get(key(a, b)) === 1) interior[a] = interior[b] = 0;
  }
  return { interior, neighbours };
}

// Prescribed singularities edited as the page's Singularity tool does, each edit timed with its solve and the
// singularities' read-out (the worker sends them with the field), as tvf bench times them (cli/bench.cpp): first
// with every index the surface needs prescribed, so that the field has exactly the prescribed singularities
// (exact): on a closed surface |chi| N singularities of index sign(chi)/N spread over it (untimed), then a
// +1/N, -1/N pair drawn out in one step (the total stays chi) and its -1/N dragged one vertex on; then the free
// case: the same pair alone, the field placing chi itself, and the -1/N dragged back. Returns the times, the
// factorizations the exact edits made (none is expected) and the mode they ran in; null without room.
function timeSingularityEdits(d, ring, chi, r) {
  const nV = ring.interior.length, N = d.symmetry();
  const used = new Set();
  const freeVertex = (start) => {
    for (let k = 0; k < nV; k++) {
      const v = (start + k) % nV;
      if (!used.has(v) && ring.interior[v]) return v;
    }
    return -1;
  };
  const background = [], count = Math.abs(chi) * N;
  for (let k = 0; k < count; k++) {
    const v = freeVertex((Math.floor((k * nV) / Math.max(count, 1)) + r * 7919) % nV);
    if (v < 0) return null;
    used.add(v);
    background.push(v);
  }
  const plus = freeVertex((r * 104729 + Math.floor(nV / 3)) % nV);
  if (plus >= 0) used.add(plus);
  const minus = plus < 0 ? -1 : freeVertex((r * 7919 + Math.floor((2 * nV) / 3)) % nV);
  if (minus >= 0) used.add(minus);
  const next = minus < 0 ? undefined : ring.neighbours[minus].find((w) => !used.has(w) && ring.interior[w]);
  if (next === undefined) return null;
  const index = 1 / N;
  const place = (v, k) => {
    const id = d.addSingularity(v, k);
    if (id < 0) fail('singularity', d.lastError());
    return id;
  };
  const timed = (edit) => {
    const t = performance.now();
    edit();
    ok('solve', d.solve());
    d.singularitiesJson();
    return performance.now() - t;
  };
  const move = (id, v) => d.moveSingularity(id, v) || fail('move singularity', d.lastError());
  if (!d.clearConstraints()) fail('clear', d.lastError());
  for (const v of background) place(v, chi > 0 ? index : -index);
  ok('solve', d.solve());
  const before = JSON.parse(d.statsJson()).factorizations;
  let id;
  const placeMs = timed(() => {
    place(plus, index);
    id = place(minus, -index);
  });
  const moveMs = timed(() => move(id, next));
  const { factorizations, singularityMode: mode } = JSON.parse(d.statsJson());
  if (!d.clearConstraints()) fail('clear', d.lastError());
  place(plus, index);
  id = place(next, -index);
  ok('solve', d.solve());
  const freeMoveMs = timed(() => move(id, minus));
  if (!d.clearConstraints()) fail('clear', d.lastError());
  return { placeMs, moveMs, freeMoveMs, factorizations: factorizations - before, mode };
}

function fail(what, message) {
  throw new Error(`${what}: ${message}`);
}
const ok = (what, r) => {
  if (typeof r === 'string' && r !== '') fail(what, r);
  return r;
};

// In this process: instantiate, optionally warm up, load, first factor, then `repeat` warm repeats.
function defaultModule(opts) {
  const threaded = resolve(ROOT, 'build-wasm/tvf_core_threads.mjs');
  return Number(opts.threads) !== 1 && existsSync(threaded) ? threaded : resolve(ROOT, 'build-wasm/tvf_core.mjs');
}

async function measureWasm(mesh, opts) {
  const modulePath = resolve(opts.module ?? defaultModule(opts));
  if (!existsSync(modulePath)) fail('wasm', `${modulePath} not found; run npm run build:wasm`);
  const createTvfCore = (await import(pathToFileURL(modulePath).href)).default;
  let t = performance.now();
  const Module = await createTvfCore();
  const instantiateMs = performance.now() - t;
  let warmUpMs;
  if (opts.warmup !== false) {
    const [levels, rounds] = String(opts.warmup).split(',').map(Number);
    t = performance.now();
    const w = Module.warmUp(levels, rounds);
    warmUpMs = performance.now() - t;
    if (w < 0) fail('warmUp', 'failed');
    if (opts.settle > 0) await new Promise((r) => setTimeout(r, opts.settle));
  }
  const bytes = readFileSync(mesh);
  const d = new Module.Designer();
  t = performance.now();
  ok('load', d.loadMesh(bytes, ''));
  const loadMs = performance.now() - t;
  if (opts.threads) {
    const wanted = Number(opts.threads);
    if (wanted > Module.solverThreadsAvailable())
      fail('--threads', `${modulePath} has ${Module.solverThreadsAvailable()} thread(s) for the solve, not ${wanted}`);
    ok('threads', d.setSolverThreads(wanted));
  }
  const symmetry = Number(opts.symmetry ?? 1);
  if (symmetry > 1) ok('symmetry', d.setSymmetry(symmetry));
  t = performance.now();
  ok('factor', d.factor());
  const firstFactorMs = performance.now() - t;
  const firstStats = JSON.parse(d.statsJson());
  const result = {
    module: modulePath.replace(`${ROOT}/`, ''), threads: d.solverThreads(),
    edges: d.edges().length / 2, instantiateMs, warmUpMs, loadMs, firstFactorMs,
    firstFactorStats: { analyzeMs: firstStats.analyzeMs, factorMs: firstStats.factorMs },
  };
  if (opts.firstOnly) return result;

  const tri = Int32Array.from(d.triangles());
  const pos = Float64Array.from(d.positions());
  const nb = faceNeighbours(tri);
  const nF = tri.length / 3;
  const ring = vertexRing(tri, Int32Array.from(d.edges()), pos.length / 3);
  const { eulerCharacteristic, boundaryLoops } = JSON.parse(d.infoJson());
  const chi = boundaryLoops ? 0 : eulerCharacteristic; // with a boundary nothing needs prescribing
  const orderings = opts.compare ? [true, false] : [!opts.amd];
  const samples = orderings.map(() => ({ analyze: [], dissection: [], factor: [], convert: [], solve: [], update: [],
    stroke: [], strokeUpdate: [], strokeRows: [], strokeRhs: [], strokeSolve: [], reconstruct: [], factorCall: [], solveCall: [],
    updateCall: [],
    strokeRefactors: 0, strokeIncrementalSolves: 0, smoothest: [], deferredStroke: [], deferredCorrection: [], deferredUpdate: [],
    singularityPlace: [], singularityMove: [], singularityFreeMove: [], singularityFactorizations: 0 }));
  const last = [];
  const statsNow = () => JSON.parse(d.statsJson());
  // Orderings interleaved repeat by repeat, so that their ratios see the same machine state.
  for (let r = 0; r < opts.repeat; ++r)
    orderings.forEach((metis, o) => {
      const s = samples[o];
      ok('clear', d.clearConstraints() ? '' : d.lastError());
      // A fresh factored system each repeat: the core reuses an ordering while the pattern is unchanged.
      ok('ordering', d.setMetisOrdering(metis));
      t = performance.now();
      ok('factor', d.factor());
      s.factorCall.push(performance.now() - t);
      let stats = statsNow();
      s.analyze.push(stats.analyzeMs);
      s.dissection.push(stats.dissectionMs);
      s.factor.push(stats.factorMs);
      s.convert.push(stats.convertMs);
      // N >= 2 (--symmetry): the smoothest field first, then a direction where a vector field has a source.
      const directions = symmetry > 1;
      if (directions) {
        ok('solve', d.solve());
        s.smoothest.push(statsNow().solveMs);
        if (d.addVector(0, 1, 0.3, 0.1, 1.0) < 0) fail('vector', d.lastError());
      } else if (d.addSource(tri[0], 1) < 0) fail('source', d.lastError());
      t = performance.now();
      ok('solve', d.solve());
      s.solveCall.push(performance.now() - t);
      s.solve.push(statsNow().solveMs);
      // As in tvf bench: a second solve plus the (lazily derived) vertex vectors, less the solve itself.
      t = performance.now();
      ok('solve', d.solve());
      d.vertexVectors();
      const both = performance.now() - t;
      s.reconstruct.push(both - statsNow().solveMs);
      const face = (r * 7919 + 13) % nF;
      t = performance.now();
      const id = directions ? d.addVector(face, 0.2, 1, 0.4, 1.0) : d.addEdge(tri[3 * face], tri[3 * face + 1], 0.1, 1.0);
      s.updateCall.push(performance.now() - t);
      if (id < 0) fail('edge', d.lastError());
      s.update.push(statsNow().updateMs);
      if (!d.remove(id)) fail('remove', d.lastError());
      ok('solve', d.solve());  // as the page does after every edit: the stroke starts from a solved design
      const strip = faceStrip(pos, tri, nb, (r * 104729 + 7) % nF, 50);
      const refactorsBefore = statsNow().precisionRefactors;
      const incrementalBefore = statsNow().incrementalSolves;
      // Mouse-up to new one-form: the walk, the rank-k update, the right-hand side and the solve
      // (reconstruction reported on its own).
      t = performance.now();
      const strokeId = d.addStroke(strip, 1.0, 1.0);
      if (strokeId < 0) fail('stroke', d.lastError());
      ok('solve', d.solve());
      const total = performance.now() - t;
      stats = statsNow();
      s.stroke.push(total - stats.reconstructMs);
      s.strokeUpdate.push(stats.updateMs);
      s.strokeRows.push(stats.rowsMs);
      s.strokeRhs.push(stats.rhsMs);
      s.strokeSolve.push(stats.solveMs);
      s.strokeEdges = strip.length / 4 - 1;
      s.strokeRefactors += stats.precisionRefactors - refactorsBefore;
      s.strokeIncrementalSolves += stats.incrementalSolves - incrementalBefore;
      if (!directions) {
        // The same stroke with its update held beside the factor, as the page's worker does (tvf bench).
        if (!d.remove(strokeId)) fail('remove', d.lastError());
        ok('solve', d.solve());
        ok('defer', d.setDeferredUpdates(true));
        t = performance.now();
        if (d.addStroke(strip, 1.0, 1.0) < 0) fail('stroke', d.lastError());
        ok('solve', d.solve());
        s.deferredStroke.push(performance.now() - t - statsNow().reconstructMs);
        s.deferredCorrection.push(statsNow().updateMs);
        ok('update', d.applyDeferredUpdates());
        s.deferredUpdate.push(statsNow().deferredUpdateMs);
        ok('defer', d.setDeferredUpdates(false));
      }
      last[o] = stats;
      const edits = opts.scaling ? null : timeSingularityEdits(d, ring, chi, r);
      if (edits) {
        s.singularityPlace.push(edits.placeMs);
        s.singularityMove.push(edits.moveMs);
        s.singularityFreeMove.push(edits.freeMoveMs);
        s.singularityFactorizations += edits.factorizations;
        s.singularityMode = edits.mode;
      }
    });
  d.delete();
  const summary = (s, stats, metis) => ({
    ...result,
    nnzPerRowM: stats.nnzPerRowM, nnzPerRowL: stats.nnzPerRowL,
    analyzeMs: median(s.analyze), dissectionMs: median(s.dissection), factorMs: median(s.factor),
    convertMs: median(s.convert), solveMs: median(s.solve), updateMs: median(s.update),
    strokeUpdateSolveMs: median(s.stroke), strokeUpdateMs: median(s.strokeUpdate), strokeRowsMs: median(s.strokeRows),
    strokeRhsMs: median(s.strokeRhs), strokeSolveMs: median(s.strokeSolve), strokeEdges: s.strokeEdges,
    strokeRefactors: s.strokeRefactors,
    deferredStrokeSolveMs: median(s.deferredStroke), deferredStrokeCorrectionMs: median(s.deferredCorrection),
    deferredStrokeUpdateMs: median(s.deferredUpdate),
    strokeIncrementalSolves: s.strokeIncrementalSolves,
    reconstructMs: median(s.reconstruct), symmetry: Number(opts.symmetry ?? 1), smoothestMs: median(s.smoothest),
    factorCallMs: median(s.factorCall), solveCallMs: median(s.solveCall), updateCallMs: median(s.updateCall),
    // One singularity edit (placing or moving, with its solve): the median of both kinds together, as tvf bench.
    singularityEditMs: median([...s.singularityPlace, ...s.singularityMove]),
    singularityPlaceMs: median(s.singularityPlace), singularityMoveMs: median(s.singularityMove),
    singularityFactorizations: s.singularityFactorizations, singularityMode: s.singularityMode,
    singularityFreeMoveMs: median(s.singularityFreeMove),
    repeat: opts.repeat, warmUp: opts.warmup === false ? 'none' : String(opts.warmup), settleMs: opts.settle,
    ordering: metis ? 'metis' : 'amd', factorKind: stats.factorKind, factorGroups: stats.factorGroups,
    // The wasm heap after the factorization and edits (it only grows): what this mesh needs in the browser.
    heapBytes: Module.HEAPU8.length,
  });
  if (!opts.compare) return summary(samples[0], last[0], orderings[0]);
  return { ...result, metis: summary(samples[0], last[0], true), amd: summary(samples[1], last[1], false) };
}

// METIS/AMD and wasm/native ratios of one run (--compare), as the acceptance criteria state them.
function ratios(native, wasm) {
  const q = (a, b) => (a > 0 && b > 0 ? Number((a / b).toFixed(3)) : null);
  const out = {
    wasmAnalyzeMetisOverAmd: q(wasm.metis.analyzeMs, wasm.amd.analyzeMs),
    wasmStrokeSolveMetisOverAmd: q(wasm.metis.strokeUpdateSolveMs, wasm.amd.strokeUpdateSolveMs),
  };
  if (native?.metis) {
    Object.assign(out, {
      nativeAnalyzeMetisOverAmd: q(native.metis.analyzeMs, native.amd.analyzeMs),
      nativeStrokeSolveMetisOverAmd: q(native.metis.strokeUpdateSolveMs, native.amd.strokeUpdateSolveMs),
      // "≤ 0.5× one solve": a solve of the system (solveMs). The stroke's own solve (strokeSolveMs) redoes the
      // forward substitution only on the paths the stroke changed, so it is less than one; shown beside.
      nativeStrokeUpdateOverSolveMetis: q(native.metis.strokeUpdateMs, native.metis.solveMs),
      nativeStrokeUpdateOverStrokeSolveMetis: q(native.metis.strokeUpdateMs, native.metis.strokeSolveMs),
      wasmOverNativeStrokeSolveMetis: q(wasm.metis.strokeUpdateSolveMs, native.metis.strokeUpdateSolveMs),
      wasmOverNativeStrokeSolveAmd: q(wasm.amd.strokeUpdateSolveMs, native.amd.strokeUpdateSolveMs),
    });
  }
  return out;
}

// The native CLI the comparison needs: built here (scripts/build-native.sh, the `npm run build:native` of the
// docs/benchmarks.md) when the default build/tvf is missing.
function ensureNativeCli(opts) {
  if (opts['no-native'] || opts.native || existsSync(opts.tvf)) return;
  if (opts.tvf !== resolve(ROOT, 'build/tvf'))
    fail('native', `${opts.tvf} not found (build it, or pass --no-native)`);
  console.error('bench:wasm: build/tvf not found; building it (npm run build:native)');
  try {
    execFileSync('bash', [resolve(ROOT, 'scripts/build-native.sh'), '--target', 'tvf'], { stdio: ['ignore', 'ignore', 'inherit'] });
  } catch {
    fail('native', 'building build/tvf failed (see above); run `npm run setup` for the Debian packages, or pass --no-native');
  }
}

function child(args, opts) {
  const flags = opts['node-flags'] ? String(opts['node-flags']).split(/\s+/).filter(Boolean) : [];
  const out = execFileSync(process.execPath, [...flags, SELF, ...args], {
    encoding: 'utf8', maxBuffer: 1 << 24, stdio: ['ignore', 'pipe', 'inherit'],
  });
  return JSON.parse(out);
}

function commonArgs(opts) {
  const a = ['--repeat', String(opts.repeat), '--big-repeat', String(opts.bigRepeat), '--tvf', opts.tvf,
    '--settle', String(opts.settle)];
  if (opts.amd) a.push('--amd');
  if (opts.compare) a.push('--compare');
  if (opts.module) a.push('--module', opts.module);
  if (opts.threads) a.push('--threads', String(opts.threads));
  if (Number(opts.symmetry) > 1) a.push('--symmetry', String(opts.symmetry));
  if (opts.warmup === false) a.push('--no-warmup');
  else a.push('--warmup', String(opts.warmup));
  if (opts.native) a.push('--native', opts.native);
  if (opts['no-native']) a.push('--no-native');
  if (opts.scaling) a.push('--scaling');
  return a;
}

function nativeFor(mesh, opts, threads) {
  if (opts['no-native']) return null;
  if (opts.native) {
    const saved = JSON.parse(readFileSync(opts.native, 'utf8')).results ?? [];
    const hit = saved.find((r) => resolve(r.mesh ?? '') === mesh || r.name === meshName(mesh));
    if (hit) return hit;
  }
  // Like with like: the same ordering(s) as the wasm side.
  const ordering = opts.compare ? ['--compare'] : opts.amd ? ['--amd'] : [];
  return runNative(opts.tvf, mesh, repeatFor(opts, mesh), [...ordering, '--threads', String(threads),
    '--symmetry', String(opts.symmetry ?? 1), ...(opts.scaling ? ['--scaling'] : [])]);
}

async function main() {
  const argv = process.argv.slice(2);
  const opts = parseArgs(argv, {
    json: false, 'first-factor-only': false, 'no-warmup': false, warmup: '3,1', settle: '100', native: '',
    'no-native': false, 'node-flags': '', module: '', amd: false, compare: false, threads: '', symmetry: '1',
    quads: '', scaling: false,
  });
  if (opts.threads && !(Number.isInteger(Number(opts.threads)) && Number(opts.threads) >= 1))
    fail('--threads', `must be a whole number of at least 1 (got ${opts.threads})`);
  opts.warmup = opts['no-warmup'] ? false : opts.warmup;
  opts.settle = Number(opts.settle);
  opts.module = opts.module || undefined;

  if (opts.quads) {
    // The quad remesher alone (wasm/quad-bench.mjs): JSON, one mesh.
    if (opts.meshes.length !== 1) fail('--quads', 'give exactly one mesh');
    const mesh = opts.meshes[0];
    ensureMeshes([mesh]);
    const repeat = repeatFor(opts, mesh);
    const wasm = await measureQuadWasm(resolve(opts.module ?? defaultModule(opts)), mesh, Number(opts.quads), repeat);
    let native;
    if (!opts['no-native']) {
      ensureNativeCli(opts);
      native = measureQuadNative(opts.tvf, mesh, Number(opts.quads), repeat);
    }
    console.log(JSON.stringify({ mesh, wasm, native, wasmOverNative: native ? wasm.quadMs / native.quadMs : undefined }));
    return;
  }
  if (opts['first-factor-only']) {
    // Child: one cold first factorization.
    const r = await measureWasm(opts.meshes[0], { ...opts, firstOnly: true });
    console.log(JSON.stringify(r));
    return;
  }
  if (opts.json) {
    if (opts.meshes.length !== 1) fail('--json', 'give exactly one mesh');
    const mesh = opts.meshes[0];
    ensureMeshes([mesh]);
    ensureNativeCli(opts);
    opts.repeat = repeatFor(opts, mesh);
    const wasm = await measureWasm(mesh, opts);
    if (opts.warmup !== false && !opts.scaling) {
      const cold = child(['--first-factor-only', '--no-warmup', mesh, '--symmetry', String(opts.symmetry),
        ...(opts.module ? ['--module', opts.module] : []),
        ...(opts.threads ? ['--threads', String(opts.threads)] : [])], opts);
      wasm.firstFactorNoWarmUpMs = cold.firstFactorMs;
      for (const o of ['metis', 'amd']) if (wasm[o]) wasm[o].firstFactorNoWarmUpMs = cold.firstFactorMs;
    }
    const native = nativeFor(mesh, opts, wasm.threads);
    const out = { mesh, edges: wasm.edges, native, wasm };
    if (opts.compare) out.ratios = ratios(native, wasm);
    console.log(JSON.stringify(out, null, 2));
    return;
  }

  // The ladder: one child process per mesh.
  ensureMeshes(opts.meshes);
  ensureNativeCli(opts);
  const rows = [];
  for (const mesh of opts.meshes) {
    const name = meshName(mesh);
    process.stderr.write(`bench:wasm: ${name} ... `);
    try {
      const r = child(['--json', mesh, ...commonArgs(opts)], opts);
      rows.push({ name, ...r });
      const w = r.wasm.metis ?? r.wasm;
      process.stderr.write(`${r.edges} edges, wasm factor ${fmt(w.factorMs)} ms, first ${fmt(r.wasm.firstFactorMs)} ms\n`);
    } catch (err) {
      rows.push({ name, mesh, error: String(err.message).split('\n')[0] });
      process.stderr.write(`FAILED\n`);
    }
  }
  const ratio = (w, n) => (w > 0 && n > 0 ? `${(w / n).toFixed(2)}×` : '–');
  // --compare: one table row per mesh and ordering, and the ratios of the run.
  const flat = rows.flatMap((r) => r.error || !r.wasm.metis ? [r] : ['metis', 'amd'].map((o) => ({
    ...r, name: `${r.name} (${o === 'metis' ? 'METIS' : 'AMD'})`, native: r.native?.[o], wasm: r.wasm[o],
  })));
  const lines = [
    '| mesh | E | factor native | factor wasm | ratio | solve native | solve wasm | ratio | update native | update wasm | ratio | stroke+solve native / wasm | first factor wasm: cold / after warm-up (warm-up) |',
    '|' + ' --- |'.repeat(13),
  ];
  for (const r of flat) {
    if (r.error) {
      lines.push(`| ${r.name} | – | ${r.error} |`);
      continue;
    }
    const n = r.native ?? {}, w = r.wasm;
    lines.push(`| ${r.name} | ${r.edges.toLocaleString('en-US')} | ${fmt(n.factorMs)} | ${fmt(w.factorMs)} | ${ratio(w.factorMs, n.factorMs)} | ` +
      `${fmt(n.solveMs, 2)} | ${fmt(w.solveMs, 2)} | ${ratio(w.solveMs, n.solveMs)} | ` +
      `${fmt(n.updateMs, 2)} | ${fmt(w.updateMs, 2)} | ${ratio(w.updateMs, n.updateMs)} | ` +
      `${fmt(n.strokeUpdateSolveMs)} / ${fmt(w.strokeUpdateSolveMs)} | ` +
      `${fmt(w.firstFactorNoWarmUpMs)} / ${fmt(w.firstFactorMs)} (${fmt(w.warmUpMs)}) |`);
  }
  console.log(lines.join('\n'));
  console.log('\nwasm, full table (times in ms; factor/solve/update as timed by the core, as in `tvf bench`):\n');
  console.log(nativeTable(flat.filter((r) => !r.error).map((r) => ({ name: r.name, ...r.wasm }))));
  const withRatios = rows.filter((r) => r.ratios);
  if (withRatios.length) {
    const keys = Object.keys(withRatios[0].ratios);
    console.log(`\nratios of one run (medians):\n\n| mesh | ${keys.join(' | ')} |\n|${' --- |'.repeat(keys.length + 1)}`);
    for (const r of withRatios) console.log(`| ${r.name} | ${keys.map((k) => fmt(r.ratios[k], 2)).join(' | ')} |`);
  }
  mkdirSync(resolve(ROOT, 'bench-data'), { recursive: true });
  const out = resolve(ROOT, 'bench-data/bench-wasm.json');
  writeFileSync(out, JSON.stringify({ date: new Date().toISOString(), node: process.version, results: rows }, null, 2) + '\n');
  console.error(`bench:wasm: wrote ${out}`);
  if (rows.some((r) => r.error)) process.exit(1);
}

try {
  await main();
} catch (err) {
  // A missing build or mesh is a message, not a stack trace.
  console.error(`bench:wasm: ${err.message}`);
  process.exit(1);
}

#!/usr/bin/env node
// Benchmarks of the real page in Debian's Chromium (never a downloaded browser), served from dist/ (build it
// first: npm run build:wasm && npm run build:web).
//
// node scripts/bench-web.mjs --json --stroke MESH [--strokes N] [--crossings N] [--port P] [--profile FILE]
//                             [--profile-load FILE]   (CPU profiles of the page's thread over the strokes, the load)
//                             [--preview-edges N]   (loadModel's previewEdges: 1 forces a preview, 0 none)
//                             [--symmetry N]   (the strokes on an N-direction field: 2 line, 4 cross; default 1)
//                             [--texture N]   (then the texture: its first synthesis and N strokes' updates,
//                             each broken into its phases: textureFirstPhases, textureUpdatePhases; and
//                             textureOnScreenMs, textureUpdateOnScreenMs: to the GPU done with the first frame
//                             that draws it, *FirstFrameMs that frame alone)
//                             [--texture-redone]   (with --texture: textureUpdateRedoneShare, each update's share
//                             of the texels whose coordinates changed, read back after it was timed)
//                             [--reopen [--reload]]   (the mesh opened again, over itself or in the page
//                             reloaded: reopenExactFieldMs, loadModel to its exact field, the ordering, preview
//                             parts and picking tree kept; with --texture its texture made again too)
//                             [--trace-reopen FILE]   (a Chromium trace of every thread over the reopening)
//                             [--profile-reopen FILE]   (a CPU profile of the page's thread over the reopening)
//                             (the load's and the reopening's frames over 100 ms, with the scripts that ran in
//                             them, are loadLongFrames and reopenLoadLongFrames; reopenFirstRefreshMs is the
//                             first field's views and frame, drawn in the task that adopts it)
//                             [--undo N]   (after the strokes, N undos then N redos, each timed as a stroke
//                             is: undoMs, redoMs (pageMs), undoUpdateMs/redoUpdateMs and undoSolveMs (the core's))
//                             [--stripes N]   (then the stripes: turned on, and N strokes' updates: stripes*
//                             keys, bench-web-stripes.mjs)
//                             [--profile-stripes FILE]   (a CPU profile of the page's thread over the stripes stage)
//                             [--trace-stripes FILE]   (a Chromium trace of every thread over the stripes stage)
//                             [--gpu]   (hardware WebGL: ANGLE on Vulkan, or TVF_GPU_ARGS; default SwiftShader)
//                             (TVF_JS_FLAGS in the environment: V8 flags for the page, as Chromium's --js-flags)
//                             [--texture-new]   (the texture's strokes new ones, elsewhere, not the first N again)
//                             [--profile-texture FILE]   (a CPU profile of the page's thread over the texture's runs)
//                             [--trace-texture FILE]   (a Chromium trace of every thread over the texture's runs)
//                             [--trace FILE]   (a Chromium trace of every process and thread over the strokes:
//                             the exact worker, the preview worker and the GPU process side by side)
//   Edit latency: loads MESH (a path; served to the page under /bench-mesh/) through tvf.loadModel, then draws
//   N strokes (default 15) of ~50 crossed edges each through tvf.addStroke, each on a strip of faces elsewhere
//   on the mesh. Prints one JSON object {mesh, edges, strokes, loadMs, median: {...}, ratios} whose medians are
//     updateMs, solveMs, rhsMs, rowsMs   the core's own timings of the edit (DesignStats)
//     workerMs      all worker-side time of the edit (message in to reply out)
//     workerOpMs, workerSolveMs, copyMs, deriveMs, designMs, workerOtherMs   where the worker's time goes:
//                   the add itself (walk + update), the solve (right-hand side, solve, face vectors), copying
//                   the field out of the wasm heap, the vertex vectors, the design change, statsMs (the core's stats), the rest
//     reconstructMs the core's face vectors after the solve (DesignStats)
//     messageMs     round trip less workerMs (structured clone, transfer, event-loop waits)
//     applyMs       the page taking the snapshot and redrawing (refreshMs of it: updating the views; renderMs:
//                   the synchronous three.js render), up to the promise resolving
//     pageMs        tvf.addStroke() call to its promise resolving with the new field drawn
//     pageNoRenderMs  pageMs less renderMs (with software GL the render is rasterization on the CPU)
//   and ratios workerOverUpdateSolve = workerMs / (updateMs + solveMs), page*OverUpdateSolve likewise (of the
//   medians), and ratiosPerEdit: the same ratios taken per edit, then the median.
//   and issue 28's measures: firstFieldMs and exactFieldMs (loadModel called → the first field drawn, the exact one:
//   tvf.settled()), strokePreviewMs and strokeExactMs (medians: a stroke's first field drawn, a preview on a big
//   mesh, and its exact field, each when its draw was issued; strokeExactOnScreenMs: the exact field with two
//   frames presented after it), longestTaskMs (the main thread's longest task during load and strokes,
//   PerformanceObserver 'longtask'), heapPeakBytes (the exact core's wasm memory at the end).
//   Writes bench-data/web-stroke-bench.json.
//
// node scripts/bench-web.mjs [--sizes 256,512,1024] [--port 8194]
//   Texture synthesis: opens /?bench=1 and prints per-level and total times for 256², 512² and 1024² atlases
//   with the ratio to a plain full-screen pass of the same size (web/synthesis/bench.js).
//   Writes bench-data/synthesis-bench.json.
import { spawn } from 'node:child_process';
import { copyFileSync, existsSync, mkdirSync, rmSync, writeFileSync } from 'node:fs';
import { basename, dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from '@playwright/test';
import { stripStrokesInPage } from '../tests/e2e/helpers.mjs';
import { startProfile } from './page-session.mjs';
import { stripesBench } from './bench-web-stripes.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const arg = (name, fallback) => {
  const i = process.argv.indexOf(name);
  return i > 0 ? process.argv[i + 1] : fallback;
};
const sizes = arg('--sizes', '256,512,1024');
const port = Number(arg('--port', process.env.PORT || 8194));
const strokeMesh = arg('--stroke', null);

function die(message) {
  console.error(`bench:web: ${message}`);
  process.exit(1);
}
if (!existsSync(resolve(ROOT, 'dist/index.html'))) die('dist/ not found; run npm run build:wasm && npm run build:web');
if (strokeMesh !== null && !existsSync(resolve(strokeMesh))) die(`mesh ${strokeMesh} not found (meshes: scripts/fetch-meshes.sh)`);

const median = (v) => {
  const s = v.filter(Number.isFinite).sort((a, b) => a - b);
  return s.length === 0 ? null : s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};

async function strokeBench(page, meshPath) {
  const count = Number(arg('--strokes', 15));
  const crossings = Number(arg('--crossings', 50));
  const name = basename(meshPath);
  // Served by the app's own server as a real download (a route through the driver took seconds at 33 MB).
  mkdirSync(resolve(ROOT, 'dist/bench-mesh'), { recursive: true });
  copyFileSync(resolve(meshPath), resolve(ROOT, 'dist/bench-mesh', name));
  // Long tasks of the page's main thread (> 50 ms by the browser's definition), from the page's start on.
  await page.addInitScript(() => {
    window.__longTasks = [];
    new PerformanceObserver((list) => window.__longTasks.push(...list.getEntries().map((e) => ({ at: e.startTime, ms: e.duration })))).observe({ type: 'longtask', buffered: true });
    // Frames over 100 ms with the scripts that ran in them (function, file and position, no profiler attached:
    // with one, the tasks change), to name a long task's code: loadLongFrames, reopenLoadLongFrames.
    window.__longFrames = [];
    const script = (s) => ({ ms: Math.round(s.duration), fn: s.sourceFunctionName, at: `${s.sourceURL.split('/').pop()}:${s.sourceCharPosition}`, invoker: s.invoker });
    new PerformanceObserver((list) => window.__longFrames.push(...list.getEntries().filter((e) => e.duration > 100).map((e) => ({ at: e.startTime, ms: Math.round(e.duration), blockingMs: Math.round(e.blockingDuration), scripts: e.scripts.filter((s) => s.duration > 20).map(script) })))).observe({ type: 'long-animation-frame', buffered: true });
  });
  page.on('console', (m) => m.type() === 'warning' && !m.text().includes('GL Driver') && console.error(`page: ${m.text()}`));
  await page.goto(`http://127.0.0.1:${port}/`);
  await page.evaluate(() => window.tvf.ready);
  // --profile-load FILE: a CPU profile of the page's main thread over the load (.cpuprofile, for DevTools).
  const loadProfile = await startProfile(page, arg('--profile-load', null));
  const load = await page.evaluate(async ({ url, previewEdges }) => {
    window.__longTasks.length = 0; // the page's own start is not the model's
    const t0 = performance.now();
    const info = await window.tvf.loadModel(url, { restore: false, ...(previewEdges != null ? { previewEdges } : {}) });
    const firstFieldMs = performance.now() - t0;
    const firstStats = window.tvf.stats();
    const previewTimings = window.tvf.perf().previewTimings ?? null;
    const modelRead = window.tvf.perf().modelRead ?? null;
    const phases = Object.fromEntries(Object.entries(window.tvf.perf().loadPhases ?? {}).map(([k, v]) => [k, v - t0]));
    await window.tvf.settled();
    if (firstStats.preview) await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
    const { analyzeMs, factorMs, analysisReused } = window.tvf.stats(); // the exact field's factorization
    return { t0, info, phases, modelRead, previewTimings, loadMs: performance.now() - t0, firstFieldMs, exactFieldMs: performance.now() - t0, preview: firstStats.preview, previewFaces: firstStats.previewFaces ?? null, previewStats: firstStats, exactFactor: { analyzeMs, factorMs, analysisReused } };
  }, { url: `/bench-mesh/${name}`, previewEdges: arg('--preview-edges', null) == null ? null : Number(arg('--preview-edges')) });
  await loadProfile.stop();
  // A task that began before loadModel was called (the page's own start, reported late) is not the load's.
  const loadTasks = (await page.evaluate(() => window.__longTasks.splice(0))).filter((t) => t.at >= load.t0);
  const loadFrames = (await page.evaluate(() => window.__longFrames.splice(0))).filter((f) => f.at >= load.t0);
  // --symmetry N: the field the strokes are drawn on (its smoothest field solved and drawn before the first).
  const symmetry = Number(arg('--symmetry', 1));
  if (symmetry !== 1) await page.evaluate(async (n) => { await window.tvf.setSymmetry(n); await window.tvf.settled(); }, symmetry);
  const starts = Array.from({ length: count }, (_, s) => (s * 104729 + 7) % load.info.faces); // spread over the mesh
  const strokes = await page.evaluate(stripStrokesInPage, { starts, crossings });
  // Making the strokes filled the page's heap with a map of every edge (~180 MB at 1.25M edges), garbage whose
  // collection would otherwise fall on a stroke (a 117 ms pause in a profile): it is collected now, and its
  // pause is not the strokes'.
  const cdp = await page.context().newCDPSession(page);
  await cdp.send('HeapProfiler.collectGarbage');
  await cdp.detach();
  await page.evaluate(() => window.__longTasks.splice(0));
  // --profile FILE: a CPU profile of the page's main thread over the strokes (.cpuprofile, for DevTools).
  const strokesProfile = await startProfile(page, arg('--profile', null));
  // --trace FILE: a Chromium trace of every process and thread over the strokes (chrome://tracing, Perfetto).
  const traceFile = arg('--trace', null);
  if (traceFile) await page.context().browser().startTracing(page, { path: traceFile, categories: ['toplevel', 'v8', 'gpu', 'gpu.angle', 'disabled-by-default-gpu.service', 'disabled-by-default-devtools.timeline', 'devtools.timeline'] });
  const runs = [];
  for (const points of strokes) {
    runs.push(await page.evaluate(async (pts) => {
      // A user's pace: the previous field is on screen (two frames presented) before the next stroke. With
      // software GL a frame of a million triangles takes the GPU process a second or more, and a render issued
      // while one is in flight waits for it.
      await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
      const t0 = performance.now();
      await window.tvf.addStroke(pts);
      const pageMs = performance.now() - t0;
      const { lastOp, refresh } = window.tvf.perf();
      const preview = window.tvf.stats().preview;
      await window.tvf.settled();
      // After a preview the exact field lands later and is drawn at once. exactMs: its draw issued, as pageMs
      // is the preview's (addStroke resolves once its draw is issued); exactOnScreenMs: two frames presented
      // after that (with software GL each waits for the rasterization of the last: seconds at a million
      // triangles). Without a preview the stroke's own field was drawn before addStroke resolved.
      const frame = () => new Promise((resolve) => requestAnimationFrame(resolve));
      let exactMs = pageMs;
      if (preview) {
        const drawn = (p) => p.exactLandedAt > t0 && p.refresh?.drawnAt >= p.exactLandedAt;
        while (!drawn(window.tvf.perf())) await frame();
        exactMs = window.tvf.perf().refresh.drawnAt - t0;
        await frame();
        await frame();
      }
      const exactOnScreenMs = preview ? performance.now() - t0 : pageMs;
      // The exact worker puts the stroke's update into its factor after its reply (Designer::setDeferredUpdates):
      // a user's next stroke, which takes longer than that to draw, finds it done, and so does the bench's.
      const deferredAt = performance.now();
      const held = () => window.tvf.perf().deferredUpdate;
      while (held() && !(held().at > t0) && performance.now() - deferredAt < 10_000) await frame();
      const deferredUpdateMs = held()?.ms ?? null;
      const stats = window.tvf.stats();
      const last = window.tvf.perf().lastExact;
      const exact = preview && last ? { workerMs: last.workerMs, ...last.workerParts, receivedMs: last.receivedAt - t0, applyMs: last.applyMs } : null;
      return { pageMs, exactMs, exactOnScreenMs, preview, lastOp, refresh, stats, exact, deferredUpdateMs };
    }, points));
  }
  await strokesProfile.stop();
  if (traceFile) await page.context().browser().stopTracing();
  const undo = arg('--undo', null) == null ? null : await undoBench(page, Number(arg('--undo')));
  const reopenAlone = process.argv.includes('--reopen') && arg('--texture', null) == null;
  const reopen = reopenAlone ? await reopenBench(page, `/bench-mesh/${name}`) : null;
  // The texture's strokes: the first N again (over themselves: the field barely moves, and a local update may
  // make no texel again), or with --texture-new N new ones elsewhere, which move the field where they go.
  const textureCount = Number(arg('--texture', 0));
  const textureStrokes = !process.argv.includes('--texture-new') ? strokes.slice(0, textureCount)
    : await page.evaluate(stripStrokesInPage, {
      starts: Array.from({ length: textureCount }, (_, s) => (s * 7919 + 2029) % load.info.faces), crossings });
  const texture = arg('--texture', null) == null ? null : await textureBench(page, textureStrokes, `/bench-mesh/${name}`);
  const stripesProfile = await startProfile(page, arg('--profile-stripes', null));
  const stripesTrace = arg('--trace-stripes', null);
  if (stripesTrace) await page.context().browser().startTracing(page, { path: stripesTrace, categories: ['toplevel', 'v8', 'gpu', 'disabled-by-default-gpu.service', 'devtools.timeline'] });
  // The stripes' strokes are new ones (elsewhere on the mesh): a stroke drawn again over itself barely moves the
  // field, and the stripes' update is of where the field moved.
  const stripeStarts = Array.from({ length: Number(arg('--stripes', 0)) },
    (_, s) => (s * 104729 + 52361) % load.info.faces);
  const stripes = arg('--stripes', null) == null ? null
    : await stripesBench(page, await page.evaluate(stripStrokesInPage, { starts: stripeStarts, crossings }));
  await stripesProfile.stop();
  if (stripesTrace) await page.context().browser().stopTracing();
  const pick = (f) => median(runs.map(f));
  const m = {
    updateMs: pick((r) => r.stats.updateMs),
    solveMs: pick((r) => r.stats.solveMs),
    rhsMs: pick((r) => r.stats.rhsMs),
    rowsMs: pick((r) => r.stats.rowsMs),
    workerMs: pick((r) => r.lastOp.workerMs),
    workerOpMs: pick((r) => r.lastOp.workerParts?.opMs),
    workerSolveMs: pick((r) => r.lastOp.workerParts?.solveMs),
    copyMs: pick((r) => r.lastOp.workerParts?.copyMs),
    deriveMs: pick((r) => r.lastOp.workerParts?.deriveMs),
    designMs: pick((r) => r.lastOp.workerParts?.designMs),
    statsMs: pick((r) => r.lastOp.workerParts?.statsMs),
    // Field arrays the worker refilled from buffers the page handed back, instead of allocating (of 3).
    reusedArrays: pick((r) => r.lastOp.workerParts?.reusedArrays),
    // The worker's time outside the parts above (the reply's stats, the message's own handling), per edit.
    workerOtherMs: pick((r) => {
      const p = r.lastOp.workerParts ?? {};
      return r.lastOp.workerMs - ['opMs', 'solveMs', 'copyMs', 'deriveMs', 'designMs', 'statsMs'].reduce((t, k) => t + (p[k] ?? 0), 0);
    }),
    reconstructMs: pick((r) => r.stats.reconstructMs),
    messageMs: pick((r) => r.lastOp.roundTripMs - r.lastOp.workerMs),
    applyMs: pick((r) => r.pageMs - r.lastOp.roundTripMs),
    refreshMs: pick((r) => r.refresh?.updateViewsMs),
    renderMs: pick((r) => r.refresh?.renderMs),
    pageMs: pick((r) => r.pageMs),
    // JS time only: with software GL (SwiftShader here) the synchronous render is the rasterizer's time.
    pageNoRenderMs: pick((r) => r.pageMs - (r.refresh?.renderMs ?? 0)),
  };
  const updateSolve = m.updateMs + m.solveMs;
  const strokeTasks = await page.evaluate(() => window.__longTasks.splice(0));
  const strokeFrames = await page.evaluate(() => window.__longFrames.splice(0));
  const longest = (tasks) => tasks.reduce((m, t) => Math.max(m, t.ms), 0);
  const result = {
    mesh: meshPath,
    renderer: await page.evaluate(rendererString),
    edges: load.info.edges,
    // Issue 28's measures: the first field and the exact one after loadModel is called; a stroke's field drawn
    // (the preview's on a big mesh) and its exact field (medians); the longest main-thread task during the load
    // and during the strokes; the exact core's wasm memory (it never shrinks: the peak).
    firstFieldMs: load.firstFieldMs,
    exactFieldMs: load.exactFieldMs,
    exactFactor: load.exactFactor,
    preview: load.preview,
    previewFaces: load.previewFaces,
    strokePreviewMs: median(runs.map((r) => r.pageMs)),
    strokeExactMs: median(runs.map((r) => r.exactMs)),
    strokeExactOnScreenMs: median(runs.map((r) => r.exactOnScreenMs)),
    // The stroke's update put into the exact factor after its field was sent (the edit's own updateMs is then
    // the correction the solve went through: solver/woodbury_correction.h).
    strokeDeferredUpdateMs: median(runs.map((r) => r.deferredUpdateMs)),
    // Where a stroke's exact field spends its time (medians): the exact worker's parts (as workerParts below),
    // its reply received on the page (ms after addStroke), and the page applying it up to the draw.
    strokeExactParts: runs.some((r) => r.exact) ? Object.fromEntries(['workerMs', 'opMs', 'solveMs', 'copyMs', 'deriveMs', 'designMs', 'statsMs', 'receivedMs', 'applyMs'].map((k) => [k, median(runs.map((r) => r.exact?.[k]))])) : null,
    strokesPreviewed: runs.filter((r) => r.preview).length,
    longestTaskMs: Math.max(longest(loadTasks), longest(strokeTasks)),
    longestLoadTaskMs: longest(loadTasks),
    // The load's long tasks: when each began (ms after loadModel was called) and how long it took.
    loadLongTasks: loadTasks.map((t) => ({ at: Math.round(t.at - load.t0), ms: t.ms })),
    loadLongFrames: loadFrames.map((f) => ({ ...f, at: Math.round(f.at - load.t0) })),
    longestStrokeTaskMs: longest(strokeTasks),
    // The frames over 100 ms from the load's end to the strokes' (the symmetry's change included), with their
    // scripts: what a long task there was.
    strokeLongFrames: strokeFrames.map((f) => ({ ...f, at: Math.round(f.at - load.t0) })),
    heapPeakBytes: runs.at(-1)?.stats.heapBytes ?? null,
    // --undo N: N undos of the strokes, then N redos (medians).
    ...(undo ?? {}),
    // --reopen without --texture: the mesh opened again.
    ...(reopen ?? {}),
    // --texture N: the texture synthesized on the field, then N of the strokes again (or N new ones, --texture-new)
    // with the texture shown.
    ...(texture ?? {}),
    // --stripes N: the stripe pattern turned on, then N of the strokes again with the stripes shown.
    ...(stripes ?? {}),
    previewHeapBytes: load.previewStats.previewHeapBytes ?? null,
    loadPhasesMs: load.phases,
    modelRead: load.modelRead,
    previewTimings: load.previewTimings,
    strokes: runs.length,
    symmetry,
    crossings,
    loadMs: load.loadMs,
    factorKind: runs.at(-1)?.stats.factorKind,
    median: m,
    // Each edit's own ratio, then the median: steadier than a ratio of medians on a busy machine.
    ratiosPerEdit: {
      workerOverUpdateSolve: Number(pick((r) => r.lastOp.workerMs / (r.stats.updateMs + r.stats.solveMs)).toFixed(2)),
      pageNoRenderOverUpdateSolve: Number(pick((r) => (r.pageMs - (r.refresh?.renderMs ?? 0)) / (r.stats.updateMs + r.stats.solveMs)).toFixed(2)),
      pageOverUpdateSolve: Number(pick((r) => r.pageMs / (r.stats.updateMs + r.stats.solveMs)).toFixed(2)),
    },
    ratios: {
      workerOverUpdateSolve: Number((m.workerMs / updateSolve).toFixed(2)),
      pageOverUpdateSolve: Number((m.pageMs / updateSolve).toFixed(2)),
      pageNoRenderOverUpdateSolve: Number((m.pageNoRenderMs / updateSolve).toFixed(2)),
    },
  };
  console.log(process.argv.includes('--json') ? JSON.stringify(result, null, 2) : result);
  mkdirSync(resolve(ROOT, 'bench-data'), { recursive: true });
  writeFileSync(resolve(ROOT, 'bench-data/web-stroke-bench.json'), JSON.stringify({ date: new Date().toISOString(), ...result }, null, 1));
  rmSync(resolve(ROOT, 'dist/bench-mesh'), { recursive: true, force: true });
}

// The WebGL renderer the page gets (unmasked where the browser tells it).
function rendererString() {
  const gl = document.createElement('canvas').getContext('webgl2');
  if (!gl) return 'no WebGL2';
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  return gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER);
}

// The texture's first synthesis (the atlas generated, the exemplar analysed) and its updates after strokes
// (auto-update: each stroke's preview, then its exact field): the time to the texture done, the main thread's
// longest task during each, and where the time went: the run's phases (synthesisStats().phases, phase-clock.js)
// with what came before the run (the stroke's solve, for an update) and after it (the texture shown to the
// promise resolving), beside the wall time measured here on its own.
// The mesh opened again (what IndexedDB kept per mesh from its first opening: the ordering, the preview's parts,
// the picking tree), in the same page over itself, or with --reload in the page reloaded (a fresh core, heap and
// JIT, as a user opening the model another day finds them): its first and exact fields timed from loadModel, as
// the first opening's are.
async function reopenBench(page, url) {
  if (process.argv.includes('--reload')) {
    await page.reload();
    await page.evaluate(() => window.tvf.ready);
    await page.evaluate(() => window.tvf.settled());
  }
  const traceFile = arg('--trace-reopen', null);
  const categories = ['toplevel', 'v8', 'gpu', 'gpu.angle', 'disabled-by-default-gpu.service', 'disabled-by-default-gpu.decoder', 'disabled-by-default-devtools.timeline', 'devtools.timeline'];
  if (traceFile) await page.context().browser().startTracing(page, { path: traceFile, categories });
  const profile = await startProfile(page, arg('--profile-reopen', null));
  const r = await page.evaluate(async (u) => {
    window.__longTasks.length = 0;
    window.__longFrames.length = 0;
    const t0 = performance.now();
    await window.tvf.loadModel(u, { restore: false });
    const firstMs = performance.now() - t0;
    const firstRefresh = window.tvf.perf().refresh; // the first field's views and frame, in its task
    await window.tvf.settled();
    const exactMs = performance.now() - t0;
    const { previewTimings, pickingTreeKept, loadPhases } = window.tvf.perf();
    const phases = Object.fromEntries(Object.entries(loadPhases ?? {}).map(([k, v]) => [k, Math.round(v - t0)]));
    const { analyzeMs, factorMs, analysisReused } = window.tvf.stats();
    const tasks = window.__longTasks.splice(0);
    const frames = window.__longFrames.splice(0).map((f) => ({ ...f, at: Math.round(f.at - t0) }));
    return { firstRefresh, frames, t0, firstMs, exactMs, analyzeMs, factorMs, analysisReused, previewTimings, pickingTreeKept, phases, tasks };
  }, url);
  if (traceFile) await page.context().browser().stopTracing();
  await profile.stop();
  return {
    reopenFirstFieldMs: r.firstMs,
    reopenExactFieldMs: r.exactMs,
    reopenExactFactor: { analyzeMs: r.analyzeMs, factorMs: r.factorMs, analysisReused: r.analysisReused },
    reopenPreviewKept: r.previewTimings?.kept ?? null,
    reopenPickingTreeKept: r.pickingTreeKept ?? null,
    reopenPhasesMs: r.phases,
    reopenPreviewTimings: r.previewTimings,
    longestReopenLoadTaskMs: r.tasks.reduce((m, t) => Math.max(m, t.ms), 0),
    reopenLoadLongTasks: r.tasks.map((t) => ({ at: Math.round(t.at - r.t0), ms: Math.round(t.ms) })),
    reopenLoadLongFrames: r.frames,
    reopenFirstRefreshMs: { updateViews: r.firstRefresh?.updateViewsMs, render: r.firstRefresh?.renderMs },
  };
}

// N undos of the last strokes, then N redos, each at a user's pace (the previous field on screen), timed from the
// call to its field drawn (the exact one, settled) with the core's update (a downdate for an undone stroke) and
// solve.
async function undoBench(page, n) {
  const step = (op) => page.evaluate(async (op) => {
    await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
    const t0 = performance.now();
    await window.tvf[op]();
    await window.tvf.settled();
    const { updateMs, solveMs, factorizations, precisionRefactors } = window.tvf.stats();
    return { ms: performance.now() - t0, updateMs, solveMs, factorizations, precisionRefactors };
  }, op);
  const undos = [], redos = [];
  for (let k = 0; k < n; k++) undos.push(await step('undo'));
  for (let k = 0; k < n; k++) redos.push(await step('redo'));
  const of = (runs, key) => median(runs.map((r) => r[key]));
  return {
    undoMs: of(undos, 'ms'), undoUpdateMs: of(undos, 'updateMs'), undoSolveMs: of(undos, 'solveMs'),
    redoMs: of(redos, 'ms'), redoUpdateMs: of(redos, 'updateMs'), redoSolveMs: of(redos, 'solveMs'), undos: n,
    undoSteps: undos.map((r) => Math.round(r.ms)), redoSteps: redos.map((r) => Math.round(r.ms)),
    undoFactorizations: undos.at(-1)?.factorizations, undoPrecisionRefactors: undos.at(-1)?.precisionRefactors,
  };
}

// window.__onScreen(t1): resolves with the milliseconds from t1 until the GPU has finished the view's next
// frame (two animation frames, then a fence in the view's context).
const ON_SCREEN = () => {
  window.__onScreen = async (t1) => {
    const root = document.querySelector('tangent-field-designer').shadowRoot;
    const gl = root.querySelector('#viewport canvas').getContext('webgl2');
    await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
    const fence = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
    gl.flush();
    while (gl.getSyncParameter(fence, gl.SYNC_STATUS) !== gl.SIGNALED) await new Promise((r) => setTimeout(r, 1));
    gl.deleteSync(fence);
    return performance.now() - t1;
  };
};

// In the page: the share of the texture's texels (inside the charts) whose synthesized coordinates changed since
// the last call (1 at the first), read back after the timing.
const REDONE_SHARE = `(async () => {
  const c = (await window.tvf.synthesisReadback()).coords, last = window.__lastCoords;
  window.__lastCoords = c;
  let changed = 0, inside = 0;
  for (let t = 0; t < c.length; t += 4) {
    if (c[t + 3] === 0) continue;
    inside++;
    if (!last || c[t] !== last[t] || c[t + 1] !== last[t + 1]) changed++;
  }
  return changed / inside;
})()`;

async function textureBench(page, strokes, url) {
  await page.evaluate(() => window.__longTasks.splice(0));
  const profile = await startProfile(page, arg('--profile-texture', null));
  const traceFile = arg('--trace-texture', null);
  const categories = ['toplevel', 'v8', 'gpu', 'gpu.angle', 'disabled-by-default-gpu.service', 'disabled-by-default-gpu.decoder', 'devtools.timeline'];
  if (traceFile) await page.context().browser().startTracing(page, { path: traceFile, categories });
  await page.evaluate(ON_SCREEN);
  const first = await page.evaluate(async () => {
    const t0 = performance.now();
    await window.tvf.synthesize();
    const s = await window.tvf.synthesisIdle();
    const t1 = performance.now();
    return { wallMs: t1 - t0, t0, t1, stats: s, firstFrameMs: await window.__onScreen(t1) };
  });
  const firstTasks = await page.evaluate(() => window.__longTasks.splice(0));
  const redone = process.argv.includes('--texture-redone') ? [] : null;
  if (redone) await page.evaluate(REDONE_SHARE);
  const updates = [];
  for (const points of strokes) {
    updates.push(await page.evaluate(async (pts) => {
      await new Promise((resolve) => requestAnimationFrame(() => requestAnimationFrame(resolve)));
      const frames = window.tvf.debugRecordFrames();
      const t0 = performance.now();
      await window.tvf.addStroke(pts);
      await window.tvf.settled();
      const s = await window.tvf.synthesisIdle();
      const t1 = performance.now();
      const firstFrameMs = await window.__onScreen(t1);
      // The view's frames from the stroke to the texture on screen (ms from the stroke).
      return { wallMs: t1 - t0, t0, t1, stats: s, firstFrameMs, frames: frames.map((t) => Math.round(t - t0)) };
    }, points));
    if (redone) redone.push(await page.evaluate(REDONE_SHARE));
  }
  const updateTasks = await page.evaluate(() => window.__longTasks.splice(0));
  // --reopen: the same mesh opened again, its texture made again (the atlas from the worker's cache).
  const reopened = !process.argv.includes('--reopen') ? null : await page.evaluate(async (u) => {
    await window.tvf.clearTexture();
    const tOpen = performance.now();
    await window.tvf.loadModel(u, { restore: false });
    await window.tvf.settled();
    // The exact field of the mesh opened again (its ordering kept from the first opening, ordering-cache.js).
    const { analyzeMs, factorMs, analysisReused } = window.tvf.stats();
    window.__reopenExact = { ms: performance.now() - tOpen, analyzeMs, factorMs, analysisReused };
    window.__reopenLoadTasks = window.__longTasks.splice(0);
    const t0 = performance.now();
    await window.tvf.synthesize();
    const s = await window.tvf.synthesisIdle();
    return { wallMs: performance.now() - t0, t0, t1: performance.now(), stats: s };
  }, url);
  const reopenTasks = reopened ? await page.evaluate(() => [window.__reopenLoadTasks, window.__longTasks.splice(0)]) : null;
  const reopenExact = reopened ? await page.evaluate(() => window.__reopenExact) : null;
  await profile.stop();
  if (traceFile) await page.context().browser().stopTracing();
  const longest = (tasks) => tasks.reduce((m, t) => Math.max(m, t.ms), 0);
  const byWall = [...updates].sort((a, b) => a.wallMs - b.wallMs);
  const medianUpdate = byWall[Math.floor((byWall.length - 1) / 2)];
  return {
    textureFirstMs: first.wallMs,
    textureUpdateMs: median(updates.map((u) => u.wallMs)),
    textureUpdates: updates.length,
    textureFirstPhases: phaseTable(first, 'before the run'),
    textureUpdatePhases: medianUpdate ? phaseTable(medianUpdate, 'stroke solved, field changed') : null,
    textureEachUpdatePhases: updates.map((u) => phaseTable(u, 'stroke solved, field changed')),
    // From the texture shown to the GPU done with the first frame that draws it (the user sees it then): the
    // next stroke starts after it, as a user's would.
    textureFirstFrameMs: first.firstFrameMs,
    textureUpdateFirstFrameMs: median(updates.map((u) => u.firstFrameMs)),
    textureOnScreenMs: first.wallMs + first.firstFrameMs,
    textureUpdateOnScreenMs: median(updates.map((u) => u.wallMs + u.firstFrameMs)),
    ...(redone ? { textureUpdateRedoneShare: redone.map((f) => +f.toFixed(4)) } : {}),
    // Per update, the faces whose Jacobian was drawn again (synthesisStats().raster).
    textureUpdateRaster: updates.map((u) => u.stats?.raster ?? null),
    textureUpdateFrames: updates.map((u) => u.frames), // the view's frames, ms from each stroke
    ...(reopened ? {
      reopenExactFieldMs: reopenExact.ms,
      reopenExactFactor: { analyzeMs: reopenExact.analyzeMs, factorMs: reopenExact.factorMs,
        analysisReused: reopenExact.analysisReused },
      textureReopenedMs: reopened.wallMs,
      textureReopenedPhases: phaseTable(reopened, 'before the run'),
      // The main thread's longest task while the model was opened again, and while its texture was made.
      longestReopenLoadTaskMs: longest(reopenTasks[0]),
      longestTextureReopenedTaskMs: longest(reopenTasks[1]),
    } : {}),
    longestTextureFirstTaskMs: longest(firstTasks),
    longestTextureUpdateTaskMs: longest(updateTasks),
    textureUpdateLongTasks: updateTasks.map((t) => Math.round(t.ms)),
    textureFirstLongTasks: firstTasks.map((t) => Math.round(t.ms)),
    textureStats: first.stats && {
      resolution: first.stats.resolution,
      totalMs: first.stats.totalMs,
      atlasMs: first.stats.atlas?.ms,
      chartMs: first.stats.atlas?.chartMs,
      gpuMs: first.stats.gpuMs,
      slices: first.stats.slices,
      sliceTexels: first.stats.sliceTexels,
      atlasWorkerSteps: first.stats.atlas?.workerSteps,
      atlasCache: first.stats.atlas?.cache,
    },
  };
}

// One texture's phases, in the page's clock: `before` (call or stroke to the run's start), the run's own, and
// 'after shown'; with their sum, the wall time measured around it, and the kernel's and the rest's shares.
function phaseTable({ wallMs, t0, t1, stats }, before) {
  if (!stats?.phases) return null;
  const round = (x) => Math.round(10 * x) / 10;
  const phases = { [before]: round(stats.startedAt - t0), ...stats.phases, 'after shown': round(t1 - stats.shownAt) };
  const sum = Object.values(phases).reduce((a, b) => a + b, 0);
  const kernel = Object.entries(phases).reduce((a, [k, v]) => a + (k.includes('kernel') ? v : 0), 0);
  return {
    phases,
    sumMs: round(sum),
    wallMs: round(wallMs),
    sumOverWall: Math.round((1000 * sum) / wallMs) / 1000,
    kernelMs: round(kernel),
    nonKernelMs: round(sum - kernel),
    viewFrames: stats.viewFrames, // the view's frames drawn during the run, beside it on the GPU
  };
}

const server = spawn(process.execPath, [resolve(ROOT, 'scripts/serve.mjs')], { env: { ...process.env, PORT: String(port) }, stdio: ['ignore', 'pipe', 'inherit'] });
await new Promise((ok, fail) => {
  server.stdout.on('data', (d) => String(d).includes('http://') && ok());
  server.on('exit', (code) => fail(new Error(`the server exited (${code})`)));
});
// --gpu: hardware WebGL (ANGLE on Vulkan by default; TVF_GPU_ARGS replaces the flags, e.g. ANGLE on EGL), as
// ../shared/tools/gpu-page/README.md ran the page on a GPU machine; else SwiftShader. Every result names the
// renderer the page got.
const GPU_ARGS = ['--use-angle=vulkan', '--enable-features=Vulkan,VulkanFromANGLE,DefaultANGLEVulkan', '--ignore-gpu-blocklist', '--enable-gpu', '--no-sandbox', '--disable-dev-shm-usage'];
const glArgs = process.argv.includes('--gpu')
  ? (process.env.TVF_GPU_ARGS ? process.env.TVF_GPU_ARGS.split(/\s+/).filter(Boolean) : GPU_ARGS)
  : ['--enable-unsafe-swiftshader', '--use-angle=swiftshader'];
const jsFlags = process.env.TVF_JS_FLAGS ? [`--js-flags=${process.env.TVF_JS_FLAGS}`] : [];
const browser = await chromium.launch({
  executablePath: process.env.TVF_CHROMIUM || '/usr/bin/chromium',
  args: [...glArgs, ...jsFlags, '--no-first-run', '--disable-background-networking', '--disable-component-update',
    '--disable-sync'],
});
try {
  const page = await browser.newPage({ viewport: { width: 1024, height: 720 } });
  if (strokeMesh !== null) {
    page.setDefaultTimeout(600_000);
    await strokeBench(page, strokeMesh);
  } else {
    await page.goto(`http://127.0.0.1:${port}/?bench=1&sizes=${sizes}`);
    const handle = await page.waitForFunction(() => window.tvfBench, null, { timeout: 600_000 });
    const result = await handle.jsonValue();
    if (result.error) throw new Error(result.error);
    for (const r of result.runs) {
      console.log(`${r.size}²: total ${r.totalMs} ms (${r.totalNoLevelSyncMs} ms without per-level waits); plain pass ${r.plainPassMs} ms; ratio ${r.ratioToPlainPass}`);
      console.log(`   levels: ${r.levels.map((l) => `${l.size}²(s${l.stackLevel}) ${l.ms}`).join(', ')}`);
  }
  console.log(`device: ${result.device}; exemplar ${result.exemplar}; analysis ${result.analysis.totalMs.toFixed(0)} ms`);
  mkdirSync(resolve(ROOT, 'bench-data'), { recursive: true });
  writeFileSync(resolve(ROOT, 'bench-data/synthesis-bench.json'), JSON.stringify({ date: new Date().toISOString(), ...result }, null, 1));
  }
} catch (err) {
  console.error(`bench:web: ${err.message.split('\n')[0]}`);
  process.exitCode = 1;
} finally {
  await browser.close();
  server.kill();
}

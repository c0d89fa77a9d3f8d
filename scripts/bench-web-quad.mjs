#!/usr/bin/env node
// The quad remesher in the real page (Debian's Chromium, never a downloaded browser; the app served from dist/ by
// scripts/serve.mjs): is the page responsive while a remesh runs, and does a big model's remesh finish with its
// progress shown? A measurement, not a test: big meshes live here, never in the browser tests.
//
//   node scripts/bench-web-quad.mjs [--mesh MESH [--quads N] [--repeat R]]... [--port P] [--no-gc]
//                                   [--feature-angle A]   (per mesh, as --quads: the design's sharp features, 0
//                                   none; default the page's new design: the model's suggestion, 35° on a
//                                   creased model, 0 on a curved one of facets)
//                                   [--profile FILE]   (a CPU profile of the page's main thread over the remeshes;
//                                   with several meshes, MESH-FILE beside FILE for each)
//
// Each --mesh starts a mesh of its own (default: bench-data/meshes/bunny00.off); a --quads, --repeat or
// --feature-angle after it is that mesh's, one before any --mesh every mesh's default (default 5000 quads, 3
// repeats), e.g.
//   node scripts/bench-web-quad.mjs --mesh bench-data/meshes/bunny00.off --quads 5000 --repeat 3 \
//                                   --mesh bench-data/meshes/armadillo-sub2.off --quads 20000 --repeat 1
// Per mesh, in a page of its own: the mesh loaded through tvf.loadModel (served under /bench-mesh-quad/ as a real
// download), tvf.setSymmetry(4), then tvf.settled() (a big model's exact field, not its preview); the page's
// garbage collected (the load's, as bench-web.mjs does before its strokes; --no-gc leaves it). Then R times:
// tvf.remesh({quads: N}), timed from the call to its promise resolving, while in the page
//   * a PerformanceObserver 'longtask' records the main thread's tasks over 50 ms (the browser's threshold),
//   * a setInterval every 100 ms reads tvf.quadMesh() ({running, stage, fraction}) and how late it fired (a
//     late tick is the main thread held: maxPollGapMs),
//   * a MutationObserver on the Quad mesh panel's stage line (#quad-stage) records every text it showed.
// Tasks count when they began between the call and two frames after its resolution (the quad mesh drawn).
// Prints one JSON object per mesh (an array for several): {mesh, faces, featureAngle, featureEdges, quads, repeat,
// remeshMs (median), longestTaskMs and tasksOver100ms (the maximum over the repeats), stages (polled, in the run's
// order), progressUpdates (distinct stage and fraction polled, median), stats (the last run's core stats)}, then
// the details (each run's time and long tasks, maxPollGapMs, the fractions polled, the panel's lines, the load's
// times). Medians, never a timed assertion. The stage lines progress through (the core's, core/quad/quad_remesh.cpp):
// starting (the page), cutting, parametrizing (again from cutting when the grid folded beside a feature curve
// and curves were let go), extracting, measuring, done.
import { copyFileSync, existsSync, mkdirSync, rmSync } from 'node:fs';
import { basename, dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { startProfile, withServedPage } from './page-session.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const SERVED = 'bench-mesh-quad'; // under dist/, removed at the end

function die(message) {
  console.error(`bench-web-quad: ${message}`);
  process.exit(1);
}

// --mesh groups with their --quads, --repeat and --feature-angle; one before any --mesh is the default.
function parseArgs(argv) {
  const defaults = { quads: 5000, repeat: 3 };
  const meshes = [];
  let port = Number(process.env.PORT || 8198);
  for (let i = 0; i < argv.length; i++) {
    const value = () => {
      if (i + 1 >= argv.length) die(`${argv[i]} needs a value`);
      return argv[++i];
    };
    const number = (name) => {
      const n = Number(value());
      if (!Number.isInteger(n) || n < 1) die(`${name} must be a positive whole number`);
      return n;
    };
    const into = () => meshes.at(-1) ?? defaults;
    switch (argv[i]) {
      case '--mesh': meshes.push({ path: value() }); break;
      case '--quads': into().quads = number('--quads'); break;
      case '--repeat': into().repeat = number('--repeat'); break;
      case '--feature-angle': {
        const a = Number(value());
        if (!(a >= 0 && a <= 180)) die('--feature-angle must be 0 to 180');
        into().featureAngle = a;
        break;
      }
      case '--port': port = number('--port'); break;
      case '--no-gc': break;
      case '--profile': value(); break;
      default: die(`unknown argument ${argv[i]}`);
    }
  }
  if (meshes.length === 0) meshes.push({ path: 'bench-data/meshes/bunny00.off' });
  return { port, meshes: meshes.map((m) => ({ ...defaults, ...m })) };
}

const { port, meshes } = parseArgs(process.argv.slice(2));
const collectGarbage = !process.argv.includes('--no-gc');
if (!existsSync(resolve(ROOT, 'dist/index.html'))) die('dist/ not found; run npm run build:wasm && npm run build:web');
for (const m of meshes) {
  if (!existsSync(resolve(m.path))) die(`mesh ${m.path} not found (meshes: scripts/fetch-meshes.sh)`);
}

// --profile FILE, with the mesh's name before FILE's own when there are several meshes.
function profileFile(meshName) {
  const i = process.argv.indexOf('--profile');
  if (i < 0) return null;
  const file = resolve(process.argv[i + 1]);
  return meshes.length === 1 ? file : resolve(dirname(file), `${meshName}-${basename(file)}`);
}

const median = (v) => {
  const s = v.filter(Number.isFinite).sort((a, b) => a - b);
  return s.length === 0 ? null : s.length % 2 ? s[(s.length - 1) / 2] : 0.5 * (s[s.length / 2 - 1] + s[s.length / 2]);
};
const round1 = (x) => (Number.isFinite(x) ? Math.round(10 * x) / 10 : x);
const STAT_KEYS = ['quads', 'faces', 'quadShare', 'irregularVertices', 'fieldSingularities', 'hausdorffRelative',
  'flippedFaces', 'degenerateFaces', 'eulerCharacteristic', 'ms'];

// One remesh in the page: its wall time, the main thread's long tasks, the state polled every 100 ms, the panel's
// stage line as shown.
function remeshInPage(quads) {
  return (async () => {
    const tvf = window.tvf;
    const frame = () => new Promise((r) => requestAnimationFrame(r));
    await frame();
    await frame();
    const stageLine = document.querySelector('tangent-field-designer')?.shadowRoot?.querySelector('#quad-stage');
    const shown = [];
    const observer = stageLine ? new MutationObserver(() => {
      const text = stageLine.textContent;
      if (text && text !== shown.at(-1)) shown.push(text);
    }) : null;
    observer?.observe(stageLine, { childList: true, characterData: true, subtree: true });
    const polls = [];
    let last = performance.now(), maxGap = 0;
    const poll = () => {
      const now = performance.now();
      maxGap = Math.max(maxGap, now - last);
      last = now;
      const s = tvf.quadMesh();
      if (s.running) polls.push({ at: now, stage: s.stage, fraction: s.fraction });
    };
    const timer = setInterval(poll, 100);
    window.__longTasks.length = 0;
    const t0 = performance.now();
    let result, error = null;
    try {
      result = await tvf.remesh({ quads });
    } catch (err) {
      error = String(err?.message ?? err);
    }
    const t1 = performance.now();
    clearInterval(timer);
    observer?.disconnect();
    // The quad mesh drawn, and long tasks reported (the observer is told after a task ends).
    await frame();
    await frame();
    await new Promise((r) => setTimeout(r, 50));
    const tasks = window.__longTasks.splice(0).filter((t) => t.at >= t0)
      .map((t) => ({ at: Math.round(t.at - t0), ms: t.ms }));
    return {
      wallMs: t1 - t0, error, tasks, maxPollGapMs: maxGap, shown,
      polls: polls.map((p) => ({ at: Math.round(p.at - t0), stage: p.stage, fraction: p.fraction })),
      stats: result?.stats ?? null, state: tvf.quadMesh(),
    };
  })();
}

async function benchMesh(browser, { path, quads, repeat, featureAngle = null }) {
  const name = basename(path);
  mkdirSync(resolve(ROOT, 'dist', SERVED), { recursive: true });
  copyFileSync(resolve(path), resolve(ROOT, 'dist', SERVED, name));
  const page = await browser.newPage({ viewport: { width: 1024, height: 720 } });
  page.setDefaultTimeout(900_000);
  page.on('console', (m) => m.type() === 'error' && console.error(`page: ${m.text()}`));
  try {
    // Long tasks of the page's main thread (> 50 ms), from the page's start on (bench-web.mjs's observer).
    await page.addInitScript(() => {
      window.__longTasks = [];
      new PerformanceObserver((list) => {
        window.__longTasks.push(...list.getEntries().map((e) => ({ at: e.startTime, ms: e.duration })));
      }).observe({ type: 'longtask', buffered: true });
    });
    await page.goto(`http://127.0.0.1:${port}/`);
    await page.evaluate(() => window.tvf.ready);
    const load = await page.evaluate(async ({ url, featureAngle }) => {
      window.__longTasks.length = 0;
      const t0 = performance.now();
      const info = await window.tvf.loadModel(url, { restore: false });
      const firstFieldMs = performance.now() - t0;
      const preview = window.tvf.stats().preview;
      if (featureAngle !== null) await window.tvf.setFeatures({ angle: featureAngle });
      await window.tvf.setSymmetry(4);
      await window.tvf.settled();
      const features = window.tvf.features();
      // The load's longest main-thread task: that the observer sees tasks at all (a big model's load has some).
      const longestTaskMs = window.__longTasks.filter((t) => t.at >= t0).reduce((m, t) => Math.max(m, t.ms), 0);
      return { faces: info.faces, firstFieldMs, exactFieldMs: performance.now() - t0, preview, longestTaskMs,
        exact: window.tvf.stats().preview === false, featureAngle: features.angle,
        featureEdges: features.edges.length / (Array.isArray(features.edges[0]) ? 1 : 2) };
    }, { url: `/${SERVED}/${name}`, featureAngle });
    if (!load.exact) throw new Error(`${name}: the field did not settle to the exact one`);
    if (collectGarbage) {
      const cdp = await page.context().newCDPSession(page);
      await cdp.send('HeapProfiler.collectGarbage');
      await cdp.detach();
    }
    const runs = [];
    // --profile FILE: a CPU profile of the page's main thread over the remeshes (.cpuprofile, for DevTools).
    const profile = await startProfile(page, profileFile(name));
    for (let r = 0; r < repeat; r++) {
      const run = await page.evaluate(remeshInPage, quads);
      if (run.error) throw new Error(`${name}: remesh ${r + 1} rejected: ${run.error}`);
      runs.push(run);
      const longest = Math.round(Math.max(0, ...run.tasks.map((t) => t.ms)));
      console.error(`bench-web-quad: ${name} remesh ${r + 1}/${repeat}: ${Math.round(run.wallMs)} ms, longest task ${longest} ms`);
    }
    await profile.stop();
    // The stages polled over every run, in the run's order (the fraction only grows: by the first fraction seen at
    // each; a poll may miss a short stage in one run and catch it in another), the fractions seen per stage.
    const fractions = {};
    for (const run of runs) {
      for (const p of run.polls) (fractions[p.stage] ??= new Set()).add(Math.round(1000 * p.fraction) / 1000);
    }
    const stages = Object.keys(fractions).sort((a, b) => Math.min(...fractions[a]) - Math.min(...fractions[b]));
    // The stage words the panel showed (every update, MutationObserver), in order, over the last run.
    const panelStages = [...new Set(runs.at(-1).shown.map((text) => text.replace(/\s*[\d.]+ %$/, '')))];
    const distinctUpdates = (run) => new Set(run.polls.map((p) => `${p.stage} ${p.fraction}`)).size;
    const lastStats = runs.at(-1).stats;
    return {
      mesh: name,
      faces: load.faces,
      // The design remeshed: the page's new design (features at 35°) unless --feature-angle set them.
      featureAngle: load.featureAngle,
      featureEdges: load.featureEdges,
      quads,
      repeat,
      remeshMs: round1(median(runs.map((r) => r.wallMs))),
      longestTaskMs: round1(Math.max(0, ...runs.flatMap((r) => r.tasks.map((t) => t.ms)))),
      tasksOver100ms: Math.max(...runs.map((r) => r.tasks.filter((t) => t.ms > 100).length)),
      stages,
      progressUpdates: median(runs.map(distinctUpdates)),
      stats: Object.fromEntries(STAT_KEYS.map((k) => [k, lastStats?.[k] ?? null])),
      // Beyond the summary: each run's wall time, the main thread's long tasks (over 50 ms; at: ms after the call),
      // the longest gap between the 100 ms polls, the fractions polled per stage, the panel's stage line as shown.
      remeshRunsMs: runs.map((r) => Math.round(r.wallMs)),
      coreMs: round1(median(runs.map((r) => r.stats?.ms))),
      longTasks: runs.map((r) => r.tasks.map((t) => ({ at: t.at, ms: round1(t.ms) }))),
      maxPollGapMs: round1(Math.max(...runs.map((r) => r.maxPollGapMs))),
      fractionsSeen: Object.fromEntries(Object.entries(fractions).map(([k, v]) => [k, [...v].sort((a, b) => a - b)])),
      panelStages,
      panelShown: runs.at(-1).shown,
      panelUpdates: median(runs.map((r) => r.shown.length)),
      load: {
        firstFieldMs: Math.round(load.firstFieldMs), exactFieldMs: Math.round(load.exactFieldMs), preview: load.preview,
        longestTaskMs: round1(load.longestTaskMs),
      },
      garbageCollectedFirst: collectGarbage,
    };
  } finally {
    await page.close();
  }
}

try {
  await withServedPage('bench-web-quad', port, async (browser) => {
    const results = [];
    for (const m of meshes) results.push(await benchMesh(browser, m));
    console.log(JSON.stringify(results.length === 1 ? results[0] : results, null, 1));
  });
} finally {
  rmSync(resolve(ROOT, 'dist', SERVED), { recursive: true, force: true });
}

// Singularity edits in the real page (Debian's Chromium, the wasm core in its worker), as the Singularity tool
// makes them: a model opened as a cross field (N from --symmetry), every index a closed surface needs prescribed
// (2N of +1/N, spread by vertex number), then one of them moved along its neighbours --moves times. Each edit's
// worker time (perf().lastOp.workerMs: the op, the solve, the read-outs) and its round trip to the page are
// printed as JSON with medians. A measurement, not a test: big meshes live here, never in the browser tests.
//   node scripts/bench-singularity-page.mjs [--mesh bench-data/meshes/bunny00.off] [--symmetry 4] [--moves 9]
import { readFileSync } from 'node:fs';
import { basename, dirname, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';
import { openDesigner } from '../tests/e2e/helpers.mjs';
import { withServedPage } from './page-session.mjs';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');
const arg = (name, fallback) => {
  const k = process.argv.indexOf(`--${name}`);
  return k > 0 ? process.argv[k + 1] : fallback;
};
const meshPath = resolve(ROOT, arg('mesh', 'bench-data/meshes/bunny00.off'));
const symmetry = Number(arg('symmetry', '4'));
const moves = Number(arg('moves', '9'));
const port = Number(arg('port', '8197'));

const median = (xs) => [...xs].sort((a, b) => a - b)[Math.floor(xs.length / 2)];

// Places the background set, then moves one singularity step by step to a neighbour not visited yet.
async function measure(page) {
  const bytes = readFileSync(meshPath).toString('base64');
  const name = basename(meshPath);
  await page.evaluate(async ([b64, n]) => {
    const data = Uint8Array.from(atob(b64), (c) => c.charCodeAt(0));
    await window.tvf.loadModel(data, { name: n, restore: false });
  }, [bytes, name]);
  await page.evaluate((n) => window.tvf.loadDesign({ boundary: 'free', gamma: 0, symmetry: n, constraints: [] }),
    symmetry);
  const info = await page.evaluate(() => window.tvf.info());
  const count = 2 * symmetry * Math.max(1, info.eulerCharacteristic ?? 2) / 2;
  const ids = await page.evaluate(async ([nV, n, k]) => {
    const out = [];
    for (let i = 0; i < k; i++) out.push(await window.tvf.addSingularity(Math.floor((i * nV) / k) + 11, 1 / n));
    return out;
  }, [info.vertices, symmetry, count]);
  const edges = await page.evaluate(() => Array.from(window.tvf.edges()));
  const worker = [], roundTrip = [];
  let at = 11;
  const visited = new Set([at]);
  for (let step = 0; step < moves; step++) {
    let next = -1;
    for (let k = 0; k < edges.length && next < 0; k += 2) {
      const other = edges[k] === at ? edges[k + 1] : edges[k + 1] === at ? edges[k] : -1;
      if (other >= 0 && !visited.has(other)) next = other;
    }
    if (next < 0) break;
    visited.add(next);
    const ms = await page.evaluate(async ([id, v]) => {
      const start = performance.now();
      await window.tvf.moveSingularity(id, v);
      return performance.now() - start;
    }, [ids[0], next]);
    const lastOp = await page.evaluate(() => window.tvf.perf().lastOp);
    worker.push(lastOp.workerMs);
    roundTrip.push(ms);
    at = next;
  }
  const summary = await page.evaluate(() => window.tvf.singularitySummary());
  return {
    mesh: name, faces: info.faces, symmetry, prescribed: ids.length, mode: summary.mode, moves: worker.length,
    singularityMoveWorkerMs: median(worker), singularityMoveRoundTripMs: median(roundTrip),
    workerMs: worker.map((t) => Math.round(t * 10) / 10),
  };
}

await withServedPage('bench-singularity-page', port, async (browser, baseURL) => {
  const page = await browser.newPage({ viewport: { width: 1024, height: 720 }, baseURL });
  page.setDefaultTimeout(600_000);
  await openDesigner(page);
  console.log(JSON.stringify(await measure(page), null, 1));
});

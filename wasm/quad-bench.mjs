// The quad remesher in wasm (core/quad/quad_remesh.h through wasm/quad_bindings.cpp), as the page's quad
// worker runs it: the smoothest cross field of a mesh remeshed to about N quads, `repeat` times, in one
// process. Medians of the whole call (quadMs, the arrays' copies in and out included) and of the core's own
// stages, and the last run's statistics; beside them the same from the native `tvf bench --quads` when given.
// Used by wasm/bench.mjs --quads N.
import { execFileSync } from 'node:child_process';
import { readFileSync } from 'node:fs';
import { pathToFileURL } from 'node:url';
import { median } from '../scripts/bench.mjs';

export async function measureQuadWasm(modulePath, mesh, quads, repeat) {
  const createTvfCore = (await import(pathToFileURL(modulePath).href)).default;
  const Module = await createTvfCore();
  const d = new Module.Designer();
  const fail = (what, e) => { if (e) throw new Error(`${what}: ${e}`); };
  fail('load', d.loadMesh(readFileSync(mesh), ''));
  fail('symmetry', d.setSymmetry(4));
  fail('solve', d.solve());
  const positions = Float64Array.from(d.positions()), triangles = Int32Array.from(d.triangles());
  const directions = Float64Array.from(d.faceVectors());
  // The design (and its factor) freed before the remeshing, as in the page, whose quad worker holds no design.
  d.delete();
  const options = JSON.stringify({ quads, symmetry: 4 });
  const total = [], stages = { cut: [], parametrize: [], extract: [], measure: [] };
  let stats, heapBytes = 0;
  for (let r = 0; r < repeat; ++r) {
    const t = performance.now();
    const out = Module.quadRemesh(positions, triangles, directions, options, null);
    total.push(performance.now() - t);
    if (out.error) throw new Error(`quadRemesh: ${out.error}`);
    heapBytes = Math.max(heapBytes, Module.HEAPU8.length);
    stats = JSON.parse(out.statsJson);
    for (const k of Object.keys(stages)) stages[k].push(stats.stageMs[k]);
  }
  return {
    module: modulePath, faces: triangles.length / 3, targetQuads: quads, repeat, quadMs: median(total),
    stageMs: Object.fromEntries(Object.entries(stages).map(([k, v]) => [k, median(v)])), heapBytes, stats,
  };
}

export function measureQuadNative(tvf, mesh, quads, repeat) {
  const out = execFileSync(tvf, ['bench', mesh, '--quads', String(quads), '--repeat', String(repeat)],
    { encoding: 'utf8', stdio: ['ignore', 'pipe', 'inherit'] });
  return JSON.parse(out);
}

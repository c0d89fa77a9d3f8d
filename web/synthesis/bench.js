// SPDX-License-Identifier: GPL-2.0-or-later
// Synthesis benchmark (page: ?bench=1, or `npm run bench:web`): a flat unit square with a constant field at 30°
// synthesized at 256², 512² and 1024² from a 64² exemplar; per level and total milliseconds (GPU waited for
// after each level), and the ratio of the total to one plain full-screen pass of the same size — the number that
// carries over between machines, since this machine may render in software (SwiftShader).

import { FloatTarget, drawFullscreen, sync } from './gl.js';
import { Synthesizer } from './synthesizer.js';
import { rendererName } from '../views/gl-renderer.js';

// A flat square grid like the synthesis tests' (tests/node/export-fixtures.mjs flatSquareGlb), straight as arrays
// (the bench needs no core).
function flatSquare(n = 16) {
  const positions = [], triangles = [], cornerUVs = [];
  for (let j = 0; j <= n; j++) for (let i = 0; i <= n; i++) positions.push(i / n, j / n, 0);
  const uv = (v) => [positions[3 * v], positions[3 * v + 1]];
  for (let j = 0; j < n; j++)
    for (let i = 0; i < n; i++) {
      const a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      for (const t of (i + j) % 2 === 0 ? [[a, b, d], [a, d, c]] : [[a, b, c], [b, d, c]]) {
        triangles.push(...t);
        for (const v of t) cornerUVs.push(...uv(v));
      }
    }
  return {
    positions: Float64Array.from(positions),
    triangles: Int32Array.from(triangles),
    cornerUVs: Float32Array.from(cornerUVs),
  };
}

// library: an ExemplarLibrary (exemplar.js). Returns {device, exemplar, runs: [{size, levels, totalMs, plainMs,
// ratio, ...}]}; `repeats` measured runs per size after one warm-up run (shader compilation), best one reported.
// Milliseconds of one plain full-screen pass (one fetch, one RGBA32F write per texel) at size^2 on the
// synthesizer's context, averaged over `repeats` after a warm-up: the unit synthesis times are compared with.
function plainPassMs(synth, size, repeats = 5) {
  const { gl, vao } = synth;
  const copy = synth.programs.copy;
  copy.check();
  const a = new FloatTarget(gl, size, size);
  const b = new FloatTarget(gl, size, size);
  const run = (n) => {
    let src = a;
    let dst = b;
    for (let i = 0; i < n; i++) {
      dst.bindAsTarget();
      copy.use().texture('uSource', src);
      drawFullscreen(gl, vao);
      [src, dst] = [dst, src];
    }
    sync(gl, src);
  };
  run(1);
  const t0 = performance.now();
  run(repeats);
  const ms = (performance.now() - t0) / repeats;
  a.dispose();
  b.dispose();
  gl.bindFramebuffer(gl.FRAMEBUFFER, null);
  return ms;
}

export async function runSynthesisBench(
  library,
  { sizes = [256, 512, 1024], exemplar = 'scales', repeats = 2, featureScale = 1 } = {},
) {
  const { tables } = await library.procedural(exemplar, 64, 1);
  const synth = new Synthesizer();
  const gl = synth.gl;
  const device = rendererName(gl);
  synth.setExemplar(tables);
  const sq = flatSquare(16);
  const t = Math.PI / 6;
  const vv = new Float64Array(sq.positions.length);
  for (let v = 0; v < vv.length; v += 3) {
    vv[v] = Math.cos(t);
    vv[v + 1] = Math.sin(t);
  }
  const runs = [];
  try {
    for (const size of sizes) {
      synth.setAtlas({ resolution: size, ...sq });
      // Every run whole (localDegrees 0): the same field again would otherwise be a local run with nothing to do.
      const whole = { featureScale, localDegrees: 0 };
      synth.synthesize(vv, whole); // warm-up: compiles the shaders for this size
      let best = null;
      for (let r = 0; r < repeats; r++) {
        const s = synth.synthesize(vv, { ...whole, timing: 'levels' });
        if (!best || s.totalMs < best.totalMs) best = s;
      }
      const total = synth.synthesize(vv, { ...whole, timing: 'total' });
      const plainMs = plainPassMs(synth, size, 10);
      runs.push({
        size,
        levels: best.levels.map((l) => ({ size: l.size, stackLevel: l.stackLevel, ms: +l.ms.toFixed(2) })),
        totalMs: +best.totalMs.toFixed(1),
        totalNoLevelSyncMs: +total.totalMs.toFixed(1),
        jacobianMs: +best.jacobianMs.toFixed(1),
        plainPassMs: +plainMs.toFixed(3),
        ratioToPlainPass: +(best.totalMs / plainMs).toFixed(0),
      });
    }
  } finally {
    synth.dispose();
  }
  return { device, exemplar: `${exemplar} 64²`, passes: 2, subpasses: 4, analysis: tables.stats.timings, runs };
}

// The bench as a text table.
export function formatBench(result) {
  const analysisMs = result.analysis.totalMs.toFixed(0);
  const head = `texture synthesis bench on ${result.device}; exemplar ${result.exemplar}`;
  const lines = [`${head}, analysis ${analysisMs} ms (wasm)`];
  for (const r of result.runs) {
    const levels = r.levels.map((l) => `${l.size}²:${l.ms}`).join(' ');
    lines.push(
      `${r.size}²: total ${r.totalMs} ms (${r.totalNoLevelSyncMs} ms without per-level waits), ` +
        `plain pass ${r.plainPassMs} ms, ratio ${r.ratioToPlainPass}; levels ${levels}`,
    );
  }
  return lines.join('\n');
}


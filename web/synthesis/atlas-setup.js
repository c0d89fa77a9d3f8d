// SPDX-License-Identifier: GPL-2.0-or-later
// The atlas a synthesis run works in, set up for the current model (controller.js): chosen or generated in the
// core's worker (which keeps it per mesh, worker-ops.js), its targets and per-face data set up on the synthesizer's GPU
// context, the textured model's geometry built for it. Each step is a phase of the run's clock
// (phase-clock.js). Owns nothing: the controller keeps the atlas and the textured model.
import { DEFAULTS } from './synthesizer.js';
import { TexturedModel } from './render.js';

// The atlas's {resolution, gutter} under the controller's options, as asked of the core's worker (the same for a
// run and for the atlas prepared ahead, atlas-ahead.js, so that the run finds it kept): an 'auto' resolution is
// chosen there, from the model (atlas-prepared.js resolvedAtlasOptions), and comes back as the atlas's.
export function atlasOptions(options) {
  return { resolution: options.resolution, gutter: options.gutter ?? DEFAULTS.gutter };
}

// c: the SynthesisController. Resolves with the atlas (c.atlas, reused while the model, resolution and gutter
// stay the same).
export async function setUpAtlas(c, model, clock) {
  const { resolution: asked, gutter } = atlasOptions(c.options);
  const held = c.atlas;
  if (held && held.key === model.key && held.asked === asked && held.gutter === gutter) return held;
  // Generating an atlas takes up to seconds on a big model: the element's core worker does it, so the page
  // keeps drawing and taking input; the synthesis programs compile meanwhile (Synthesizer.programsReady, asked
  // once the request is out: its first look at them may wait for the GPU process).
  const sentAt = performance.timeOrigin + performance.now();
  const request = c.computeAtlas(model, { resolution: asked, gutter });
  const programs = c.ensureSynth().programsReady();
  programs.catch(() => {}); // a failure is thrown by the await below
  const chosen = await request;
  const receivedAt = performance.timeOrigin + performance.now();
  if (chosen.cache) {
    // Before the worker took the request (other work of its own first), and after it replied.
    chosen.cache.waitedMs = chosen.cache.startedAt - sentAt;
    chosen.cache.replyMs = receivedAt - chosen.cache.finishedAt;
  }
  const kept = chosen.cache?.cached;
  clock.mark(kept ? 'atlas (worker: kept for this mesh)' : 'atlas (worker: charts, packing, corners, seams)');
  await programs;
  clock.mark('shader compilation (waited for)');
  // The raster takes the corners and seams; the atlas kept here is the one the exports and stats read.
  const { corners = null, seams = null, ...atlas } = chosen;
  const { resolution } = atlas;
  const { positions, triangles, neighbour } = model.surface;
  const { cornerUVs } = atlas;
  const spec = { resolution, positions, triangles, neighbour, cornerUVs, corners, seams, gutter };
  if (c.options.interleave) await c.ensureSynth().drained(clock, "waits for the GPU (the view's frames)");
  let task = performance.now(); // a new task once the steps took the page a while (none for a blocking synthesis)
  for (const _ of c.ensureSynth().setAtlasSteps(spec))
    if (c.options.interleave && performance.now() - task > 16) {
      await new Promise((resolve) => setTimeout(resolve, 0));
      task = performance.now();
    }
  clock.mark('atlas corner data to the GPU');
  c.atlas = { key: model.key, asked, gutter, ...atlas };
  if (!c.render) c.render = new TexturedModel(c.viewer);
  // Before the synthesis, not beside it: the model's program is compiled here, and without
  // KHR_parallel_shader_compile that waits for the GPU process, which in the view's context would first finish
  // the synthesis's queued slices (a 0.43 s task when it ran beside them).
  await c.render.setGeometry(model.surface, c.atlas.cornerUVs);
  clock.mark('textured geometry (built, staged)');
  return c.atlas;
}

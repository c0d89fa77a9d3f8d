// SPDX-License-Identifier: GPL-2.0-or-later
// A model's texture atlas prepared in the core's worker as soon as the model is shown, before any texture is
// asked for, so that the first texture skips the charts, packing and seams (bunny00 on a real GPU: 1.47 s of a
// 1.87 s first texture). A request per step (worker-ops.js prepareTextureAtlas): edits sent meanwhile go
// between the steps, behind at most one of them (the core's atlas choice, the longest). The atlas stays in the
// worker's memory only, until a texture uses it; the synthesis programs are compiled next (a first texture on
// bunny00 with the atlas kept waited 0.2 s for them on SwiftShader). Models over AHEAD_FACES faces are left
// alone: their atlas takes seconds that the exact field's first edits would wait behind. Owned by the designer
// (its 'load').
import { atlasOptions } from './atlas-setup.js';

export const AHEAD_FACES = 150_000;

// request(op, args): the session's request to the core's worker; controller: the SynthesisController (its
// options say the resolution and gutter a run will ask for); model: {positions, triangles, cornerUVs}.
// Resolves with the last step's {done, cached}, or false for a model left alone.
export async function prepareAtlasAhead(request, controller, { positions, triangles, cornerUVs }) {
  if (triangles.length / 3 > AHEAD_FACES) return false;
  const options = atlasOptions(controller.options);
  let r = await request('prepareTextureAtlas', [positions, triangles, cornerUVs ?? null, options]);
  while (!r.done) r = await request('prepareTextureAtlas', []);
  return r;
}

// The synthesizer's programs compiled ahead in the view's context (controller: the SynthesisController), then,
// once a fence says the GPU process has linked them (Synthesizer.programsReady: without
// KHR_parallel_shader_compile, as on SwiftShader, a look at a link status before that waits for the link, which
// held the page 124-154 ms in some big models' openings), drawn once each (pipeline-warm-up.js). Never fails
// anything: with the context lost meanwhile (ensureSynth refuses it: no float targets to find then), the next
// texture makes them.
export function prepareProgramsAhead(controller) {
  if (!controller.viewer?.renderer) return;
  try {
    controller.ensureSynth().warmUpPipelines().catch(() => {}); // a context lost meanwhile: nothing to warm
  } catch {
    // the context lost: its restore starts over
  }
}

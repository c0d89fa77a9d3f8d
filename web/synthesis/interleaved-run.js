// SPDX-License-Identifier: GPL-2.0-or-later
// One interleaved synthesis run (Synthesizer.synthesizeInterleaved): the synthesizer's steps (the field's slices,
// then the pyramid's draws) issued a slice at a time, with the page's thread free between slices. The GPU is
// drained before the run and between the field's slices (each a big upload that would otherwise wait for a
// busy GPU process on the page's thread), and the pyramid's draws are paced by slice-pacer.js. Every wait is a
// phase of the run's clock (phase-clock.js). Owns nothing.
import { FIELD_UPLOAD_PHASE, PhaseClock } from './phase-clock.js';
import { nextTask as nextTaskDefault } from './slice-pacer.js';

// pacer: the synthesizer's SlicePacer; makeSteps(): the steps' generator (made once the GPU is drained). Options:
// onProgress(f) gets the share done (0..1); cancelled() turning true stops the run, which resolves to null;
// clock: the run's PhaseClock; nextTask: how to wait a little (tests may pass their own).
export async function interleavedRun(
  pacer,
  makeSteps,
  { onProgress = () => {}, cancelled = () => false, clock = new PhaseClock(), nextTask = nextTaskDefault } = {},
) {
  pacer.start();
  await pacer.drain(clock, nextTask, cancelled, "waits for the GPU (the view's frames)");
  if (cancelled()) return null;
  const steps = makeSteps();
  let pending = 0, kernel = false;
  for (let r = steps.next(); ; r = steps.next()) {
    if (r.done) return { ...r.value, gpuMs: pacer.finish(clock), slices: pacer.slices, sliceTexels: pacer.texels };
    onProgress(r.value.progress);
    if (r.value.field) {
      // The field goes to the GPU a slice of faces per task, each once the GPU has taken the one before, and
      // is then rasterized into the atlas (its own phase, r.value.phase).
      await pacer.drain(clock, nextTask, cancelled, r.value.phase ?? FIELD_UPLOAD_PHASE);
      if (cancelled()) return null;
      continue;
    }
    if (!kernel) {
      kernel = true;
      clock.mark(FIELD_UPLOAD_PHASE);
      pacer.begin();
    }
    pending += r.value.texels;
    if (pending < pacer.texels && !r.value.gpuIdle) continue;
    pending = 0;
    await pacer.end(clock, nextTask, cancelled, { last: !!r.value.gpuIdle });
    if (cancelled()) {
      pacer.start();
      return null;
    }
    if (!r.value.gpuIdle) pacer.begin();
  }
}

// SPDX-License-Identifier: GPL-2.0-or-later
// The texture's CPU half warmed up in the core's worker while it has nothing else to do (after a model is first
// shown): an atlas prepared for a small generated torus, dropped (the default exemplar's analysis is asked for
// by the Texture panel's thumbnail, and kept). V8 first
// runs wasm and JavaScript on its baseline tier, and a call that is running stays on it: under node on this
// machine, the core's atlas choice for bunny00 took 665 ms cold, 436 ms after this warm-up (265-271 ms itself)
// and 380-383 ms hot. Owned by worker-ops.js (its warmUpTexture op).
import { torus } from '../core/preview/warm-up.js';
import { preparedAtlas } from './atlas-prepared.js';

// Returns the milliseconds spent.
export function warmUpTexture(Module) {
  const t0 = performance.now();
  const { positions, triangles } = torus(48, 24);
  preparedAtlas(Module, { positions, triangles, cornerUVs: null }, { resolution: 256, gutter: 2 });
  return performance.now() - t0;
}

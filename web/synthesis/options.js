// SPDX-License-Identifier: GPL-2.0-or-later
// The options synthesize() takes (controller.js), checked before anything runs: the synthesizer's own (their
// defaults are synthesizer.js's DEFAULTS) and the controller's. Owns nothing; imports nothing.

export const MAX_RESOLUTION = 2048;
// The synthesizer's options, handed on to each run.
export const OPTION_KEYS = [
  'featureScale',
  'magnitudeExponent',
  'jitter',
  'finestJitter',
  'passes',
  'kappa',
  'seed',
  'gutter',
  'seams',
  'timing',
  'sliceFaces',
  'localDegrees',
];
// The controller's: the atlas side, resynthesis on field changes, yielding to the page between draws.
export const CONTROLLER_KEYS = ['resolution', 'autoUpdate', 'interleave'];

// Throws on the first option that is unknown or out of range.
export function checkSynthesisOptions(options) {
  if (options.resolution !== undefined && options.resolution !== 'auto') {
    const r = options.resolution;
    if (!Number.isInteger(r) || r < 16 || r > MAX_RESOLUTION || r & (r - 1))
      throw new Error(`resolution must be 'auto' or a power of two in [16, ${MAX_RESOLUTION}] (got ${r})`);
  }
  for (const k of Object.keys(options)) {
    if (!CONTROLLER_KEYS.includes(k) && !OPTION_KEYS.includes(k)) throw new Error(`unknown synthesis option '${k}'`);
  }
  if (options.featureScale !== undefined && options.featureScale !== 'auto' && !(options.featureScale > 0))
    throw new Error("featureScale must be 'auto' or > 0");
  const degrees = options.localDegrees;
  if (degrees !== undefined && !(typeof degrees === 'number' && degrees >= 0 && degrees <= 180))
    throw new Error(`localDegrees must be a number of degrees in [0, 180] (got ${options.localDegrees})`);
  if (options.sliceFaces !== undefined && !(Number.isInteger(options.sliceFaces) && options.sliceFaces > 0))
    throw new Error(`sliceFaces must be a positive integer (got ${options.sliceFaces})`);
}

// SPDX-License-Identifier: GPL-2.0-or-later
// Which pyramid levels a synthesis runs and what each reads (LH05 Sec. 3): synthesis level k (2^k finest
// texels per texel) reads Gaussian-stack level round(log2(sigma_k)), sigma_k = 2^k / featureScale exemplar
// pixels per texel; the coarsest level run is the first whose stack level reaches the top of the stack (nearly
// a constant colour), or the 2x2 atlas. Pure arithmetic, apart from the GPU work, so it can be reasoned about
// (and changed) on its own.

// o: the synthesis options (featureScale, jitter, finestJitter); levelCount: atlas levels (finest first);
// stackTop: the exemplar's top stack level; finestLevel: 0, or 1 for a preview. Coarsest first:
// [{k, stackLevel, spacing, jitter}].
export function levelPlan(o, levelCount, stackTop, finestLevel) {
  const sigma0 = 1 / o.featureScale;
  let coarsest = 0;
  while (coarsest + 1 < levelCount) {
    coarsest++;
    if (Math.round(Math.log2(sigma0 * 2 ** coarsest)) >= stackTop - 1) break;
  }
  coarsest = Math.max(coarsest, finestLevel);
  const plan = [];
  for (let k = coarsest, i = 0; k >= finestLevel; k--, i++) {
    const s = Math.min(stackTop, Math.max(0, Math.round(Math.log2(sigma0 * 2 ** k))));
    plan.push({ k, stackLevel: s, spacing: 2 ** s, jitter: jitterOf(o, i, k) });
  }
  return plan;
}

// The finest level adds its own jitter (finestJitter); the others take theirs from `jitter`, a number or one
// value per level run, coarsest first.
function jitterOf(o, i, k) {
  if (k === 0) return o.finestJitter;
  return Array.isArray(o.jitter) ? (o.jitter[i] ?? o.jitter[o.jitter.length - 1]) : o.jitter;
}

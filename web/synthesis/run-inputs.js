// SPDX-License-Identifier: GPL-2.0-or-later
// What one synthesis run (controller.js) hands the synthesizer, made from the model, its atlas and the
// controller's options: the synthesizer's options, an 'auto' feature scale chosen from the model and the exemplar
// (auto-settings.js), and the field it follows: a vector field's 1-form, whose Whitney field the raster makes
// per corner (geometry/whitney-corners.js), or a line or cross field combed per corner for the atlas
// (geometry/chart-comb.js). Owns nothing.
import { atlasCombedCornersSteps } from '../geometry/chart-comb.js';
import { defaultFeatureScale, shapeMeasures } from './auto-settings.js';
import { OPTION_KEYS } from './options.js';

// The synthesizer's options for one run. preview: stop one level short of the finest (quick edits). The
// model's shape complexity and folds, once computed, stay with its atlas (atlas.complexity, atlas.foldDegrees;
// an atlas kept by an earlier version may lack the folds).
export function runOptions(options, model, atlas, exemplarSize, preview) {
  const synthOptions = {};
  for (const k of OPTION_KEYS) if (options[k] !== undefined) synthOptions[k] = options[k];
  const coverage = atlas.stats.coverage ?? atlas.stats.check?.coverage ?? 0.5;
  if (synthOptions.featureScale === 'auto') {
    if (atlas.complexity == null || atlas.foldDegrees == null)
      ({ complexity: atlas.complexity, foldDegrees: atlas.foldDegrees } = shapeMeasures(model.surface));
    const { complexity, foldDegrees } = atlas;
    synthOptions.featureScale = defaultFeatureScale(atlas.resolution, coverage, exemplarSize, complexity, foldDegrees);
  }
  if (preview) synthOptions.finestLevel = 1;
  return synthOptions;
}

// What the synthesizer follows: a vector field's Whitney reconstruction from model.oneForm (paper Eq. 4: linear
// over each face, exact at every texel; made per slice of faces by the raster), or a preview's
// model.vertexVectors as they are; a line or cross field's
// model.vertexVectors combed per corner for the atlas (geometry/chart-comb.js), its cuts along the chart seams
// where it can (model.faceVectors, the field's own face representatives, when the model hands them in).
// A step at a time (stepped() runs it): the comb of a line or cross field yields between slices of faces
// (bunny00's 75k faces took the page 160-210 ms in one task).
export function* fieldInputSteps(model, atlas) {
  const symmetry = model.symmetry ?? 1;
  if (symmetry === 1) {
    // A big model's preview, known by its vertex vectors alone: those, linear over each face.
    if (!model.oneForm) return { symmetry, input: model.vertexVectors };
    const S = model.surface;
    return { symmetry, input: { whitney: { positions: S.positions, rows: S.edgeRows, oneForm: model.oneForm } } };
  }
  const t0 = performance.now();
  const faceVectors = model.faceVectors ?? null;
  const { surface, vertexVectors } = model;
  const comb = yield* atlasCombedCornersSteps(surface, vertexVectors, faceVectors, symmetry, atlas.cornerUVs);
  return { symmetry, input: { cornerVectors: comb.corners }, ms: performance.now() - t0, cutEdges: comb.flips.length };
}

// Runs `steps` (a generator) to its end, giving the page's thread back (a task) whenever they have held it for
// 8 ms, if `interleave`. Resolves with its value, or null once cancelled() turns true.
export async function stepped(steps, interleave, cancelled) {
  let t = performance.now();
  for (;;) {
    const r = steps.next();
    if (r.done) return r.value;
    if (!interleave || performance.now() - t < 8) continue;
    await new Promise((resolve) => setTimeout(resolve, 0));
    if (cancelled()) return null;
    t = performance.now();
  }
}

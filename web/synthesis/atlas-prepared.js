// SPDX-License-Identifier: GPL-2.0-or-later
// The atlas with what drawing into it needs, made in the core's worker (worker-ops.js textureAtlas): the atlas
// itself (atlas.js), the per-face data of its raster (atlas-corners.js) and its gutter (atlas-gutter.js), its
// seam indirection (seams.js) and the shape complexity the default feature size follows (auto-settings.js). At
// 832k faces these took the page's thread 1.7 s in the task that set the atlas up, and 0.17 s in the next.
import { Surface } from '../geometry/surface.js';
import { chooseAtlas } from './atlas.js';
import { cornerData } from './atlas-corners.js';
import { gutterQuads } from './atlas-gutter.js';
import { defaultResolution, shapeMeasures } from './auto-settings.js';
import { seamIndirection } from './seams.js';

export function preparedAtlas(Module, input, options) {
  return finishSteps(preparedAtlasSteps(Module, input, options));
}

// The model's atlas options with an 'auto' resolution chosen (auto-settings.js defaultResolution, from the face
// count, the shape complexity and the facets' folds, which need the model's Surface: all made here, in the worker,
// once per request, and handed on to preparedAtlasSteps). Returns {options, shape: {surface, complexity,
// foldDegrees} | null}.
export function resolvedAtlasOptions({ positions, triangles }, options) {
  if (options.resolution !== 'auto') return { options, shape: null };
  const surface = new Surface(positions, triangles, null);
  const { complexity, foldDegrees } = shapeMeasures(surface);
  const resolution = defaultResolution(triangles.length / 3, complexity, foldDegrees);
  return { options: { ...options, resolution }, shape: { surface, complexity, foldDegrees } };
}

// The rest of a generator's steps, at once; its value.
export function finishSteps(steps) {
  for (;;) {
    const r = steps.next();
    if (r.done) return r.value;
  }
}

// The same, a step at a time (a generator returning the atlas): the worker prepares a model's atlas ahead
// between other requests (worker-ops.js prepareTextureAtlas). workerSteps: each step's own time. options: with a
// numeric resolution; shape: resolvedAtlasOptions()'s, or null to make them here.
export function* preparedAtlasSteps(Module, { positions, triangles, cornerUVs }, options, shape = null) {
  let t = performance.now();
  const took = () => -t + (t = performance.now());
  const atlas = chooseAtlas(Module, { positions, triangles, cornerUVs }, options);
  atlas.workerSteps = { chooseMs: took() };
  yield;
  t = performance.now();
  atlas.corners = cornerData(positions, triangles, atlas.cornerUVs);
  atlas.workerSteps.cornersMs = took();
  const surface = shape?.surface ?? new Surface(positions, triangles, null);
  ({ complexity: atlas.complexity, foldDegrees: atlas.foldDegrees } = shape ?? shapeMeasures(surface));
  atlas.resolution = options.resolution;
  atlas.workerSteps.complexityMs = took();
  yield;
  t = performance.now();
  atlas.seams = seamIndirection(
    { positions, triangles, neighbour: surface.neighbour },
    atlas.cornerUVs,
    options.resolution,
  );
  atlas.workerSteps.seamsMs = atlas.seams.ms = took();
  const { cornerUVs: uv, corners, resolution } = atlas;
  const quads = { triangles, cornerUVs: uv, corners, resolution, gutter: options.gutter ?? 2 };
  atlas.corners.gutter = gutterQuads({ ...quads, neighbour: surface.neighbour });
  atlas.workerSteps.gutterMs = took();
  return atlas;
}

// The arrays a prepared atlas hands over (transferred, not copied).
export function preparedBuffers(atlas) {
  const out = [
    atlas.cornerUVs.buffer,
    atlas.corners.uv.buffer,
    atlas.corners.frames.buffer,
    atlas.corners.faceArea.buffer,
    atlas.corners.gutter.uv.buffer,
    atlas.corners.gutter.source.buffer,
    atlas.corners.gutter.indices.buffer,
    atlas.seams.map.buffer,
  ];
  if (atlas.faceCharts) out.push(atlas.faceCharts.buffer);
  return out;
}

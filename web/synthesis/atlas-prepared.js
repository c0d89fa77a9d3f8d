// SPDX-License-Identifier: GPL-2.0-or-later
// The atlas with what drawing into it needs, made in the core's worker (worker-ops.js textureAtlas): the atlas
// itself (atlas.js), the per-corner data of its raster (atlas-corners.js), its seam indirection (seams.js) and
// the shape complexity the default feature size follows (auto-settings.js). At 832k faces these took the
// page's thread 1.7 s in the task that set the atlas up, and 0.17 s in the next.
import { Surface } from '../geometry/surface.js';
import { chooseAtlas } from './atlas.js';
import { cornerData } from './atlas-corners.js';
import { shapeComplexity } from './auto-settings.js';
import { seamIndirection } from './seams.js';

export function preparedAtlas(Module, { positions, triangles, cornerUVs }, options) {
  const t0 = performance.now();
  const atlas = chooseAtlas(Module, { positions, triangles, cornerUVs }, options);
  const t1 = performance.now();
  atlas.corners = cornerData(positions, triangles, atlas.cornerUVs);
  const t2 = performance.now();
  const surface = new Surface(positions, triangles, null);
  atlas.complexity = shapeComplexity(surface);
  const t3 = performance.now();
  atlas.seams = seamIndirection(
    { positions, triangles, neighbour: surface.neighbour },
    atlas.cornerUVs,
    options.resolution,
  );
  const t4 = performance.now();
  atlas.seams.ms = t4 - t3;
  atlas.workerSteps = { chooseMs: t1 - t0, cornersMs: t2 - t1, complexityMs: t3 - t2, seamsMs: t4 - t3 };
  return atlas;
}

// The arrays a prepared atlas hands over (transferred, not copied).
export function preparedBuffers(atlas) {
  const out = [
    atlas.cornerUVs.buffer,
    atlas.corners.data.buffer,
    atlas.corners.faceArea.buffer,
    atlas.seams.map.buffer,
  ];
  if (atlas.faceCharts) out.push(atlas.faceCharts.buffer);
  return out;
}

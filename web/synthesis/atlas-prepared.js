// SPDX-License-Identifier: GPL-2.0-or-later
// The atlas with what drawing into it needs, made in the core's worker (core-worker.js textureAtlas): the atlas
// itself (atlas.js), the per-corner data of its raster (atlas-corners.js) and its seam indirection (seams.js).
// At 832k faces the last two took the page's thread 1.7 s in the task that set the atlas up.
import { chooseAtlas } from './atlas.js';
import { cornerData } from './atlas-corners.js';
import { seamIndirection } from './seams.js';

export function preparedAtlas(Module, { positions, triangles, cornerUVs }, options) {
  const atlas = chooseAtlas(Module, { positions, triangles, cornerUVs }, options);
  atlas.corners = cornerData(positions, triangles, atlas.cornerUVs);
  const t0 = performance.now();
  atlas.seams = seamIndirection({ positions, triangles }, atlas.cornerUVs, options.resolution);
  atlas.seams.ms = performance.now() - t0;
  return atlas;
}

// The arrays a prepared atlas hands over (transferred, not copied).
export function preparedBuffers(atlas) {
  const out = [atlas.cornerUVs.buffer, atlas.corners.data.buffer, atlas.corners.faceArea.buffer, atlas.seams.map.buffer];
  if (atlas.faceCharts) out.push(atlas.faceCharts.buffer);
  return out;
}

// SPDX-License-Identifier: GPL-2.0-or-later
// The synthesis settings chosen for the user ('auto'): the atlas resolution from the face count and the model's
// curvature and facets, and the feature scale from them, the atlas's texel density and the exemplar's size. Pure
// functions of the model, kept apart from the controller so the tests can check them against analytic shapes
// (docs/texture-synthesis.md, "How the resolution and the feature size are chosen").

// Default feature size. Stripes read as following the field only where the field (and the surface it lies on)
// turns little over a stripe period; on a curved model the field turns with the surface, so the exemplar tile
// is sized from the model's curvature: tiles across sqrt(area) = TILES_PER_COMPLEXITY x the shape complexity
// (sqrt(area) x the area-mean |mean curvature|: 3.5 for a sphere, ~14 for the bunny, ~18 for homer, ~34 for a thin
// knotted tube), between MIN_TILES and MAX_TILES. Measured on exported GLBs (docs/texture-synthesis.md): on
// homer 6 tiles left 9.6° mean deviation, 12 tiles 5.8°, with the same synthesis. 0.66 (refined_elephant, c ≈ 19:
// 12.7 tiles) left the genus-3 elephant at 6.43° / 83 %; 0.84 (16 tiles) measured 5.19° / 90 %. A 2048² atlas at
// 12.7 tiles did not help (6.59° / 82 %): the feature size, not texels per face, was the limit.
const TILES_PER_COMPLEXITY = 0.84;
const MIN_TILES = 6;
const MAX_TILES = 16;
// A tile spans at least this many atlas texels: the procedural exemplars repeat their feature four times a tile
// (the stripes' period is a quarter of the exemplar), and a period drawn with fewer than 10 texels is not
// resolved. At 64² that is 0.625 texels per exemplar pixel; a larger exemplar may take fewer per pixel, a smaller
// one needs more, and the tile count gives way first.
const MIN_TILE_TEXELS = 40;
// The resolution is chosen before the atlas exists: its charts are taken to cover this share of it (generated
// atlases cover 0.50-0.69).
const TYPICAL_COVERAGE = 0.55;
// The share of the curvature's tiles the texel floor may take away before the atlas doubles its resolution:
// the bunny keeps 10.3 of its 11.6 tiles at 512² (4.89° / 90.5 %); a 5,500-face genus-3 elephant kept 9.9 of 16
// there (11.0° / 64 %), and a 6,000-face camel 9.7 (8.7° / 71 %).
const TILES_KEPT = 0.8;

// A coarse model's facets turn the field at every edge by up to the fold between its faces, and a stripe period
// that spans such turns cannot follow them (issue 45's low-poly models; docs/texture-synthesis.md). Where the
// shape complexity times the length-weighted mean fold between faces (degrees) exceeds FOLD_REFERENCE, the
// curvature's tiles are multiplied by (that product / FOLD_REFERENCE)^FOLD_EXPONENT, up to MAX_FOLDED_TILES
// (what a 2048² atlas holds at MIN_TILE_TEXELS). Measured products: the default bunny 153, homer 150, lion-head-7000
// 146 (all within the targets as they were), refined_elephant-5500 256 (16 tiles 7.70° / 75 %, 32 tiles 5.63° /
// 85.0 %, 40 tiles 5.27° / 87.2 %), camel-6000 331 (16: 6.61° / 82 %, 24: 5.51° / 87 %, 32: 4.97° / 90 %);
// finely meshed models 60-130 (bunny00 61, refined_elephant 65, diplodocus 126), but camel 189 and knot2 515.
const FOLD_REFERENCE = 160;
const FOLD_EXPONENT = 2;
const MAX_FOLDED_TILES = 40;

// The tiles across sqrt(area) the model's shape complexity asks for, more where its facets fold sharply
// (foldDegrees: shapeMeasures()'s).
export function defaultTiles(complexity = MIN_TILES / TILES_PER_COMPLEXITY, foldDegrees = 0) {
  const curvature = Math.min(MAX_TILES, Math.max(MIN_TILES, TILES_PER_COMPLEXITY * complexity));
  const folds = Math.max(1, (complexity * foldDegrees) / FOLD_REFERENCE) ** FOLD_EXPONENT;
  return Math.min(MAX_FOLDED_TILES, curvature * folds);
}

// The atlas resolution a model gets by default, between 256² and 1024² (2048² where a coarse model's folds ask
// for more tiles than 1024² holds): enough texels per face for the Jacobian to vary smoothly (≈ 16 texels per
// face at ~60 % coverage), and, given the shape complexity, for a tile to span MIN_TILE_TEXELS at TILES_KEPT of
// the tiles the curvature asks for (a coarse but curved model would otherwise get the face count's resolution
// and too few texels per stripe).
export function defaultResolution(numFaces, complexity = null, foldDegrees = 0) {
  const forFaces = Math.sqrt((numFaces * 16) / 0.6);
  const tiles = complexity == null ? 0 : defaultTiles(complexity, foldDegrees);
  const forTiles = (TILES_KEPT * tiles * MIN_TILE_TEXELS) / Math.sqrt(TYPICAL_COVERAGE);
  const limit = tiles > MAX_TILES ? 2048 : 1024;
  let r = 256;
  while (r < Math.max(forFaces, forTiles) && r < limit) r *= 2;
  return r;
}

// sqrt(area) x the area-mean |mean curvature|, from dihedral angles: sum over interior edges of |theta_e| l_e,
// over 2 x area (1 / radius on a sphere, so a sphere scores sqrt(4 pi) = 3.5). Scale-free. surface: the model's
// Surface (geometry/surface.js: positions, triangles, face normals and areas, the half-edge map `neighbour`);
// degenerate faces take no part.
export function shapeComplexity(surface) {
  return shapeMeasures(surface).complexity;
}

// {complexity: shapeComplexity()'s, foldDegrees: the mean dihedral angle between neighbouring faces, in degrees,
// weighted by the edges' lengths: how coarsely the facets approximate the shape}.
export function shapeMeasures({ positions, triangles, normals, areas, neighbour }) {
  const nF = triangles.length / 3;
  let area = 0, bend = 0, length = 0;
  for (let f = 0; f < nF; f++) area += areas[f];
  for (let h = 0; h < 3 * nF; h++) {
    const other = neighbour[h];
    if (other < h) continue; // a boundary, or the edge seen from its other side
    const f = Math.floor(h / 3), g = Math.floor(other / 3);
    if (!(areas[f] > 0 && areas[g] > 0)) continue;
    const i = 3 * triangles[h], j = 3 * triangles[3 * f + ((h + 1) % 3)];
    const d =
      normals[3 * f] * normals[3 * g] +
      normals[3 * f + 1] * normals[3 * g + 1] +
      normals[3 * f + 2] * normals[3 * g + 2];
    const len = Math.hypot(
      positions[i] - positions[j],
      positions[i + 1] - positions[j + 1],
      positions[i + 2] - positions[j + 2],
    );
    bend += Math.acos(Math.min(1, Math.max(-1, d))) * len;
    length += len;
  }
  return {
    complexity: area > 0 ? (bend / (2 * area)) * Math.sqrt(area) : 0,
    foldDegrees: length > 0 ? ((bend / length) * 180) / Math.PI : 0,
  };
}

// The feature scale (atlas texels per exemplar pixel at the atlas's mean density) that makes one exemplar tile
// span sqrt(area) / tiles on the surface, tiles from the shape complexity (above): tile length
// m * featureScale * texelLength, with texelLength = sqrt(area / coverage) / R; a tile at least MIN_TILE_TEXELS.
export function defaultFeatureScale(resolution, coverage, exemplarSize, complexity, foldDegrees = 0) {
  const tiles = defaultTiles(complexity, foldDegrees);
  const fs = (resolution * Math.sqrt(Math.max(coverage, 0.05))) / (tiles * exemplarSize);
  return Math.min(8, Math.max(MIN_TILE_TEXELS / exemplarSize, fs));
}

// Line and cross fields combed for texture synthesis (web/geometry/chart-comb.js) against independent truth:
// a constant field scrambled by random 2πk/N rotations per face and per vertex comes back as one direction at
// every corner; a field with a +1/2 singularity (θ = arg(z) / 2 around the centre of a flat grid) can only be
// combed with a cut from the singularity to the boundary, and that cut follows an atlas seam placed across the
// grid instead of wandering; the face directions from the vertex representatives recover the field.
import assert from 'node:assert/strict';
import test from 'node:test';
import { grid, scrambledField, surfaceOf } from './fakes.mjs';
import { randomSequence } from '../../web/geometry/arrow-sampling.js';
import { atlasCombedCorners, combForAtlas, faceDirections } from '../../web/geometry/chart-comb.js';



// UVs of a flat grid in [0, 1]² as two charts split at x = 0.5 (the right half moved up by 0.01: a seam).
function twoChartUVs(s) {
  const U = new Float64Array(6 * s.nF);
  for (let f = 0; f < s.nF; f++) {
    const right = s.centroid(f)[0] > 0.5;
    for (let k = 0; k < 3; k++) {
      const p = s.vertex(s.triangles[3 * f + k]);
      U.set([p[0], p[1] + (right ? 0.01 : 0)], 6 * f + 2 * k);
    }
  }
  return U;
}

test('chart comb: a scrambled constant line/cross field comes back as one direction at every corner', () => {
  const s = surfaceOf(grid(10, 1));
  for (const N of [2, 4]) {
    for (const useFaces of [true, false]) {
      const { V, F } = scrambledField(s, N, () => 0.7, randomSequence(3 + N));
      const { corners, flips } = atlasCombedCorners(s, V, useFaces ? F : null, N, twoChartUVs(s));
      assert.equal(flips.length, 0, 'no cut in a field without singularities');
      const first = corners.subarray(0, 3);
      for (let c = 0; c < corners.length; c += 3) {
        const d = corners[c] * first[0] + corners[c + 1] * first[1] + corners[c + 2] * first[2];
        assert.ok(d > 1 - 1e-9, `N=${N} faces=${useFaces}: corner ${c / 3} turned away (${d})`);
      }
    }
  }
});

test('chart comb: face directions from the vertex representatives recover a smooth line field', () => {
  const s = surfaceOf(grid(10, 1));
  const theta = (x, y) => 0.5 * x + 0.3 * y;
  const { V } = scrambledField(s, 2, theta, randomSequence(5));
  const D = faceDirections(s, V, 2);
  for (let f = 0; f < s.nF; f++) {
    const [x, y] = s.centroid(f);
    const a = theta(x, y);
    const cos = Math.abs(D[3 * f] * Math.cos(a) + D[3 * f + 1] * Math.sin(a));
    assert.ok(cos > Math.cos(0.05), `face ${f}: ${cos}`);
  }
});

test('chart comb: the cut a +1/2 singularity forces runs to the boundary, along the seam when there is one', () => {
  const s = surfaceOf(grid(20, 2, -1));
  // θ = arg(z)/2 about (0.05, 0.03): a +1/2 singularity inside a face near the centre.
  const theta = (x, y) => Math.atan2(y - 0.03, x - 0.05) / 2;
  const { V, F } = scrambledField(s, 2, theta, randomSequence(11));
  // Without an atlas: one cut, a chain of edges from the singularity to the boundary (every flip edge's faces
  // lie on one ray from the singularity, give or take a face).
  const free = combForAtlas(s, F, 2);
  assert.ok(free.flips.length >= 9 && free.flips.length <= 40, `cut of ${free.flips.length} edges`);
  // With a seam along the ray x = 0.05 + t, y ≈ 0 (the two charts: y above / below 0 for x > 0): the cut
  // follows it.
  const U = new Float64Array(6 * s.nF);
  for (let f = 0; f < s.nF; f++) {
    const [cx, cy] = s.centroid(f);
    const lower = cx > 0.1 && cy < 0;
    for (let k = 0; k < 3; k++) {
      const p = s.vertex(s.triangles[3 * f + k]);
      U.set([(p[0] + 1) / 2, (p[1] + 1) / 2 + (lower ? -0.01 : 0)], 6 * f + 2 * k);
    }
  }
  const seamed = combForAtlas(s, F, 2, U);
  let onSeam = 0;
  for (const [f, g] of seamed.flips) {
    const a = s.centroid(f), b = s.centroid(g);
    const mid = [(a[0] + b[0]) / 2, (a[1] + b[1]) / 2];
    if (Math.abs(mid[1]) < 0.1 && mid[0] > 0) onSeam++;
  }
  assert.ok(seamed.flips.length > 0 && onSeam >= seamed.flips.length - 2, `${onSeam} of ${seamed.flips.length} cut edges on the seam`);
});

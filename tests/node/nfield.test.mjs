// N-symmetric fields (web/geometry/nfield.js and what the views build on it) against independent truth:
// representatives scrambled by known random rotations of 2πk/N are recovered; combing undoes the scrambling
// of a constant field exactly; indices of fields with a known winding (θ = k · arg z) come out as k, a
// multiple of 1/N; the glyph has N spokes 2π/N apart; labels are the reduced fractions.
import assert from 'node:assert/strict';
import test from 'node:test';
import { grid, scrambledField, surfaceOf } from './fakes.mjs';
import { randomSequence } from '../../web/geometry/arrow-sampling.js';
import {
  closestRotation,
  closestRotation2d,
  familyCosine,
  lineFamilies,
  matchedCorners,
  rotateAbout,
  spokeAngles,
  symmetryOf,
} from '../../web/geometry/nfield.js';
import { findSingularities } from '../../web/geometry/singularities.js';
import { atlasCombedCorners, combForAtlas } from '../../web/geometry/chart-comb.js';
import { arrowGeometry, glyphGeometry, spokeTriangles } from '../../web/views/markers.js';
import { indexLabel, singularityFill } from '../../web/views/singularity-style.js';
import { linePasses } from '../../web/views/lic-lines.js';

const TWO_PI = 2 * Math.PI;
const near = (a, b, tol, what) => a.forEach((x, k) => assert.ok(Math.abs(x - b[k]) < tol, `${what}: ${a} vs ${b}`));
const rot2 = ([x, y], a) => [Math.cos(a) * x - Math.sin(a) * y, Math.sin(a) * x + Math.cos(a) * y];
const unit = (v) => v.map((x) => x / Math.hypot(...v));


test('nfield: the symmetry is an integer 1..6, anything else a vector field; families and spokes per N', () => {
  assert.deepEqual([1, 2, 4, 6, 0, 7, 2.5, undefined, '4', null].map(symmetryOf), [1, 2, 4, 6, 1, 1, 1, 1, 1, 1]);
  assert.deepEqual([1, 2, 3, 4, 5, 6].map((N) => lineFamilies(N).count), [1, 1, 3, 2, 5, 3]);
  assert.deepEqual([2, 3, 4, 5, 6].map((N) => lineFamilies(N).bothWays), [true, false, true, false, true]);
  assert.deepEqual(lineFamilies(4).angles, [0, Math.PI / 2]);
  assert.equal(familyCosine(2), -1, 'one family: every line counts');
  assert.ok(Math.abs(familyCosine(4) - Math.SQRT1_2) < 1e-15);
  for (let N = 1; N <= 6; N++) spokeAngles(N).forEach((a, k) => assert.ok(Math.abs(a - (TWO_PI * k) / N) < 1e-15));
});

test('nfield: a representative turned by a random 2πk/N (plus a wobble under π/N) is matched back', () => {
  const random = randomSequence(7);
  for (let N = 1; N <= 6; N++) {
    for (let trial = 0; trial < 200; trial++) {
      const v = rot2([1, 0], TWO_PI * random());
      const k = Math.floor(random() * N), wobble = (random() - 0.5) * (0.9 * Math.PI) / N;
      const ref = rot2(v, (TWO_PI * k) / N + wobble);
      near(closestRotation2d(v, ref, N), rot2(v, (TWO_PI * k) / N), 1e-12, `2D N=${N}`);
      // The same in 3D, about a random normal, with v and ref in its tangent plane.
      const n = unit([random() - 0.5, random() - 0.5, random() - 0.5]);
      const t = unit([n[1], -n[0], 0].map((x, c) => x + 0.1 * c * n[2]));
      const t3 = t.map((x, c) => x - (t[0] * n[0] + t[1] * n[1] + t[2] * n[2]) * n[c]);
      const v3 = rotateAbout(unit(t3), n, TWO_PI * random());
      const ref3 = rotateAbout(v3, n, (TWO_PI * k) / N + wobble);
      near(closestRotation(v3, ref3, n, N), rotateAbout(v3, n, (TWO_PI * k) / N), 1e-12, `3D N=${N}`);
    }
  }
});

test('nfield: matched corners of a scrambled constant field all equal their face\'s representative', () => {
  const s = surfaceOf(grid(8, 1));
  for (const N of [2, 3, 4, 6]) {
    const { V, F } = scrambledField(s, N, () => 0.4, randomSequence(N));
    const C = matchedCorners(s, V, F, N);
    for (let f = 0; f < s.nF; f++)
      for (let k = 0; k < 3; k++) near(C.subarray(9 * f + 3 * k, 9 * f + 3 * k + 3), F.subarray(3 * f, 3 * f + 3), 1e-12, `N=${N} face ${f}`);
  }
});

test('nfield: combing a scrambled constant field makes every face and corner one representative', () => {
  const s = surfaceOf(grid(8, 1));
  for (const N of [2, 4, 5]) {
    const { V, F } = scrambledField(s, N, () => -1.1, randomSequence(10 + N));
    const { faces: combed, corners: C } = atlasCombedCorners(s, V, F, N), first = combed.slice(0, 3);
    for (let f = 0; f < s.nF; f++) near(combed.subarray(3 * f, 3 * f + 3), first, 1e-12, `N=${N} face ${f}`);
    for (let c = 0; c < C.length / 3; c++) near(C.subarray(3 * c, 3 * c + 3), first, 1e-12, `N=${N} corner ${c}`);
    // Without face representatives the corners comb from each face's corner 0, to the same result up to the
    // one rotation left free.
    const loose = atlasCombedCorners(s, V, null, N).corners, a = Math.atan2(loose[1], loose[0]);
    for (let c = 0; c < loose.length / 3; c++) assert.ok(Math.abs(Math.atan2(loose[3 * c + 1], loose[3 * c]) - a) < 1e-9 || Math.abs(Math.abs(Math.atan2(loose[3 * c + 1], loose[3 * c]) - a) - TWO_PI) < 1e-9);
  }
});

test('nfield: a line field around a +1/2 singularity combs consistently except across one cut', () => {
  const n = 12, s = surfaceOf(grid(n, 2, -1));
  const { F } = scrambledField(s, 2, (x, y) => 0.5 * Math.atan2(y - 0.01, x - 0.013), randomSequence(3));
  const combed = combForAtlas(s, F, 2).faces;
  let cut = 0;
  for (let h = 0; h < s.neighbour.length; h++) {
    const g = (s.neighbour[h] / 3) | 0, f = (h / 3) | 0;
    if (s.neighbour[h] < 0 || g < f) continue;
    if (combed[3 * f] * combed[3 * g] + combed[3 * f + 1] * combed[3 * g + 1] < 0) cut++;
  }
  assert.ok(cut > 0, 'a half-integer singularity cannot be combed everywhere');
  assert.ok(cut <= 2 * n, `the cut is a path from the singularity to the boundary, not ${cut} edges`);
});

// θ = k · arg(z − c) has index k at c: for an N-field, k a multiple of 1/N. The cases keep |k| < 4/N: the 8
// faces around the centre turn by 2πk/8 each, and a turn of π/N between faces is ambiguous on any mesh.
test('singularities of N-fields: θ = k·arg z gives index k (a multiple of 1/N) at its centre, none elsewhere', () => {
  const s = surfaceOf(grid(12, 2, -1));
  let centre = -1, best = Infinity;
  for (let v = 0; v < s.nV; v++) {
    const [x, y] = s.vertex(v);
    if (s.facesAround(v).length === 8 && Math.hypot(x, y) < best) (best = Math.hypot(x, y)), (centre = v);
  }
  const [cx, cy] = s.vertex(centre);
  for (const [N, k] of [[2, 0.5], [2, -0.5], [4, 0.25], [4, -0.25], [4, 0.75], [3, -1 / 3], [6, 1 / 6], [4, 0.5], [2, -1]]) {
    const { F } = scrambledField(s, N, (x, y) => k * Math.atan2(y - cy, x - cx), randomSequence(Math.round(100 * k) + N));
    const found = findSingularities(s, F, N);
    assert.equal(found.length, 1, `N=${N}, k=${k}: ${JSON.stringify(found)}`);
    assert.equal(found[0].vertex, centre);
    assert.ok(Math.abs(found[0].index - k) < 1e-12, `N=${N}: index ${found[0].index}, expected ${k}`);
  }
  // Read as a vector field, the scrambled representatives would give nonsense; symmetry 1 is the old reading.
  const { F } = scrambledField(s, 1, (x, y) => Math.atan2(y - cy, x - cx), randomSequence(5));
  assert.deepEqual(findSingularities(s, F, 1), findSingularities(s, F));
});

test('glyphs: N = 1 is the arrow; N ≥ 2 is N spokes of length 1/2 from the centre, 2π/N apart', () => {
  assert.deepEqual(glyphGeometry(1).getAttribute('position').array, arrowGeometry().getAttribute('position').array);
  for (let N = 2; N <= 6; N++) {
    const P = spokeTriangles(N, { length: 0.5, halfWidth: 0.05 });
    assert.deepEqual(glyphGeometry(N).getAttribute('position').array, P);
    assert.equal(P.length, N * 18, 'two triangles per spoke');
    for (let k = 0; k < N; k++) {
      const pts = Array.from({ length: 6 }, (_, i) => [P[18 * k + 3 * i], P[18 * k + 3 * i + 1]]);
      const a = (TWO_PI * k) / N, dir = [Math.cos(a), Math.sin(a)];
      // Along the spoke: from 0 to 1/2; across it: ±the half-width.
      const along = pts.map(([x, y]) => x * dir[0] + y * dir[1]), across = pts.map(([x, y]) => -x * dir[1] + y * dir[0]);
      assert.ok(Math.abs(Math.min(...along)) < 1e-7 && Math.abs(Math.max(...along) - 0.5) < 1e-7, `spoke ${k} of ${N}`);
      assert.ok(across.every((c) => Math.abs(Math.abs(c) - 0.05) < 1e-7), `spoke ${k} of ${N} width`);
    }
    // A line field's glyph is a segment through the centre with no head: symmetric under x → −x.
    if (N === 2) {
      const xs = [];
      for (let i = 0; i < P.length; i += 3) xs.push(P[i]);
      assert.ok(Math.abs(Math.min(...xs) + 0.5) < 1e-7 && Math.abs(Math.max(...xs) - 0.5) < 1e-7);
    }
  }
});

test('singularity labels: integers as before, fractions in lowest terms; colours ramp by sign and size', () => {
  assert.deepEqual([1, -1, 2, -3].map((i) => indexLabel(i)), ['+1', '\u22121', '+2', '\u22123']);
  assert.deepEqual([0.5, -0.5, 0.25, -0.25, 0.75, 1, -1, 1.5].map((i) => indexLabel(i, 4)), ['+1/2', '\u22121/2', '+1/4', '\u22121/4', '+3/4', '+1', '\u22121', '+3/2']);
  assert.deepEqual([1 / 3, -2 / 3, 0.5, 1 / 6, 5 / 6].map((i) => indexLabel(i, 6)), ['+1/3', '\u22122/3', '+1/2', '+1/6', '+5/6']);
  // Whole indices keep the vector field's colours.
  assert.deepEqual([1, 2, -1, -2].map(singularityFill), ['#facc15', '#facc15', '#c084fc', '#c084fc']);
  const fills = [0.25, 0.5, 0.75, 1, -0.25, -0.5, -0.75, -1].map(singularityFill);
  assert.equal(new Set(fills).size, fills.length, `distinct: ${fills}`);
  // The ramp moves monotonically from pale to the full colour with |index|: blue falls for yellow, green for violet.
  const ch = (hex, i) => parseInt(hex.slice(1 + 2 * i, 3 + 2 * i), 16);
  const pos = [1 / 6, 0.25, 1 / 3, 0.5, 0.75, 1].map(singularityFill), neg = [-1 / 6, -0.25, -1 / 3, -0.5, -0.75, -1].map(singularityFill);
  for (let i = 1; i < pos.length; i++) {
    assert.ok(ch(pos[i], 2) < ch(pos[i - 1], 2), `${pos}`);
    assert.ok(ch(neg[i], 1) < ch(neg[i - 1], 1), `${neg}`);
  }
});

test('LIC of N-fields: one pass per family, blended into the running mean of the passes', () => {
  assert.deepEqual(linePasses(2, 3.5).map((p) => [p.angle, p.passAlpha, p.minCos, p.contrast]), [[0, 1, 0, 3.5]]);
  const cross = linePasses(4, 3.5);
  assert.deepEqual(cross.map((p) => p.angle), [0, Math.PI / 2]);
  assert.ok(cross.every((p) => Math.abs(p.minCos - Math.SQRT1_2) < 1e-15));
  // Alpha blending with 1/(k+1) over what is there leaves the mean of the passes drawn.
  const values = [0.2, 0.9, 0.4, 0.7, 0.1];
  let shown = 0;
  linePasses(5, 1).forEach((p, k) => (shown = p.passAlpha * values[k] + (1 - p.passAlpha) * shown));
  assert.ok(Math.abs(shown - values.reduce((a, b) => a + b) / 5) < 1e-15);
});

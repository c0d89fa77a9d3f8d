// The magnitude colour map (web/views/colormap.js) against the published viridis table (matplotlib's
// _viridis_data, van der Walt & Smith) and a sort-based 98th percentile.
import assert from 'node:assert/strict';
import test from 'node:test';
import { Color, SRGBColorSpace } from 'three';
import { VIRIDIS, viridis } from '../../web/views/colormap.js';
import { magnitudeScale } from '../../web/geometry/magnitudes.js';

// matplotlib's viridis at t = 0, 0.25, 0.5, 0.75, 1 (table entries 0, 64, 128, 192, 255), sRGB in [0, 1].
const PUBLISHED = [
  [0, [0.267004, 0.004874, 0.329415]],
  [0.25, [0.229739, 0.322361, 0.545706]],
  [0.5, [0.127568, 0.566949, 0.550556]],
  [0.75, [0.369214, 0.788888, 0.382914]],
  [1, [0.993248, 0.906157, 0.143936]],
];

const srgb = (t) => {
  const c = viridis(t, new Color()).getRGB({ r: 0, g: 0, b: 0 }, SRGBColorSpace);
  return [c.r, c.g, c.b];
};

test('viridis matches the published table at its ends and quarters (within 8-bit rounding)', () => {
  for (const [t, rgb] of PUBLISHED) {
    const got = srgb(t);
    for (let k = 0; k < 3; k++) assert.ok(Math.abs(got[k] - rgb[k]) <= 0.6 / 255, `t = ${t}, channel ${k}: ${got[k]} vs ${rgb[k]}`);
  }
  assert.equal(viridis(0, new Color()).getHexString(), '440154');
  assert.equal(viridis(1, new Color()).getHexString(), 'fde725');
});

test('viridis: lightness rises monotonically along the ramp', () => {
  // Relative luminance (linear RGB, Rec. 709 weights); three.js colours hold linear components.
  const luminance = (t) => {
    const c = viridis(t, new Color());
    return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
  };
  let previous = -Infinity;
  for (let i = 0; i <= 1000; i++) {
    const y = luminance(i / 1000);
    assert.ok(y > previous, `luminance falls at t = ${i / 1000}`);
    previous = y;
  }
});

test('viridis clamps t to [0, 1] and reads NaN as 0', () => {
  const hex = (t) => viridis(t, new Color()).getHex();
  assert.equal(hex(-3), hex(0));
  assert.equal(hex(7), hex(1));
  assert.equal(hex(NaN), hex(0));
  assert.equal(hex(Infinity), hex(0));
  assert.equal(VIRIDIS[0], 0x440154, 'the legend starts where the ramp does');
  assert.equal(VIRIDIS.at(-1), 0xfde725);
});

// Deterministic random numbers (the tests must not vary between runs).
function lcg(seed) {
  let s = seed >>> 0;
  return () => ((s = (Math.imul(s, 1664525) + 1013904223) >>> 0) / 2 ** 32);
}

function percentileBySort(mags, p) {
  const sorted = [...mags].sort((a, b) => a - b);
  return sorted[Math.min(sorted.length - 1, Math.floor(p * sorted.length))];
}

test('magnitudeScale: max is the largest length, top the 98th percentile of the lengths', () => {
  const random = lcg(7);
  for (const m of [1, 2, 49, 50, 51, 100, 1000, 4097]) {
    const v = new Float64Array(3 * m);
    const mags = [];
    for (let i = 0; i < m; i++) {
      // Heavy-tailed lengths, as sources and vortices make them.
      const len = random() < 0.05 ? 1e3 * random() : random();
      const a = 2 * Math.PI * random(), z = 2 * random() - 1, r = Math.sqrt(1 - z * z);
      v.set([len * r * Math.cos(a), len * r * Math.sin(a), len * z], 3 * i);
      mags.push(Math.hypot(v[3 * i], v[3 * i + 1], v[3 * i + 2]));
    }
    const { max, top } = magnitudeScale(v);
    const largest = Math.max(...mags);
    assert.ok(Math.abs(max - largest) <= 1e-12 * largest, `m = ${m}: max ${max}, largest length ${largest}`);
    const expected = percentileBySort(mags, 0.98);
    assert.ok(Math.abs(top - expected) <= 1e-12 * expected, `m = ${m}: top ${top}, sorted 98th percentile ${expected}`);
    assert.ok(top <= max);
  }
});

test('magnitudeScale: a zero 98th percentile falls back to the max; no vectors give zeros', () => {
  const v = new Float64Array(3 * 100);
  v[0] = 3;
  v[1] = 4;
  assert.deepEqual(magnitudeScale(v), { max: 5, top: 5 });
  assert.deepEqual(magnitudeScale(new Float64Array(0)), { max: 0, top: 0 });
  assert.deepEqual(magnitudeScale(new Float64Array(30)), { max: 0, top: 0 });
});

test('magnitudeScale: non-finite lengths count as 0; huge finite ones are measured without overflow', () => {
  const v = Float64Array.from([NaN, 0, 0, Infinity, 0, 0, 1e200, 1e200, 0, 1, 0, 0]);
  const { max } = magnitudeScale(v);
  assert.ok(Math.abs(max / (Math.SQRT2 * 1e200) - 1) < 1e-12, `max ${max}`);
  const only = magnitudeScale(Float64Array.from([NaN, 1, 1, 0, 0, Infinity]));
  assert.deepEqual(only, { max: 0, top: 0 });
});

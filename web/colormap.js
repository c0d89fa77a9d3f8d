// Perceptual colour map for magnitudes: viridis (van der Walt & Smith, matplotlib), as nine stops of the
// published table with linear interpolation between them. Lightness rises monotonically, so it reads the same
// in greyscale and for the common colour-vision deficiencies, unlike a rainbow ramp.
import { Color } from 'three';

// The stops at t = 0, 1/8, …, 1. element.css draws the legend with the same stops.
export const VIRIDIS = [0x440154, 0x472d7b, 0x3b528b, 0x2c728e, 0x21918c, 0x28ae80, 0x5ec962, 0xaddc30, 0xfde725];

const STOPS = VIRIDIS.map((c) => new Color(c));

// t in [0, 1] (clamped; NaN reads as 0) → out, a three.js Color.
export function viridis(t, out) {
  const clamped = Number.isFinite(t) ? Math.min(Math.max(t, 0), 1) : 0;
  const s = clamped * (STOPS.length - 1);
  const i = Math.min(Math.floor(s), STOPS.length - 2);
  return out.copy(STOPS[i]).lerp(STOPS[i + 1], s - i);
}

// The magnitude scale the arrows, the surface colours and the legend share, for vectors 3 per item: the
// largest magnitude and the 98th percentile, where the ramp tops out (sources and vortices make a few huge
// values that would otherwise leave everything else at the bottom). Non-finite magnitudes count as 0.
export function magnitudeScale(vectors) {
  const m = vectors.length / 3;
  const mags = new Float64Array(m);
  for (let i = 0; i < m; i++) {
    const v = Math.hypot(vectors[3 * i], vectors[3 * i + 1], vectors[3 * i + 2]);
    mags[i] = Number.isFinite(v) ? v : 0;
  }
  mags.sort();
  const max = m ? mags[m - 1] : 0;
  const top = (m ? mags[Math.min(m - 1, Math.floor(0.98 * m))] : 0) || max;
  return { max, top };
}

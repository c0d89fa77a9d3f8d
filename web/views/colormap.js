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

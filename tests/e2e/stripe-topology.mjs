// The topology of a stripe or grid picture read back from the page (tests/e2e/stripes.spec.mjs): how the stripes'
// own direction turns round a point, from the pixels alone. Per sample point on a circle, the grey's gradients
// within a window give the direction of the stripes there as the argument of sum |g|^2 e^(i m phi) (phi the
// gradient's angle; m = 2: stripes, a direction mod pi; m = 4: a grid's two families, mod pi/2); unwrapped round
// the circle (windows that see almost no gradient skipped), its total turn in whole turns is the index of the picture's own direction field there times m:
// +1/2 of a line field's stripes (one stripe ends there) and +1/4 of a grid (three of its lines meet) both give 1,
// a point where the stripes only run on, 0. Works on a grey image (width × height, row 0 at the top); imports
// nothing.

// The total turn (in turns, not rounded) of the stripes' direction round the circle (cx, cy, r), with m as above.
export function directionTurns({ width, height, grey }, cx, cy, r, window, m) {
  const samples = Math.max(64, Math.ceil((2 * Math.PI * r) / 3));
  const args = [], strength = [];
  for (let k = 0; k < samples; k++) {
    const a = (2 * Math.PI * k) / samples;
    const px = cx + r * Math.cos(a), py = cy + r * Math.sin(a);
    let re = 0, im = 0;
    for (let y = Math.floor(py - window); y <= Math.ceil(py + window); y++)
      for (let x = Math.floor(px - window); x <= Math.ceil(px + window); x++) {
        if (x < 1 || y < 1 || x >= width - 1 || y >= height - 1) continue;
        if ((x - px) ** 2 + (y - py) ** 2 > window * window) continue;
        const gx = (grey[y * width + x + 1] - grey[y * width + x - 1]) / 2;
        const gy = (grey[(y + 1) * width + x] - grey[(y - 1) * width + x]) / 2;
        const w = gx * gx + gy * gy, phi = Math.atan2(gy, gx);
        re += w * Math.cos(m * phi);
        im += w * Math.sin(m * phi);
      }
    args.push(Math.atan2(im, re));
    strength.push(Math.hypot(re, im));
  }
  // Windows that see almost no gradient (inside a grid's cell) say nothing of the direction: skipped.
  const floor = 0.1 * [...strength].sort((a, b) => a - b)[Math.floor(samples / 2)];
  const kept = args.filter((_, k) => strength[k] > floor);
  let total = 0;
  for (let k = 0; k < kept.length; k++) {
    let d = kept[(k + 1) % kept.length] - kept[k];
    d -= 2 * Math.PI * Math.round(d / (2 * Math.PI));
    total += d;
  }
  return total / (2 * Math.PI);
}

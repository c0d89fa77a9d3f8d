// A WebGL context's drawing buffer as RGBA8, row 0 at the top (readPixels gives the bottom row first): what both
// renderer scenes hand back to tests/e2e/anisotropy-renderers.spec.mjs.
export function topDownPixels(gl, width, height) {
  const pixels = new Uint8Array(4 * width * height);
  gl.readPixels(0, 0, width, height, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
  const rows = new Uint8Array(pixels.length);
  for (let y = 0; y < height; y++)
    rows.set(pixels.subarray(4 * width * (height - 1 - y), 4 * width * (height - y)), 4 * width * y);
  return rows;
}

// SPDX-License-Identifier: GPL-2.0-or-later
// The synthesized texture as an image file: the output size an export asks for, and RGBA8 to PNG. Rows are
// written as read back (row 0 = atlas v 0) so the PNG's top row is v = 0, as glTF samples TEXCOORD_0 and as the
// core writes its flow maps: the image pairs with the atlas UVs unchanged, in the GLB and outside it.
import { canvasElement } from '../dom.js';

// Output pixels per atlas texel for an export: {resolution} (output size, a power of two in [16, 8192]) or
// {magnification} (1..8; `fallback` when neither is given). atlasResolution: texels per side of the result.
export function exportMagnification({ magnification, resolution } = {}, atlasResolution, fallback) {
  if (resolution !== undefined) {
    if (!Number.isInteger(resolution) || resolution < 16 || resolution > 8192 || resolution & (resolution - 1))
      throw new Error(`export resolution must be a power of two in [16, 8192] (got ${resolution})`);
    return resolution / atlasResolution;
  }
  const m = magnification ?? fallback;
  if (!(m >= 1 && m <= 8)) throw new Error(`magnification must be in [1, 8] (got ${m})`);
  return m;
}

// RGBA8 pixels (row 0 first) to a PNG Blob.
export async function pngBlob(pixels, width, height) {
  const image = new ImageData(
    new Uint8ClampedArray(pixels.buffer, pixels.byteOffset, pixels.byteLength),
    width,
    height,
  );
  if (typeof OffscreenCanvas !== 'undefined') {
    const c = new OffscreenCanvas(width, height);
    c.getContext('2d').putImageData(image, 0, 0);
    return c.convertToBlob({ type: 'image/png' });
  }
  const c = canvasElement(width, height);
  c.getContext('2d').putImageData(image, 0, 0);
  return new Promise((resolve) => c.toBlob(resolve, 'image/png'));
}

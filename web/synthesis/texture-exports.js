// SPDX-License-Identifier: GPL-2.0-or-later
// The synthesized texture read out of a SynthesisController (controller.js) for files and tests: a PNG as the
// page renders it, the texture a GLB export embeds, the raw result. Every read runs in the controller's queue
// (controller.exclusive), after the synthesis queued before it, so it never sees a half-made texture. Owns
// nothing; imports texture-image.js.
import { exportMagnification, pngBlob } from './texture-image.js';

function requireResult(c) {
  if (!c.stats || !c.synth?.result) throw new Error('nothing synthesized yet: call synthesize() first');
}

// The exemplar's colours at the synthesized coordinates, magnified as the page's renderer does, as a PNG Blob.
function image(c, magnification) {
  const { width, height, pixels } = c.synth.readColour({ magnification, nearest: false });
  return pngBlob(pixels, width, height);
}

// The synthesized texture as a PNG Blob, rendered as the page renders it (magnification: the four nearest
// texels' patches blended) at {resolution} pixels per side or {magnification} pixels per atlas texel; the top
// row is atlas v = 0 (texture-image.js).
export function texturePng(c, options = {}) {
  return c.exclusive(async () => {
    requireResult(c);
    return image(c, exportMagnification(options, c.stats.resolution, 1));
  });
}

// The texture a GLB export embeds (export/index.js): {png (Uint8Array), cornerUVs (the atlas, 6 per face of
// the model)} at {resolution} or {magnification} (default 2 pixels per atlas texel), or null when none is
// shown. required: the last texture even when switched off, and an error when there is none. Waits for the
// synthesis in flight, so the file has the texture of the field it carries.
export async function glbTexture(c, { resolution, magnification, required = false } = {}) {
  if (c.active) await c.whenIdle();
  return c.exclusive(async () => {
    if (!required && !c.active) return null;
    if (!c.stats || !c.synth?.result) {
      if (required) throw new Error('no synthesized texture to export: call synthesize() first');
      return null;
    }
    const blob = await image(c, exportMagnification({ resolution, magnification }, c.stats.resolution, 2));
    return { png: new Uint8Array(await blob.arrayBuffer()), cornerUVs: c.atlas.cornerUVs.slice() };
  });
}

// For tests and tools: the raw result (copies). coords/jacobian: RGBA32F per atlas texel; colour: RGBA8
// (nearest exemplar pixel); exemplar: RGBA8; rows start at v = 0.
export function textureReadback(c) {
  return c.exclusive(async () => {
    requireResult(c);
    const r = c.stats.resolution;
    return {
      resolution: r,
      coords: c.synth.readCoordinates(),
      jacobian: c.synth.readJacobian(),
      colour: c.synth.readColour({ nearest: true }).pixels,
      exemplar: c.exemplar.tables.rgba8.slice(),
      exemplarSize: c.exemplar.tables.size,
      cornerUVs: c.atlas.cornerUVs.slice(),
      // The chart of every face of a generated atlas (null for the model's own UVs).
      faceCharts: c.atlas.faceCharts?.slice() ?? null,
    };
  });
}

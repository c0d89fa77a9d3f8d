// SPDX-License-Identifier: GPL-2.0-or-later
// The view's WebGL context lost and restored, for the texture synthesis (controller.js): everything made in it
// is gone (the synthesizer, the atlas's raster, the texture shown); once it is back, a texture that was shown is
// made again (the atlas from the worker's cache). Owns the two listeners, which dispose() removes.

// c: the SynthesisController.
export function watchContext(c) {
  const canvas = c.viewer?.renderer?.domElement;
  if (!canvas?.addEventListener) return;
  c.onContextLost = () => {
    c.runToken++;
    c.synth = null;
    c.atlas = null;
    c.lastFieldVersion = undefined;
    c.runVersion = undefined;
    c.render?.dropTextures();
  };
  c.onContextRestored = () => c.active && c.fieldChanged();
  canvas.addEventListener('webglcontextlost', c.onContextLost);
  canvas.addEventListener('webglcontextrestored', c.onContextRestored);
}

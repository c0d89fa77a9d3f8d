// SPDX-License-Identifier: GPL-2.0-or-later
// What draws a WebGL context: its renderer's name, unmasked where the browser tells it, and whether that is
// software GL. Owns nothing; imports nothing.

// The renderer's name (WEBGL_debug_renderer_info's, else the masked RENDERER string).
export function rendererName(gl) {
  const info = gl.getExtension('WEBGL_debug_renderer_info');
  return String(gl.getParameter(info ? info.UNMASKED_RENDERER_WEBGL : gl.RENDERER) ?? '');
}

// SwiftShader, llvmpipe, softpipe, WARP: rasterized by the CPU, where a pixel's and a sample's cost is the page's.
export function isSoftwareGL(gl) {
  return /swiftshader|llvmpipe|softpipe|software|basic render/i.test(rendererName(gl));
}

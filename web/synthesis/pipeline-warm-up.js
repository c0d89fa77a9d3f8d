// SPDX-License-Identifier: GPL-2.0-or-later
// The synthesis programs drawn once ahead of the first texture, into a 4x4 float target with float textures
// bound to every unit: software GL (SwiftShader) compiles a program's pipeline and its samplers for a texture
// format at their first draw, not at the link, so the first texture's raster took 221-350 ms where every later
// one took 68-110 (bunny00, docs/benchmarks.md). On a GPU the draws cost next to nothing. The locator program
// is drawn with a vertex array of its own attributes. Everything made here is deleted before it returns; the
// caller holds the GL state (the synthesizer's guard).
import { FloatTarget, drawFullscreen } from './gl.js';
import { locatorAttributes } from './atlas-raster.js';

const UNITS = 8; // at least the most samplers a synthesis program reads

// gl: the synthesizer's context; programs: its programs, linked (Synthesizer.programsReady); vao: its full-screen
// vertex array.
export function warmUpPipelines(gl, programs, vao) {
  const target = new FloatTarget(gl, 4, 4, null, { check: false });
  const input = new FloatTarget(gl, 4, 4, null, { target: false });
  const bytes = gl.createTexture();
  gl.bindTexture(gl.TEXTURE_2D, bytes);
  gl.texImage2D(gl.TEXTURE_2D, 0, gl.RGBA8, 4, 4, 0, gl.RGBA, gl.UNSIGNED_BYTE, null);
  const locator = locatorVertices(gl, programs.locator.program);
  try {
    target.bindAsTarget();
    // Every sampler reads unit 0 unless told otherwise: the float textures there, then the exemplar's bytes
    // (its colours, which the resolve passes read) for a second round.
    for (const texture of [input.texture, bytes]) {
      for (let u = 0; u < UNITS; u++) {
        gl.activeTexture(gl.TEXTURE0 + u);
        gl.bindTexture(gl.TEXTURE_2D, input.texture);
      }
      gl.activeTexture(gl.TEXTURE0);
      gl.bindTexture(gl.TEXTURE_2D, texture);
      for (const [name, p] of Object.entries(programs)) {
        if (name === 'locator') continue;
        gl.useProgram(p.program);
        drawFullscreen(gl, vao);
      }
    }
    gl.useProgram(programs.locator.program);
    gl.bindVertexArray(locator.vao);
    gl.drawArrays(gl.TRIANGLES, 0, 3);
    gl.bindVertexArray(null);
  } finally {
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    target.dispose();
    input.dispose();
    gl.deleteTexture(bytes);
    gl.deleteBuffer(locator.uv);
    gl.deleteBuffer(locator.corner);
    gl.deleteVertexArray(locator.vao);
  }
}

// One triangle for the locator program, with its attributes as the atlas raster sets them.
function locatorVertices(gl, program) {
  const vao = gl.createVertexArray();
  gl.bindVertexArray(vao);
  const uv = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, uv);
  gl.bufferData(gl.ARRAY_BUFFER, new Float32Array([0, 0, 1, 0, 0, 1]), gl.STATIC_DRAW);
  const corner = gl.createBuffer();
  gl.bindBuffer(gl.ARRAY_BUFFER, corner);
  gl.bufferData(gl.ARRAY_BUFFER, new Int32Array([0, 1, 2]), gl.STATIC_DRAW);
  locatorAttributes(gl, program, uv, corner);
  gl.bindVertexArray(null);
  gl.bindBuffer(gl.ARRAY_BUFFER, null);
  return { vao, uv, corner };
}

// SPDX-License-Identifier: GPL-2.0-or-later
// What a Synthesizer (synthesizer.js) hands out of its result: copies on the GPU for the view (display targets,
// blitted: exact; nothing is read back on the way to the screen), and read-backs for files and tests
// (coordinates, Jacobians, the resolved colour image). Each
// call is one batch of the synthesizer's GL guard (gl-guard.js). Owns the display targets it makes until the
// caller disposes them.
import { ByteTarget, FloatTarget, drawFullscreen } from './gl.js';

// The result level's coordinates and Jacobian, copied into targets of their own that later runs do not
// touch: {resolution, coord, jac} (FloatTargets; the caller disposes them).
export function displayCopy(s) {
  return s.guard.run(() => {
    const gl = s.gl;
    const level = s.levels[s.resultLevel ?? 0];
    const copy = (src) => {
      const dst = new FloatTarget(gl, src.width, src.height, null, { check: false });
      gl.bindFramebuffer(gl.READ_FRAMEBUFFER, src.framebuffer);
      gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, dst.framebuffer);
      gl.blitFramebuffer(0, 0, src.width, src.height, 0, 0, src.width, src.height, gl.COLOR_BUFFER_BIT, gl.NEAREST);
      return dst;
    };
    const out = { resolution: level.size, coord: copy(s.result), jac: copy(level.jac) };
    gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
    gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
    return out;
  });
}

export function readCoordinates(s) {
  return s.guard.run(() => s.result.read());
}

export function readJacobian(s, level = s.resultLevel ?? 0) {
  return s.guard.run(() => s.levels[level].jac.read());
}

// The exemplar's colours at the synthesized coordinates: RGBA8, (resolution * magnification)^2, row 0 = v 0.
// magnification: output pixels per atlas texel (any positive number; the output is resolution * magnification
// rounded). The same magnification as the page's renderer unless nearest.
export function readColour(s, { magnification = 1, nearest = true } = {}) {
  return s.guard.run(() => {
    s.programs.resolve.check();
    const gl = s.gl;
    const level = s.levels[s.resultLevel ?? 0];
    const size = Math.round(level.size * magnification);
    const target = new ByteTarget(gl, size, size);
    target.bindAsTarget();
    s.programs.resolve
      .use()
      .texture('uCoord', s.result)
      .texture('uJac', level.jac)
      .texture('uExemplar', s.exemplar.rgba)
      .float('uMag', size / level.size)
      .float('uM', s.exemplar.size)
      .int('uMask', s.exemplar.size - 1)
      .int('uNearest', nearest ? 1 : 0);
    drawFullscreen(gl, s.vao);
    const pixels = target.read();
    target.dispose();
    gl.bindFramebuffer(gl.FRAMEBUFFER, null);
    return { width: size, height: size, pixels };
  });
}

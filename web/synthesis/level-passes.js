// SPDX-License-Identifier: GPL-2.0-or-later
// The draws of one pyramid level (synthesizer.js, LH05 Sec. 3): each parity class upsampled (or initialised) into
// its quarter, and one correction sub-pass of a class. Both write into the level's spare quarter, which then takes
// the class's place, and both keep a texel as it was where a local run (local-update.js) leaves it: `redo` is
// the level's mask of texels to synthesize again, `local` whether to read it, `rects` (level texels) where it may
// be set, or null for the whole level. Drawn within the rectangles only, the spare is copied back into the
// quarter there instead of taking its place. Owns nothing.
import { drawFullscreen, drawWithin } from './gl.js';

// The spare drawn with the program setUp() readies: made the class's quarter, or copied into it where `rects`
// (level texels) say.
function drawIntoQuarter(s, L, c, rects, setUp) {
  const gl = s.gl;
  L.spare.bindAsTarget();
  setUp();
  if (!rects) {
    drawFullscreen(gl, s.vao);
    [L.quarters[c], L.spare] = [L.spare, L.quarters[c]];
    return;
  }
  const quarter = rects.map(({ x, y, w, h }) => ({ x: x >> 1, y: y >> 1, w: w >> 1, h: h >> 1 }));
  drawWithin(gl, s.vao, quarter);
  gl.bindFramebuffer(gl.READ_FRAMEBUFFER, L.spare.framebuffer);
  gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, L.quarters[c].framebuffer);
  for (const { x, y, w, h } of quarter)
    gl.blitFramebuffer(x, y, x + w, y + h, x, y, x + w, y + h, gl.COLOR_BUFFER_BIT, gl.NEAREST);
  gl.bindFramebuffer(gl.READ_FRAMEBUFFER, null);
  gl.bindFramebuffer(gl.DRAW_FRAMEBUFFER, null);
}

// s: the synthesizer (gl, vao, programs, exemplar); L: the level; parent: the coarser level's result or null;
// step: levelPlan()'s; c: the class; o: the run's options.
export function upsampleClass(s, L, parent, step, c, o, { redo, local, rects }) {
  drawIntoQuarter(s, L, c, rects, () => useUpsample(s, L, parent, step, c, o, redo, local));
}

function useUpsample(s, L, parent, step, c, o, redo, local) {
  s.programs.upsample
    .use()
    .texture('uRedo', redo)
    .texture('uParent', parent ?? L.jac)
    .texture('uJac', L.jac)
    .texture('uOld', L.quarters[c])
    .int('uLocal', local ? 1 : 0)
    .int('uCoarsest', parent ? 0 : 1)
    .ivec2('uClass', c & 1, c >> 1)
    .float('uJitter', step.jitter)
    .int('uLevel', step.k)
    .int('uSeed', o.seed | 0)
    .float('uM', s.exemplar.size);
}

// One correction sub-pass of class c with the exemplar's stack level E.
export function correctClass(s, L, E, step, c, o, { redo, local, rects }) {
  drawIntoQuarter(s, L, c, rects, () => useCorrection(s, L, E, step, c, o, redo, local));
}

function useCorrection(s, L, E, step, c, o, redo, local) {
  const m = s.exemplar.size;
  s.programs.correct
    .use()
    .texture('uRedo', redo)
    .texture('uS0', L.quarters[0])
    .texture('uS1', L.quarters[1])
    .texture('uS2', L.quarters[2])
    .texture('uS3', L.quarters[3])
    .texture('uJac', L.jac)
    .texture('uIndir', L.indirection)
    .int('uSeams', o.seams ? 1 : 0)
    .texture('uApp0', E.app0)
    .texture('uApp1', E.app1)
    .texture('uNbr0', E.nbr0)
    .texture('uNbr1', E.nbr1)
    .texture('uCand', E.cand)
    .mat4v('uProj', E.proj)
    .vec4v('uProjOff', E.projOff)
    .ivec2('uSize', L.size, L.size)
    .ivec2('uClass', c & 1, c >> 1)
    .int('uMask', m - 1)
    .float('uM', m)
    .float('uH', step.spacing)
    .float('uKappa', o.kappa)
    .int('uLocal', local ? 1 : 0);
}

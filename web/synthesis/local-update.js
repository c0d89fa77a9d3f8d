// SPDX-License-Identifier: GPL-2.0-or-later
// A synthesis run redone only where the field moved (synthesizer.js). LH05's synthesis is local: a texel's
// coordinate depends on its parent's and on its level's neighbours a texel or two away, and the rest of the
// pyramid on the same jitter (a hash of the texel, level and seed). So each level keeps the Jacobian its texels were
// last synthesized with, and a run whose options, exemplar and atlas are those of the run before marks, level by
// level, the texels whose Jacobian moved by more than three quarters of `localDegrees` (or was never
// synthesized), widened by two texels so that the new patches are corrected against their kept neighbours; only
// those are upsampled and corrected, the others keep their coordinates. The Jacobian itself is drawn again only
// where the field moved by more than the last quarter (atlas-raster.js), so a texel kept follows the field within
// localDegrees (scale alike: the Jacobian's relative change), however many runs it is kept through: it is
// compared with the Jacobian it was made with, not the last run's. A level's moved texels are flagged as never
// synthesized before its passes, and all it made get their new Jacobian after them: a run cancelled half-way
// leaves the next run the texels it had begun. The passes are drawn only round the blocks of texels that moved
// (level-passes.js).
// Owns the per-level kept Jacobians and masks (on the atlas's levels, disposed with it) and its programs (the
// synthesizer disposes them with its own).
import { ByteTarget, FloatTarget, FULLSCREEN_VS, Program, drawWithin } from './gl.js';
import { RASTER_SHARE, TILE, blockMaskRects, blocksOf } from './raster-delta.js';

const HEADER = `#version 300 es
precision highp float;
precision highp int;
precision highp sampler2D;
`;
// Stands for "never synthesized" in a kept Jacobian (a real one is a few exemplar pixels per texel).
const UNSYNTHESIZED = 1e30;
const WIDEN = 2; // texels round a moved one that are synthesized again with it, at every level
// A level of at least TILE texels a side is drawn only round its TILE-texel blocks that hold a moved texel (a block
// more each way: the widening stays within it: bandRects); a smaller level whole, and a level with no moved texel
// not at all (synthesizer.js).

// 1 where the texel's Jacobian moved from the kept one by more than uTol relative to the larger (the angle's
// chord: a rotation by θ moves a 2x2 Jacobian by 2 sin(θ/2) of its norm), or was never synthesized.
const MOVED_FS = `${HEADER}
uniform sampler2D uJac;
uniform sampler2D uKept;
uniform float uTol;
out vec4 outM;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  vec4 a = texelFetch(uJac, p, 0), b = texelFetch(uKept, p, 0);
  bool moved = b.x >= ${UNSYNTHESIZED.toExponential()} || length(a - b) > uTol * max(length(a), length(b));
  outM = vec4(moved ? 1.0 : 0.0);
}`;

// The moved texels widened by WIDEN texels (a square).
const WIDEN_FS = `${HEADER}
uniform sampler2D uMoved;
out vec4 outM;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy), last = textureSize(uMoved, 0) - 1;
  float m = 0.0;
  for (int y = -${WIDEN}; y <= ${WIDEN}; ++y)
    for (int x = -${WIDEN}; x <= ${WIDEN}; ++x)
      m = max(m, texelFetch(uMoved, clamp(p + ivec2(x, y), ivec2(0), last), 0).r);
  outM = vec4(m);
}`;

// 1 for a TILE x TILE block of the level with a moved texel.
const TILES_FS = `${HEADER}
uniform sampler2D uMoved;
out vec4 outT;
void main() {
  ivec2 corner = ${TILE} * ivec2(gl_FragCoord.xy);
  float m = 0.0;
  for (int y = 0; y < ${TILE}; ++y)
    for (int x = 0; x < ${TILE}; ++x) m = max(m, texelFetch(uMoved, corner + ivec2(x, y), 0).r);
  outT = vec4(m);
}`;

// Writes "never synthesized" (uFromJac = 0) or the texel's Jacobian (1) into the kept Jacobian where the mask is
// set (or everywhere: uAll).
const KEEP_FS = `${HEADER}
uniform sampler2D uMask;
uniform sampler2D uJac;
uniform int uAll;
uniform int uFromJac;
out vec4 outJ;
void main() {
  ivec2 p = ivec2(gl_FragCoord.xy);
  if (uAll == 0 && texelFetch(uMask, p, 0).r < 0.5) discard;
  outJ = uFromJac == 1 ? texelFetch(uJac, p, 0) : vec4(${UNSYNTHESIZED.toExponential()});
}`;

// What makes a run's kept coordinates reusable by the next: the same atlas and exemplar on the GPU and the same
// options (the field apart; the finest level does not matter, each level keeps its own).
const KEY_OPTIONS = ['featureScale', 'magnitudeExponent', 'jitter', 'finestJitter', 'passes', 'kappa', 'seed', 'seams'];

export class LocalUpdate {
  // gl and vao: the synthesizer's context and full-screen vertex array.
  constructor(gl, vao) {
    this.gl = gl;
    this.vao = vao;
    this.programs = {
      moved: new Program(gl, FULLSCREEN_VS, MOVED_FS, 'local-moved'),
      widen: new Program(gl, FULLSCREEN_VS, WIDEN_FS, 'local-widen'),
      keep: new Program(gl, FULLSCREEN_VS, KEEP_FS, 'local-keep'),
      tiles: new Program(gl, FULLSCREEN_VS, TILES_FS, 'local-tiles'),
    };
    this.key = null;
    this.next = false; // whether the next run of the same atlas, exemplar and options is local
  }

  // At a run's start: whether it can be local (the same atlas, exemplar and options as the run before, and
  // o.localDegrees > 0). A run that cannot marks every level never synthesized: a run cancelled on its way leaves
  // nothing the next could take for made under these options.
  begin(atlas, exemplar, o) {
    const key = [atlas, exemplar, ...KEY_OPTIONS.map((k) => JSON.stringify(o[k]))];
    const same = this.key !== null && key.every((v, i) => v === this.key[i]);
    this.key = key;
    // The raster is within RASTER_SHARE of the angle of the field (atlas-raster.js), this the rest.
    this.tolerance = 2 * Math.sin(((1 - RASTER_SHARE) * (o.localDegrees ?? 0) * Math.PI) / 360);
    this.local = same && o.localDegrees > 0;
    this.drawnShare = 1;
    this.reason = o.localDegrees > 0 ? (same ? null : 'first run of this atlas, exemplar and options') : 'off';
    this.next = o.localDegrees > 0;
    // Every texel to make: a run cut short leaves the next one to compare them anywhere.
    if (!this.local)
      for (const L of atlas.levels) {
        if (L.kept) this.#fill(L.kept, UNSYNTHESIZED);
        L.jacDrawn = null;
      }
    return this.local;
  }

  // A local run, once the field is rasterized, for every level it makes (levels: the atlas's, finest first; plan:
  // levelPlan()'s): its mask of moved texels, and of blocks that hold one. The run then waits for the GPU (a
  // phase of the kernel's) before readBlocks(). Both are drawn only where the level's Jacobian was drawn since the
  // level was last made (L.jacDrawn, raster-delta.js noteJacobianDrawn): a texel elsewhere was compared then and
  // made again if it had moved (over the whole pyramid they were most of a bunny00 update's kernel with software
  // GL).
  find(levels, plan) {
    const { moved, tiles } = this.programs;
    for (const { k } of plan) {
      const L = levels[k];
      this.#allocate(L);
      L.rects = null;
      const where = L.jacDrawn ?? null;
      if (where) for (const t of [L.moved, L.blocks]) if (t) this.#fill(t, 0);
      this.#pass(L.moved, where, () =>
        moved.use().texture('uJac', L.jac).texture('uKept', L.kept).float('uTol', this.tolerance),
      );
      if (L.blocks) this.#pass(L.blocks, where && blocksOf(where), () => tiles.use().texture('uMoved', L.moved));
    }
  }

  // Once the GPU is done with find()'s passes: where each level is to be drawn (`rects`, level texels, in bands of
  // block rows; an empty list where nothing is to be made again), and the share of the finest level that is.
  readBlocks(levels, plan) {
    if (!this.local) return;
    for (const { k } of plan) {
      const L = levels[k];
      if (L.blocks) L.rects = bandRects(L.blocks.read(), L.blocks.width);
    }
    const finest = levels[plan.at(-1).k];
    this.drawnShare = (finest.rects?.reduce((a, r) => a + r.w * r.h, 0) ?? finest.size ** 2) / finest.size ** 2;
  }

  // Before level L's passes: its mask of texels to make again (the moved ones widened), and where it may be set
  // ({redo, local, rects}; a run that is not local makes every texel and reads neither; outside rects the mask is
  // not made). The moved texels are flagged as never made until after(): a run cancelled before then leaves
  // the next one the same mask again, the ring round them included.
  before(L) {
    this.#allocate(L);
    if (!this.local) L.rects = null;
    else if (L.rects?.length === 0) L.jacDrawn = []; // nothing moved: every texel follows its Jacobian as drawn
    else {
      this.#pass(L.redo, L.rects, () => this.programs.widen.use().texture('uMoved', L.moved));
      this.#keep(L, L.moved, { all: false, fromJac: false });
    }
    return { redo: L.redo, local: this.local, rects: L.rects };
  }

  // After level L's passes: its texels made (all, or those of its mask) keep the Jacobian they were made with, and
  // the next run compares them only where the Jacobian is drawn again (a run cancelled before then compares them
  // where it did, the texels it flagged never made included).
  after(L) {
    this.#keep(L, L.redo, { all: !this.local, fromJac: true });
    L.jacDrawn = [];
  }

  #keep(L, mask, { all, fromJac }) {
    this.#pass(L.kept, all ? null : L.rects, () =>
      this.programs.keep
        .use()
        .texture('uMask', mask)
        .texture('uJac', L.jac)
        .int('uAll', all ? 1 : 0)
        .int('uFromJac', fromJac ? 1 : 0),
    );
  }

  // One full-screen pass into target of the program setUp() readies, within rects (null: all of it).
  #pass(target, rects, setUp) {
    target.bindAsTarget();
    setUp();
    drawWithin(this.gl, this.vao, rects);
  }

  #allocate(L) {
    if (L.kept) return;
    L.kept = new FloatTarget(this.gl, L.size, L.size, null, { check: false });
    this.#fill(L.kept, UNSYNTHESIZED);
    L.moved = new ByteTarget(this.gl, L.size, L.size);
    L.redo = new ByteTarget(this.gl, L.size, L.size);
    if (L.size >= TILE) L.blocks = new ByteTarget(this.gl, L.size / TILE, L.size / TILE);
  }

  #fill(target, value) {
    target.bindAsTarget();
    this.gl.clearBufferfv(this.gl.COLOR, 0, [value, value, value, value]);
  }

  // The run's account for its stats (localDrawnShare: the share of the finest level its passes were drawn over).
  // localNext: the next run of the same atlas, exemplar and options will be local.
  summary() {
    return { local: this.local, localReason: this.reason, localNext: this.next, localDrawnShare: this.drawnShare };
  }
}

// The blocks' mask (RGBA8, n x n, row 0 first) widened by a block each way (the widening's texels stay within
// it), as rectangles in level texels (raster-delta.js blockMaskRects: bands of block rows, a rectangle per run of
// columns). Bands over all the columns between their first and last block, widened by a block row into the bands
// beside them, drew up to twice the level: 1.1-1.8 times it for an edit that moved half of the default bunny's
// faces.
function bandRects(bytes, n) {
  const set = new Uint8Array(n * n);
  for (let y = 0; y < n; y++)
    for (let x = 0; x < n; x++) {
      if (!bytes[4 * (y * n + x)]) continue;
      for (let yy = Math.max(0, y - 1); yy <= Math.min(n - 1, y + 1); yy++)
        set.fill(1, yy * n + Math.max(0, x - 1), yy * n + Math.min(n, x + 2));
    }
  return blockMaskRects(set, n);
}

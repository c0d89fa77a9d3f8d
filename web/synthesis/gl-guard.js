// SPDX-License-Identifier: GPL-2.0-or-later
// The synthesizer drawing in the view's own WebGL context (so that its result is shown where it is made, with
// no read-back and no upload on the way to the screen) shares that context's state with three.js, which caches
// the state it set. Every batch of the synthesizer's GL calls therefore starts and ends with
// renderer.resetState(): GL back to its defaults (no blending, culling, depth or scissor test; framebuffer,
// program, vertex array and pixel-store state reset) and three.js's cache emptied, so that neither side draws
// with the other's state. A synthesizer with a context of its own has no renderer and no guard.
export class GLGuard {
  constructor(renderer = null) {
    this.renderer = renderer;
    this.depth = 0; // batches inside batches reset once
  }

  // fn() as one batch; returns its value.
  run(fn) {
    if (!this.renderer || this.depth) return fn();
    this.depth++;
    this.renderer.resetState();
    try {
      return fn();
    } finally {
      this.renderer.resetState();
      this.depth--;
    }
  }

  // The steps of a generator, each (up to its yield) one batch; returns the generator's value.
  *steps(generator) {
    for (;;) {
      const r = this.run(() => generator.next());
      if (r.done) return r.value;
      yield r.value;
    }
  }
}

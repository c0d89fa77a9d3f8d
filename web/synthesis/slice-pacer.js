// SPDX-License-Identifier: GPL-2.0-or-later
// How much of a synthesis goes to the GPU per frame. A fixed share (32k texel shadings a frame) made a 1024²
// pyramid about 860 slices, a frame each, for work a real GPU does in 29 ms; software GL, on the other hand,
// falls seconds behind (and so does the page's own drawing) when given more than it can draw in a frame. So
// each slice is fenced and the next one sized by what the GPU did: twice as much when it was done within a
// frame's time, half when it still worked on it two frames' time later; the page waits for the slice before
// the one just issued, so the GPU always has work queued. The size learnt is kept for the synthesizer's next
// run.
//
// Phases (phase-clock.js): 'kernel: draws' (issuing a slice on the page's thread), 'kernel: GPU' (polls waited
// while the GPU worked on a slice), 'waits between slices' (the poll in which the GPU was found done). Where the
// context has EXT_disjoint_timer_query_webgl2, the GPU's own time replaces the polls' guess (finish()).
const FRAME_MS = 16.7;

// A short task: the page's thread free for whatever waits, without waiting for a frame to be drawn.
export const nextTask = () => new Promise((resolve) => setTimeout(resolve, 0));

export class SlicePacer {
  constructor(gl, { texels = 1 << 16, minTexels = 1 << 12, maxTexels = 1 << 26 } = {}) {
    this.gl = gl;
    this.texels = texels;
    this.minTexels = minTexels;
    this.maxTexels = maxTexels;
    this.timer = gl.getExtension('EXT_disjoint_timer_query_webgl2');
    this.query = null;
    this.queries = [];
    this.inFlight = []; // fences of slices the GPU may still work on, oldest first
    this.slices = 0;
  }

  // A run starts: no GPU time measured yet.
  start() {
    this.#dropQueries();
    this.#dropFences();
    this.slices = 0;
  }

  // Before a slice's draws.
  begin() {
    if (!this.timer || this.query) return;
    this.query = this.gl.createQuery();
    this.gl.beginQuery(this.timer.TIME_ELAPSED_EXT, this.query);
  }

  // After a slice's draws: flushes them and waits until the GPU is done with the slice before (or with this one
  // too when `last`, or the run is cancelled), so that the GPU always has the next slice queued and never more
  // than two. The fences are looked at every few milliseconds (`poll`, a short task: the page's thread stays
  // free, and a slice done mid-frame is followed at once, not at the next frame). The next slice is twice as
  // big when the wait took under a frame, half as big when it took over two.
  async end(clock, poll, cancelled, { last = false } = {}) {
    const gl = this.gl;
    if (this.query) {
      gl.endQuery(this.timer.TIME_ELAPSED_EXT);
      this.queries.push(this.query);
      this.query = null;
    }
    this.slices++;
    const fence = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
    gl.flush();
    clock.mark('kernel: draws');
    if (!fence) {
      await poll(); // a lost context
      clock.mark('waits between slices');
      return;
    }
    this.inFlight.push(fence);
    const keep = last ? 0 : 1, t0 = performance.now();
    while (this.inFlight.length > keep && !cancelled()) {
      await poll();
      const before = this.inFlight.length;
      while (this.inFlight.length && gl.getSyncParameter(this.inFlight[0], gl.SYNC_STATUS) === gl.SIGNALED)
        gl.deleteSync(this.inFlight.shift());
      // Every slice done: the GPU may have idled since it finished, for part of the poll.
      clock.mark(this.inFlight.length === 0 && before > 0 ? 'waits between slices' : 'kernel: GPU');
    }
    if (last || cancelled()) this.#dropFences();
    const waited = performance.now() - t0;
    if (waited < FRAME_MS) this.texels = Math.min(this.maxTexels, 2 * this.texels);
    else if (waited > 2 * FRAME_MS) this.texels = Math.max(this.minTexels, this.texels / 2);
  }

  // Waits (polling, as end() does) until the GPU has done everything issued so far, marking the wait as
  // `phase`. Before a big upload: a bufferSubData issued while the GPU process is busy (the view's frame of a
  // big textured model takes it seconds with software GL) waits for it on the page's thread (4.4 s of one
  // task in an armadillo-sub2 update).
  async drain(clock, poll, cancelled, phase) {
    const gl = this.gl;
    const fence = gl.fenceSync(gl.SYNC_GPU_COMMANDS_COMPLETE, 0);
    gl.flush();
    clock.mark(phase);
    if (!fence) return;
    try {
      while (!cancelled() && gl.getSyncParameter(fence, gl.SYNC_STATUS) !== gl.SIGNALED) await poll();
    } finally {
      gl.deleteSync(fence);
    }
    clock.mark(phase);
  }

  #dropFences() {
    for (const f of this.inFlight) this.gl.deleteSync(f);
    this.inFlight = [];
  }

  // The run is done (every slice waited for): with a GPU timer, its measured time becomes the kernel's and the
  // rest of the frames waited the waits'. Returns the GPU's milliseconds, or null without a timer.
  finish(clock) {
    const gl = this.gl;
    if (!this.timer || !this.queries.length) return null;
    let ns = 0;
    const disjoint = gl.getParameter(this.timer.GPU_DISJOINT_EXT);
    for (const q of this.queries) {
      if (!gl.getQueryParameter(q, gl.QUERY_RESULT_AVAILABLE)) return this.#dropQueries();
      ns += gl.getQueryParameter(q, gl.QUERY_RESULT);
    }
    this.#dropQueries();
    if (disjoint) return null;
    const gpuMs = ns / 1e6;
    const waited = (clock.phases['kernel: GPU'] ?? 0) + (clock.phases['waits between slices'] ?? 0);
    clock.move('kernel: GPU', 'waits between slices', clock.phases['kernel: GPU'] ?? 0);
    clock.move('waits between slices', 'kernel: GPU', Math.min(gpuMs, waited));
    return gpuMs;
  }

  #dropQueries() {
    if (this.query) this.gl.endQuery(this.timer.TIME_ELAPSED_EXT);
    for (const q of [...this.queries, this.query]) if (q) this.gl.deleteQuery(q);
    this.queries = [];
    this.query = null;
    return null;
  }
}

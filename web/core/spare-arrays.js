// The worker's spare field arrays: buffers of earlier field arrays the page handed back (core-proxy.js
// recycle()), kept by length. Refilling one is a memcpy; a fresh ArrayBuffer of the same size costs Chromium
// several times that (new zeroed pages, and garbage on both sides): copies took 134 of a stroke's 582 ms in the
// worker at 1.25M edges.
const SPARES_PER_LENGTH = 2;

export class SpareArrays {
  constructor() {
    this.byLength = new Map();
    // The field arrays' lengths on the current mesh (3 per face, 3 per vertex, 1 per edge): spares of any other
    // length (a previous model's) are dropped, not kept.
    this.lengths = new Set();
  }

  // A new mesh: its field lengths, and no spares of the previous one.
  reset(lengths) {
    this.byLength.clear();
    this.lengths = new Set(lengths);
  }

  take(buffers) {
    for (const buffer of buffers ?? []) {
      const array = new Float64Array(buffer);
      if (!this.lengths.has(array.length)) continue;
      const list = this.byLength.get(array.length) ?? [];
      if (list.length < SPARES_PER_LENGTH) list.push(array);
      this.byLength.set(array.length, list);
    }
  }

  // A spare of this length, or a fresh array.
  pop(length) {
    return this.byLength.get(length)?.pop() ?? new Float64Array(length);
  }

  // A copy of a view of the wasm heap, into a spare when there is one of its length (counts.reused counts those).
  copyOut(view, counts) {
    const array = this.byLength.get(view.length)?.pop();
    if (!array) return view.slice();
    array.set(view);
    counts.reused++;
    return array;
  }
}

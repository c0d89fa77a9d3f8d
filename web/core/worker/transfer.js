// A worker op's result that carries its own transfer list: the dispatch (dispatch.js) posts `value` with the
// buffers of `list` transferred rather than copied. Used by every op group that hands over arrays, synthesis'
// included (synthesis/worker-ops.js). Imports nothing.

export class Transfer {
  constructor(value, list) {
    this.value = value;
    this.list = list;
  }

  // A {value, list} pair made elsewhere (field-parts.js's replies).
  static of({ value, list }) {
    return new Transfer(value, list);
  }
}

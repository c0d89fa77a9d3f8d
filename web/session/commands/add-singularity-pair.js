// A +/- pair of prescribed singularities as one step (the Singularity tool's drag from empty surface: +1/N at
// the press, -1/N at the release), so that the total index never changes between two undo steps. One request
// each way: the worker's addSingularities, and its removeConstraints for the undo; each singularity gets a page
// id of its own, kept across undo and redo, and is listed, moved and removed as any prescribed one.
export class AddSingularityPair {
  static type = 'AddSingularityPair';

  // pair: [[vertex, index], [vertex, index]]; uids: their page ids once the first execution gave them.
  constructor(pair, uids = [null, null]) {
    this.pair = pair;
    this.uids = uids;
  }

  get label() {
    return `add singularities #${this.uids[0]} and #${this.uids[1]}`;
  }

  get result() {
    return [...this.uids];
  }

  request() {
    return { op: 'addSingularities', args: [this.pair] };
  }

  applied(reply, table) {
    this.uids = this.uids.map((uid, k) => {
      uid ??= table.nextUid++;
      table.uids.set(uid, reply.value[k]);
      table.nextUid = Math.max(table.nextUid, uid + 1); // a deserialized command brings its own page ids
      return uid;
    });
  }

  undoRequest(table) {
    return { op: 'removeConstraints', args: [this.uids.map((uid) => table.coreIdOf(uid))] };
  }

  undone(reply, table) {
    for (const uid of this.uids) table.uids.delete(uid);
  }

  serialize() {
    return { type: AddSingularityPair.type, pair: structuredClone(this.pair), uids: [...this.uids] };
  }

  static deserialize({ pair, uids }) {
    return new AddSingularityPair(structuredClone(pair), [...uids]);
  }
}

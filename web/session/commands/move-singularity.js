// Moves a prescribed singularity to another vertex, with the vertex it leaves: the core keeps its id and index
// (one change of the connection each way), so the page id needs no bookkeeping.
export class MoveSingularity {
  static type = 'MoveSingularity';

  constructor(uid, from, to) {
    this.uid = Number(uid);
    this.from = from;
    this.to = to;
  }

  static of(table, uid, vertex) {
    const spec = table.specOf(Number(uid));
    if (spec.type !== 'singularity') throw new Error(`constraint ${uid} is a ${spec.type}, not a singularity`);
    return new MoveSingularity(uid, spec.vertex, vertex);
  }

  get label() {
    return `move singularity #${this.uid}`;
  }

  get result() {
    return true;
  }

  get changes() {
    return this.from !== this.to;
  }

  request(table) {
    return this.changes ? { op: 'moveSingularity', args: [table.coreIdOf(this.uid), this.to] } : null;
  }

  // The vertex as the core holds it.
  applied(reply, table) {
    if (reply) this.to = table.specOf(this.uid).vertex;
  }

  undoRequest(table) {
    return { op: 'moveSingularity', args: [table.coreIdOf(this.uid), this.from] };
  }

  serialize() {
    const { uid, from, to } = this;
    return { type: MoveSingularity.type, uid, from, to };
  }

  static deserialize({ uid, from, to }) {
    return new MoveSingularity(uid, from, to);
  }
}

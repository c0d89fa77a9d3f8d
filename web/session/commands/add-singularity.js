// Prescribes a singularity: the field's index at an interior vertex, a nonzero multiple of 1/N (the core
// refuses a boundary vertex, another index, a vertex that has one). In the design it is a constraint like any
// other ({type: 'singularity', vertex, index}): its page id survives a delete and its undo, the delete is
// remove-constraint.js's and brings vertex and index back. Only the request differs from AddConstraint's: the
// core's own addSingularity.
import { AddConstraint } from './add-constraint.js';

export const singularitySpec = (vertex, index) => ({ type: 'singularity', vertex, index });

export class AddSingularity extends AddConstraint {
  static type = 'AddSingularity';

  constructor(vertex, index, uid = null) {
    super(singularitySpec(vertex, index), uid);
  }

  get label() {
    return `add singularity #${this.uid}`;
  }

  request() {
    return { op: 'addSingularity', args: [this.spec.vertex, this.spec.index] };
  }

  serialize() {
    const { uid, spec } = this;
    return { type: AddSingularity.type, uid, vertex: spec.vertex, index: spec.index };
  }

  static deserialize({ vertex, index, uid }) {
    return new AddSingularity(vertex, index, uid);
  }
}

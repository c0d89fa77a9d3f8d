// A +/- pair of prescribed singularities as one step (the Singularity tool's drag from empty surface: +1/N at
// the press, -1/N at the release), so that the total index never changes between two undo steps: several
// singularities added at once (add-singularities.js), two of them, labelled by their page ids.
import { AddSingularities } from './add-singularities.js';

export class AddSingularityPair extends AddSingularities {
  static type = 'AddSingularityPair';

  // pair: [[vertex, index], [vertex, index]]; uids: their page ids once the first execution gave them.
  constructor(pair, uids = [null, null]) {
    super(pair, uids);
  }

  get pair() {
    return this.list;
  }

  get label() {
    return `add singularities #${this.uids[0]} and #${this.uids[1]}`;
  }

  serialize() {
    return { type: AddSingularityPair.type, pair: structuredClone(this.list), uids: [...this.uids] };
  }

  static deserialize({ pair, uids }) {
    return new AddSingularityPair(structuredClone(pair), [...uids]);
  }
}

// The field's topology as the user designs it, for one Session: prescribed singularities placed, moved and
// removed, the sharp features set, and the reads of both (the field's singularities with the prescribed ones
// flagged and named by page id, what the prescribed indices leave to the field, the features in use). Every
// edit is a command (commands/) run by the session, one history step each, as any other edit; a refusal of
// the core rejects with its message and leaves the design as it was.
//
// Owns no state beyond the session's. Imports the session's commands.
import {
  AddSingularity,
  AddSingularities,
  AddSingularityPair,
  MoveSingularity,
  RemoveConstraint,
  SetFeatures,
} from './commands/index.js';

export class FieldTopology {
  constructor(session) {
    this.session = session;
  }

  // index: a nonzero multiple of 1/N; resolves with the singularity's page id. meshSerial: as addConstraint's.
  addSingularity(vertex, index, meshSerial = undefined) {
    return this.#onModel(meshSerial, () => new AddSingularity(vertex, index));
  }

  // Two singularities ([vertex, index] each, a +/- pair) as one step; resolves with their page ids.
  addSingularityPair(first, second, meshSerial = undefined) {
    return this.#onModel(meshSerial, () => new AddSingularityPair([[...first], [...second]]));
  }

  // Several singularities ([[vertex, index], ...]: a .sing file's) as one step, all or none; resolves with
  // their page ids. what: where they came from (the step's label).
  addSingularities(list, what = '') {
    return this.session.execute(() => {
      if (!Array.isArray(list) || !list.every((s) => Array.isArray(s) && s.length === 2))
        throw new Error('singularities must be a list of [vertex, index] pairs');
      return new AddSingularities(list.map((s) => [...s]), undefined, what);
    });
  }

  // A Directional .sing file's singularities (its text) added as one step, all or none, each index k / N of the
  // file's N: the design's N must hold it as a multiple of its own 1/N (the core refuses one that is not). A
  // refusal names the file, and the file's N where it is not the design's. Resolves with their page ids.
  async addSingFile(text, name = 'the .sing file') {
    const s = this.session;
    let read = null;
    const named = (err) => {
      const n = s.settings().symmetry;
      const why = read && read.symmetry !== n ? ` (the file's N is ${read.symmetry}, the design's ${n})` : '';
      return new Error(`${name}: ${err.message}${why}`);
    };
    try {
      read = await s.request('readSing', [String(text)], { exclusive: true });
    } catch (err) {
      throw named(err);
    }
    const list = read.singularities.map(({ vertex, index }) => [vertex, index]);
    if (!list.length) throw new Error(`${name} holds no singularity`);
    return this.addSingularities(list, name).catch((err) => {
      throw named(err);
    });
  }

  // A tool's edit, dropped when the model changed before it reached the core.
  #onModel(meshSerial, makeCommand) {
    const s = this.session;
    return s.execute(() => {
      if (meshSerial !== undefined && meshSerial !== s.meshSerial)
        throw new Error('the model changed before this edit reached the core; it was not applied');
      return makeCommand();
    });
  }

  moveSingularity(uid, vertex) {
    return this.session.execute((table) => MoveSingularity.of(table, uid, vertex));
  }

  // As any constraint's removal; refused for a constraint that is not a singularity.
  removeSingularity(uid) {
    return this.session.execute((table) => {
      const command = RemoveConstraint.of(table, uid);
      if (command.spec.type !== 'singularity')
        throw new Error(`constraint ${uid} is a ${command.spec.type}, not a singularity`);
      return command;
    });
  }

  // features: any of {angle, add, remove}.
  setFeatures(features) {
    return this.session.execute((table) => SetFeatures.of(table, features));
  }

  // The current field's singularities [{vertex, index, prescribed, id (page id, prescribed ones)}]: the core's
  // read-out when the design prescribes some (it flags them), else the page's own; a singularity where the
  // design prescribes that index is prescribed either way (a big model's preview field is the page's).
  singularities() {
    const s = this.session;
    const byVertex = new Map();
    for (const { uid, spec } of s.table.entries()) if (spec.type === 'singularity') byVertex.set(spec.vertex, uid);
    return s.field.requireSingularities().map(({ vertex, index, prescribed = false }) => {
      const uid = byVertex.get(vertex);
      const named = uid !== undefined && (prescribed || s.table.specOf(uid).index === index);
      return named ? { vertex, index, prescribed: true, id: uid } : { vertex, index, prescribed };
    });
  }

  // {mode: 'none' | 'exact' | 'free', eulerCharacteristic, prescribedIndex, freeIndex}: the field's stats;
  // exact: the design asks for only the prescribed singularities (none when none are prescribed).
  summary() {
    const { singularityMode = 'none', eulerCharacteristic = 0, prescribedIndex = 0, freeIndex = 0 } =
      this.session.field.stats;
    const exact = this.session.table.settings().exactSingularities;
    return { mode: singularityMode, eulerCharacteristic, prescribedIndex, freeIndex, exact };
  }

  // true: the field has exactly the prescribed singularities, none when none are prescribed.
  setExactSingularities(exact) {
    return this.session.setSetting('exactSingularities', exact);
  }

  // {angle, add, remove} as the design holds them, and `edges`: the vertex pairs in use ([[a, b], ...]; none
  // known for a big model's preview field).
  features() {
    const pairs = this.session.field.featureEdges ?? [];
    const edges = [];
    for (let k = 0; k + 1 < pairs.length; k += 2) edges.push([pairs[k], pairs[k + 1]]);
    return { ...structuredClone(this.session.table.features()), edges };
  }
}

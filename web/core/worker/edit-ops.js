// The worker's edits of one constraint, a prescribed singularity's included (dispatch.js files them as `edits`: the
// core solves after each and the reply carries a snapshot). Each says how to take itself back should that solve fail
// (state.undoEdit) and which design entries it changed (state.changedIds), so that the snapshot carries only those. The
// edits of the design as a whole are setting-ops.js's. Imports nothing.

export function editOps(state) {
  return {
    edits: {
      // One constraint in the design format: new ones and re-added ones (undo of a delete) alike go through the
      // core's own design-file parser.
      add(spec) {
        const id = state.core.addConstraintJson(spec);
        state.undoEdit = () => state.core.remove(id);
        state.changedIds = [id];
        return id;
      },

      // A prescribed singularity (index a nonzero multiple of 1/N at an interior vertex); its core id.
      addSingularity(vertex, index) {
        const id = state.core.addSingularity(vertex, index);
        state.undoEdit = () => state.core.remove(id);
        state.changedIds = [id];
        return id;
      },

      // Several at once ([[vertex, index], ...]: a +/- pair, one step for the page); their core ids. A refusal of
      // any takes back those added before it.
      addSingularities(list) {
        const ids = [];
        state.undoEdit = () => ids.forEach((id) => state.core.remove(id));
        for (const [vertex, index] of list) ids.push(state.core.addSingularity(vertex, index));
        state.changedIds = ids;
        return ids;
      },

      // The singularity keeps its id and index; the core refuses what addSingularity would.
      moveSingularity(id, vertex) {
        const before = state.core.constraint(id)?.vertex;
        state.core.moveSingularity(id, vertex);
        if (before !== undefined) state.undoEdit = () => state.core.moveSingularity(id, before);
        state.changedIds = [id];
        return true;
      },

      remove(id) {
        state.core.remove(id);
        state.changedIds = [];
        return true;
      },

      // Several constraints in one step (the undo of a pair).
      removeConstraints(ids) {
        for (const id of ids) state.core.remove(id);
        state.changedIds = [];
        return true;
      },

      setWeight(id, w) {
        const before = state.core.constraint(id)?.weight;
        state.core.setWeight(id, w);
        if (before !== undefined) state.undoEdit = () => state.core.setWeight(id, before);
        state.changedIds = [id];
        return true;
      },

      setStrength(id, s) {
        const before = state.core.constraint(id)?.strength;
        state.core.setStrength(id, s);
        if (before !== undefined) state.undoEdit = () => state.core.setStrength(id, before);
        state.changedIds = [id];
        return true;
      },
    },
  };
}

// The worker's ops that change the design as a whole rather than one constraint: the boundary condition, γ, the
// symmetry N, the curvature alignment, the sharp features, whether the field has only the prescribed singularities
// and a whole design document. After each the worker solves (refactoring: each changes the system or its
// right-hand side) and sends the whole document back: dispatch.js files them as `edits`, with no changed ids. Each
// sets state.undoEdit: how to take the edit back should the solve after it fail, so that the core never keeps a
// state it cannot solve. Imports nothing.

export function settingOps(state) {
  const core = () => state.core;
  const onUndo = (undo) => (state.undoEdit = undo);

  // The whole design put back as it is now; its constraints come back under fresh core ids, which the page maps
  // onto its own (session/commands/).
  const restoreNow = () => {
    const before = core().designJson();
    return () => core().applyDesignJson(before);
  };

  const edits = {
    setBoundary(bc) {
      const before = JSON.parse(core().designJson()).boundary;
      onUndo(() => core().setBoundary(before));
      core().setBoundary(bc);
      core().factor();
      return true;
    },

    setGamma(g) {
      const before = core().gamma();
      onUndo(() => core().setGamma(before));
      core().setGamma(g);
      core().factor();
      return true;
    },

    // s ≥ 0 (0: off); the core refuses s > 0 for a vector field or an odd N.
    setCurvatureAlignment(s) {
      const before = core().curvatureAlignment();
      onUndo(() => core().setCurvatureAlignment(before));
      core().setCurvatureAlignment(s);
      return true;
    },

    // The symmetry N as one edit (session/commands/set-symmetry.js). The core refuses N ≥ 2 while the design
    // holds a constraint only a vector field has, so `remove` (their core ids) goes first; the curvature
    // alignment is set aside while N changes (odd N has none) and `curvatureAlignment` is what the new N gets;
    // `add` (specs: those an undo brings back) goes in last, under the new N. Returns the core ids of `add`.
    setSymmetry(n, { remove = [], curvatureAlignment = 0, add = [] } = {}) {
      const c = core();
      onUndo(restoreNow());
      for (const id of remove) c.remove(id);
      if (c.curvatureAlignment() > 0) c.setCurvatureAlignment(0);
      c.setSymmetry(n);
      if (curvatureAlignment > 0) c.setCurvatureAlignment(curvatureAlignment);
      return add.map((spec) => c.addConstraintJson(spec));
    },

    // The sharp features {angle (degrees; 0: none detected), add, remove ([[a, b], ...] vertex pairs)}; a key
    // left out keeps its value. A change of the system's base: the factor is made again.
    setFeatures(features = {}) {
      const before = core().features();
      onUndo(() => core().setFeatures(before));
      core().setFeatures({ ...before, ...features });
      core().factor();
      return true;
    },

    // true: the field has exactly the prescribed singularities (none when none are prescribed). The field system
    // may change kind (the prescribed one or the smoothest): it is factored again.
    setExactSingularities(exact) {
      const before = core().exactSingularities();
      onUndo(() => core().setExactSingularities(before));
      core().setExactSingularities(exact);
      core().factor();
      return true;
    },

    applyDesign(design) {
      onUndo(restoreNow());
      core().applyDesignJson(JSON.stringify(design));
      core().factor();
      return true;
    },
  };
  return { edits };
}

// The client's calls on the design's constraints (core-client.js composes them): one constraint in or out (a
// prescribed singularity added or moved), its weight and strength, the stored specs and the design document.
// A refusal comes back as -1 or false, with the core's reason in lastError(). Owns nothing; imports
// client/checks.js and core-error.js.
import { CoreError } from '../core-error.js';
import { check, guard, prefixed, requireNumber } from './checks.js';

// Base: a class whose instances hold the embind Designer as `designer` (core-client.js).
export const editCalls = (Base) =>
  class EditCalls extends Base {
    #id(what, id) {
      if (typeof id !== 'number' || id < 0) {
        const msg = guard(what, () => this.designer.lastError()) || 'rejected by the core';
        throw new CoreError(prefixed(what, msg));
      }
      return id;
    }

    // One constraint in the design format (docs/design-format.md): the only way constraints enter the core,
    // parsed by the same code as design files (new ones, and exact re-adds for undo).
    addConstraintJson(spec) {
      const json = JSON.stringify(spec);
      return this.#id('constraint', guard('constraint', () => this.designer.addConstraintJson(json)));
    }

    // Core ids in the core's order: that of designJson().constraints, with the prescribed singularities (which
    // the document lists apart, as "singularities") where they were added; constraintSpecs() lines up with it.
    constraintIds() {
      return JSON.parse(guard('constraints', () => this.designer.constraintIdsJson()));
    }

    // Every constraint's spec in constraintIds()' order, a singularity as {type: 'singularity', vertex, index}.
    constraintSpecs() {
      return JSON.parse(guard('constraints', () => this.designer.constraintsJson()));
    }

    // A prescribed singularity (index a nonzero multiple of 1/N at an interior vertex): its core id. The core's
    // refusal (a boundary vertex, a bad index, a vertex that has one) is a CoreError, the design unchanged.
    addSingularity(vertex, index) {
      requireNumber('add singularity: vertex', vertex);
      requireNumber('add singularity: index', index);
      const what = 'add singularity'; // the core's reason names the singularity ("singularity at vertex 3: ...")
      return this.#id(what, guard(what, () => this.designer.addSingularity(vertex, index)));
    }

    // The singularity `id` to another vertex, its id and index kept.
    moveSingularity(id, vertex) {
      requireNumber('move singularity: id', id);
      requireNumber('move singularity: vertex', vertex);
      const ok = guard('move singularity', () => this.designer.moveSingularity(id, vertex));
      if (!ok) throw new CoreError(prefixed('move singularity', this.#lastError() || `no singularity with id ${id}`));
    }

    remove(id) {
      requireNumber('remove: id', id);
      const ok = guard('remove', () => this.designer.remove(id));
      if (!ok) throw new CoreError(prefixed('remove', this.#lastError() || `no constraint with id ${id}`));
    }

    setWeight(id, weight) {
      requireNumber('weight: id', id);
      requireNumber('weight', weight);
      const ok = guard('weight', () => this.designer.setWeight(id, weight));
      if (!ok) throw new CoreError(prefixed('weight', this.#lastError() || `cannot reweight constraint ${id}`));
    }

    setStrength(id, strength) {
      requireNumber('strength: id', id);
      requireNumber('strength', strength);
      const ok = guard('strength', () => this.designer.setStrength(id, strength));
      if (!ok) {
        throw new CoreError(prefixed('strength', this.#lastError() || `cannot change the strength of ${id}`));
      }
    }

    #lastError() {
      try {
        return this.designer.lastError();
      } catch {
        return '';
      }
    }

    // One constraint in the design format, or null when there is no constraint `id`.
    constraint(id) {
      requireNumber('constraint: id', id);
      return JSON.parse(guard('constraint', () => this.designer.constraintJson(id)));
    }

    designJson() {
      return guard('design', () => this.designer.designJson());
    }

    applyDesignJson(json) {
      check('design', guard('design', () => this.designer.applyDesignJson(json)));
    }
  };

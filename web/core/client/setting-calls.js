// The client's calls on the design's settings (core-client.js composes them): the boundary condition, γ, the
// symmetry N, the curvature alignment, the sharp features, whether the field has only the prescribed
// singularities, and the model's info. Owns nothing; imports
// client/checks.js and core-error.js.
import { CoreError } from '../core-error.js';
import { check, guard, requireNumber } from './checks.js';

// Base: a class whose instances hold the embind Designer as `designer` (core-client.js).
export const settingCalls = (Base) =>
  class SettingCalls extends Base {
    gamma() {
      return guard('gamma', () => this.designer.gamma());
    }

    info() {
      return JSON.parse(guard('info', () => this.designer.infoJson()));
    }

    setBoundary(bc) {
      // 'free' | 'tangential' | 'normal' | {angle}: the core takes the JSON value, quotes included.
      const json = JSON.stringify(bc);
      check('boundary', guard('boundary', () => this.designer.setBoundaryJson(json)));
    }

    setGamma(gamma) {
      requireNumber('gamma', gamma);
      // setGamma returns nothing, or an error string in a stricter build.
      check('gamma', guard('gamma', () => this.designer.setGamma(gamma)));
    }

    symmetry() {
      return guard('symmetry', () => this.designer.symmetry());
    }

    // n: 1 a vector field, 2 a line field, 4 a cross field (the core takes 1..6, and refuses N ≥ 2 while a
    // source, sink, vortex or edge constraint is in the design). Embind would truncate 2.5 to 2 unseen: checked
    // here.
    setSymmetry(n) {
      if (!Number.isInteger(n)) {
        const got = typeof n === 'number' ? String(n) : n == null ? 'nothing' : JSON.stringify(n);
        throw new CoreError(`symmetry must be a whole number from 1 to 6 (got ${got})`);
      }
      check('symmetry', guard('symmetry', () => this.designer.setSymmetry(n)));
    }

    // Feature edges: those whose dihedral angle exceeds `angle` degrees (0: none), plus `add`, minus `remove`
    // ([[a, b], ...] vertex pairs). The core refuses a pair that is not an edge or an angle outside [0, 180].
    setFeatures({ angle = 0, add = [], remove = [] } = {}) {
      requireNumber('features: angle', angle);
      const flat = (what, pairs) => {
        if (!Array.isArray(pairs)) throw new CoreError(`features: ${what} must be a list of [a, b] vertex pairs`);
        return pairs.flatMap((p) => {
          if (!Array.isArray(p) || p.length !== 2 || !p.every((v) => typeof v === 'number'))
            throw new CoreError(`features: ${what} must be a list of [a, b] vertex pairs (got ${JSON.stringify(p)})`);
          return p;
        });
      };
      const plus = flat('add', add), minus = flat('remove', remove);
      check('features', guard('features', () => this.designer.setFeatures(angle, plus, minus)));
    }

    // true: the field has exactly the prescribed singularities, none when none are prescribed (a torus's cross
    // field without any); false: with none prescribed the smoothest field places its own.
    setExactSingularities(exact) {
      if (typeof exact !== 'boolean')
        throw new CoreError(`exactSingularities must be true or false (got ${JSON.stringify(exact) ?? 'nothing'})`);
      check('exact singularities', guard('exact singularities', () => this.designer.setExactSingularities(exact)));
    }

    exactSingularities() {
      return guard('exact singularities', () => this.designer.exactSingularities());
    }

    // {angle, add, remove} as set.
    features() {
      return JSON.parse(guard('features', () => this.designer.featuresJson()));
    }

    curvatureAlignment() {
      return guard('curvature alignment', () => this.designer.curvatureAlignment());
    }

    // s ≥ 0 (0: off): how strongly the field is pulled towards the principal curvature directions; for even N
    // only.
    setCurvatureAlignment(s) {
      requireNumber('curvature alignment', s);
      check('curvature alignment', guard('curvature alignment', () => this.designer.setCurvatureAlignment(s)));
    }
  };

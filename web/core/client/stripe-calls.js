// The client's stripe pattern calls (core-client.js composes them): the design's stripe pattern
// (core/design/design_stripes.h, Knöppel et al. 2015) of the field the page draws, kept in the core per model so
// that the next one starts from it, and its arrays for the GLB export. Owns nothing; imports client/checks.js.
import { check, guard } from './checks.js';

// Base: a class whose instances hold the embind Designer as `designer` (core-client.js).
export const stripeCalls = (Base) =>
  class StripeCalls extends Base {
    // vertexVectors: 3 per vertex (a Hodge part the page draws) or null (the design's own field); options:
    // {frequency, profile, magnitudeSpacing, ...} (design_stripes.h); interrupted: null, or a function the
    // core asks between its steps (true abandons the pattern). Returns the pattern's stats, or null when it
    // was abandoned (the last pattern stays).
    computeStripes(vertexVectors, options, interrupted = null) {
      const json = JSON.stringify(options ?? {});
      const call = () => this.designer.computeStripes(vertexVectors ?? null, json, interrupted);
      check('stripes', guard('stripes', call));
      if (this.designer.stripesInterrupted()) return null;
      return JSON.parse(guard('stripes', () => this.designer.stripeStatsJson()));
    }

    // The last pattern's arrays, copied out of the wasm heap: cornerPhase (families × 3 per face, family-major,
    // radians) and branchIndex (families per face, family-major).
    stripeArrays() {
      return guard('stripes', () => ({
        families: JSON.parse(this.designer.stripeStatsJson()).families,
        cornerPhase: this.designer.stripeCornerPhase().slice(),
        branchIndex: this.designer.stripeBranchIndex().slice(),
      }));
    }
  };

// The client's read-outs of the current model and field (core-client.js composes them): the mesh, the field
// arrays, the Hodge decomposition, a 1-form's reconstruction, the stats, the singularities and the feature
// edges. Views the core returns point into wasm memory and die at the next mutating call or memory growth, so
// everything handed out is a copy (slice(): one memcpy into a buffer of its own, which the worker can then
// transfer).
// Owns nothing; imports client/checks.js.
import { checkObject, guard } from './checks.js';

const sliceOf = (view) => view.slice();

// Base: a class whose instances hold the embind Designer as `designer` (core-client.js).
export const readOuts = (Base) =>
  class ReadOuts extends Base {
    mesh() {
      return guard('mesh', () => ({
        positions: this.designer.positions().slice(),
        triangles: this.designer.triangles().slice(),
      }));
    }

    // The field arrays, copied out of the wasm heap by `copy(view)` (a fresh array by default; the worker
    // passes one that refills a spare).
    faceVectors(copy = sliceOf) {
      return guard('faceVectors', () => copy(this.designer.faceVectors()));
    }

    vertexVectors(copy = sliceOf) {
      return guard('vertexVectors', () => copy(this.designer.vertexVectors()));
    }

    oneForm(copy = sliceOf) {
      return guard('oneForm', () => copy(this.designer.oneForm()));
    }

    edges() {
      return guard('edges', () => this.designer.edges().slice());
    }

    fieldJson() {
      return guard('field', () => this.designer.fieldJson());
    }

    // The Hodge decomposition (Eq. 3) of the current field, computed now by the core (two Poisson solves):
    // {exact, coexact, harmonic, metric (Float64Array per edge, oneForm's order), potential0 (per vertex),
    // potential2 (per face), metricName, milliseconds, energyShares: {exact, coexact, harmonic}}; arrays of
    // their own.
    hodge() {
      return checkObject('hodge', guard('hodge', () => this.designer.hodge()));
    }

    // Face and vertex vectors of a 1-form (Float64Array per edge, oneForm's order) by the core's own
    // reconstruction, the one the field's read-outs come from: {faceVectors, vertexVectors}, arrays of their own.
    reconstruct(oneForm) {
      return checkObject('reconstruct', guard('reconstruct', () => this.designer.reconstruct(oneForm)));
    }

    stats() {
      return JSON.parse(guard('stats', () => this.designer.statsJson()));
    }

    // [{vertex, index, prescribed}]: the field's singularities, each flagged when the design prescribes it.
    singularities() {
      return JSON.parse(guard('singularities', () => this.designer.singularitiesJson()));
    }

    // The edges the field follows as features (indices into edges(), ascending), an Int32Array of its own.
    featureEdges() {
      return guard('feature edges', () => this.designer.featureEdges().slice());
    }

    // The same edges as vertex pairs, flat ([a, b, a, b, ...]), read through the core's view of the edge list
    // (not a copy of it).
    featureEdgePairs() {
      return guard('feature edges', () => {
        const used = this.designer.featureEdges().slice();
        const pairs = new Int32Array(2 * used.length);
        const edges = this.designer.edges();
        for (let k = 0; k < used.length; k++) {
          pairs[2 * k] = edges[2 * used[k]];
          pairs[2 * k + 1] = edges[2 * used[k] + 1];
        }
        return pairs;
      });
    }
  };

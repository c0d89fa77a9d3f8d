// The parts of the worker's current field (core-worker.js): its Hodge decomposition c = dα + δβ + h (Eq. 3),
// made by the core on the first request for a field version and kept for every later request on that version,
// and each part's vectors, reconstructed by the core from the part's 1-form exactly as the field's are. Nothing
// is computed unless asked (edits never pay for it); the worker calls drop() at every solve.
import { CoreError } from './core-client.js';

export const COMPONENTS = ['whole', 'exact', 'coexact', 'harmonic'];

export class FieldParts {
  // core(): the worker's CoreClient now.
  constructor(core) {
    this.core = core;
    this.kept = null; // {version, value (core.hodge() plus decomposeMs), parts: Map name -> arrays}
  }

  drop() {
    this.kept = null;
  }

  // The decomposition of field `version` (the current one), computed now when it has none yet.
  decomposition(version) {
    if (this.kept?.version !== version) {
      const t = performance.now();
      const h = this.core().hodge();
      this.kept = { version, value: { ...h, decomposeMs: performance.now() - t }, parts: new Map() };
    }
    return this.kept;
  }

  // {oneForm, faceVectors, vertexVectors} of a part; 'whole': the field's own arrays (fresh copies). A part's
  // arrays are the kept ones: copy them before transferring.
  component(version, name) {
    if (!COMPONENTS.includes(name))
      throw new CoreError(`component: unknown component ${JSON.stringify(name)} (expected ${COMPONENTS.join(', ')})`);
    const core = this.core();
    if (name === 'whole') return { oneForm: core.oneForm(), faceVectors: core.faceVectors(), vertexVectors: core.vertexVectors() };
    const kept = this.decomposition(version);
    let part = kept.parts.get(name);
    if (!part) {
      const oneForm = kept.value[name];
      part = { oneForm, ...core.reconstruct(oneForm) };
      kept.parts.set(name, part);
    }
    return part;
  }

  // The `hodge` op's reply: copies of the kept arrays, and their buffers to transfer.
  hodgeReply(version) {
    const h = this.decomposition(version).value;
    const value = {
      exact: h.exact.slice(),
      coexact: h.coexact.slice(),
      harmonic: h.harmonic.slice(),
      innerProduct: h.metric.slice(),
      potential0: h.potential0.slice(),
      potential2: h.potential2.slice(),
      energyShares: { ...h.energyShares },
      metric: h.metricName,
      decomposeMs: h.decomposeMs,
    };
    const arrays = [value.exact, value.coexact, value.harmonic, value.innerProduct, value.potential0, value.potential2];
    return { value, list: arrays.map((a) => a.buffer) };
  }

  // The `hodgeShares` op's reply: what the shares line needs, without the per-edge arrays.
  sharesReply(version) {
    const { energyShares, decomposeMs } = this.decomposition(version).value;
    return { energyShares: { ...energyShares }, decomposeMs };
  }

  // The `component` op's reply, likewise.
  componentReply(version, name) {
    const part = this.component(version, name);
    const value = name === 'whole' ? part : {
      oneForm: part.oneForm.slice(),
      faceVectors: part.faceVectors.slice(),
      vertexVectors: part.vertexVectors.slice(),
    };
    return { value, list: [value.oneForm.buffer, value.faceVectors.buffer, value.vertexVectors.buffer] };
  }
}

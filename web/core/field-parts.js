// The parts of one version of the worker's field: its Hodge decomposition c = dα + δβ + h (Eq. 3), made by the
// core on the first request and kept for every later one, and each part's vectors, reconstructed by the core
// from the part's 1-form exactly as the field's are. Nothing is computed unless asked (edits never pay for it).
// Owned by the field version's derived-field object (worker/derived-field.js), which makes one on first request
// and is replaced, parts and all, at every solve. COMPONENTS is also the page's list of the parts it may show.
import { CoreError } from './core-error.js';

export const COMPONENTS = ['whole', 'exact', 'coexact', 'harmonic'];

export class FieldParts {
  // core: the worker's CoreClient, holding the field version these parts are of.
  constructor(core) {
    this.core = core;
    this.kept = null; // core.hodge() plus decomposeMs
    this.parts = new Map(); // name -> {oneForm, faceVectors, vertexVectors}
  }

  // The decomposition, computed now when it has none yet.
  decomposition() {
    if (!this.kept) {
      const t = performance.now();
      const h = this.core.hodge();
      this.kept = { ...h, decomposeMs: performance.now() - t };
    }
    return this.kept;
  }

  // {oneForm, faceVectors, vertexVectors} of a part; 'whole': the field's own arrays (fresh copies). A part's
  // arrays are the kept ones: copy them before transferring.
  component(name) {
    if (!COMPONENTS.includes(name))
      throw new CoreError(`component: unknown component ${JSON.stringify(name)} (expected ${COMPONENTS.join(', ')})`);
    const core = this.core;
    if (name === 'whole')
      return { oneForm: core.oneForm(), faceVectors: core.faceVectors(), vertexVectors: core.vertexVectors() };
    let part = this.parts.get(name);
    if (!part) {
      const oneForm = this.decomposition()[name];
      part = { oneForm, ...core.reconstruct(oneForm) };
      this.parts.set(name, part);
    }
    return part;
  }

  // The `hodge` op's reply: copies of the kept arrays, and their buffers to transfer.
  hodgeReply() {
    const h = this.decomposition();
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
  sharesReply() {
    const { energyShares, decomposeMs } = this.decomposition();
    return { energyShares: { ...energyShares }, decomposeMs };
  }

  // The `component` op's reply, likewise.
  componentReply(name) {
    const part = this.component(name);
    const value = name === 'whole' ? part : {
      oneForm: part.oneForm.slice(),
      faceVectors: part.faceVectors.slice(),
      vertexVectors: part.vertexVectors.slice(),
    };
    return { value, list: [value.oneForm.buffer, value.faceVectors.buffer, value.vertexVectors.buffer] };
  }
}

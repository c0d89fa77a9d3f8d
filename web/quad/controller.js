// SPDX-License-Identifier: GPL-2.0-or-later
// The quad mesh of one designer: the target (an edge length or a number of quads), the run (started on a worker
// of its own, run.js; its stage and fraction; cancelled by ending that worker), the result and whether it is still
// the design's. Remeshing is no design edit: no command, no history entry, nothing saved with the design. The
// quad mesh is derived from one field version and goes stale when the field changes: it stays drawn, and the
// panel says so. Another model drops it. Owns its QuadView; imports its own folder.
import { quadGlb, quadObj } from './quad-files.js';
import { remeshTarget } from './quad-mesh.js';
import { CANCELLED } from './run.js';

// The one refusal of a field that is not a cross field, the API's rejection and the panel's line alike.
export const QUAD_REFUSAL = 'Quad meshes need a cross field';
export const DEFAULT_TARGET = { quads: 5000 };

const copyMesh = (m) => ({
  positions: m.positions.slice(),
  faceStart: m.faceStart.slice(),
  faceVertices: m.faceVertices.slice(),
  irregular: m.irregular.slice(),
});

export class QuadController {
  // view: a QuadView (quad-view.js) or null; getInput(): resolves to {positions, triangles, faceDirections (copies),
  // featureEdges (vertex pairs, flat), symmetry, version (the field's)} of the field now, or null without a model;
  // symmetry(): the design's N now; fieldVersion(): the field's version now; startRun(input, options, onProgress)
  // → {promise, cancel} (run.js); modelName(): the model's name; onChange(): the state changed (the panel redraws).
  constructor({
    view = null, getInput, symmetry, fieldVersion, startRun, modelName = () => 'model', onChange = () => {},
  }) {
    this.view = view;
    this.getInput = getInput;
    this.symmetry = symmetry;
    this.fieldVersion = fieldVersion;
    this.startRun = startRun;
    this.modelName = modelName;
    this.onChange = onChange;
    this.target = { ...DEFAULT_TARGET };
    this.visible = true;
    this.run = null; // {cancel, stage, fraction} of the run in flight
    this.result = null; // {mesh, stats, version} of the last run that finished
    this.stale = false;
    this.error = null;
  }

  state() {
    return {
      running: !!this.run,
      stage: this.run?.stage ?? null,
      fraction: this.run?.fraction ?? 0,
      target: { ...this.target },
      visible: this.visible,
      hasResult: !!this.result,
      stale: this.stale,
      stats: this.result ? { ...this.result.stats } : null,
      error: this.error,
    };
  }

  // target: {edgeLength} | {quads}, checked; the panel's next Remesh uses it.
  setTarget(target) {
    this.target = remeshTarget(target, 'setTarget');
    this.onChange();
  }

  setVisible(visible) {
    this.visible = !!visible;
    this.view?.setVisible(this.visible);
    this.onChange();
  }

  // Remeshes the current field (options: {edgeLength} | {quads}, default the panel's target, which it becomes).
  // Resolves with copies of the mesh and its stats; rejects with an Error naming the reason: QUAD_REFUSAL for a
  // field that is not a cross field, the core's words for a mesh it cannot remesh, CANCELLED after cancel().
  // A remesh while one runs replaces it (which rejects with CANCELLED).
  async remesh(options) {
    const target = options === undefined ? { ...this.target } : remeshTarget(options);
    this.target = target;
    if (this.symmetry() !== 4) {
      this.error = QUAD_REFUSAL;
      this.onChange();
      throw new Error(QUAD_REFUSAL);
    }
    if (this.run) this.#end();
    const run = { cancel: () => false, stage: 'starting', fraction: 0 };
    this.run = run;
    this.error = null;
    this.onChange();
    try {
      const input = await this.getInput();
      if (this.run !== run) throw new Error(CANCELLED);
      if (!input) throw new Error('remesh: no model is loaded');
      if (input.symmetry !== 4) throw new Error(QUAD_REFUSAL);
      const { positions, triangles, faceDirections } = input;
      const options = { ...target, symmetry: input.symmetry, featureEdges: input.featureEdges ?? [] };
      const started = this.startRun({ positions, triangles, faceDirections }, options,
        ({ stage, fraction }) => {
          if (this.run !== run) return;
          run.stage = stage;
          run.fraction = fraction;
          this.onChange();
        });
      run.cancel = started.cancel;
      const value = await started.promise;
      if (this.run !== run) throw new Error(CANCELLED);
      this.run = null;
      this.#adopt(value, input);
      return { ...copyMesh(this.result.mesh), stats: { ...this.result.stats } };
    } catch (err) {
      if (this.run === run) {
        this.run = null;
        this.error = err.message === CANCELLED ? null : err.message;
        this.onChange();
      }
      throw err instanceof Error ? err : new Error(String(err));
    }
  }

  #adopt(value, input) {
    const { positions, faceStart, faceVertices, irregular, stats, derived } = value;
    this.result = { mesh: { positions, faceStart, faceVertices, irregular }, stats, version: input.version };
    // The field may have changed while the run was out: the mesh is of the field it was given.
    this.stale = this.fieldVersion() !== input.version;
    this.error = null;
    this.view?.setMesh(this.result.mesh, { edgeLength: stats.edgeLength, stale: this.stale, derived });
    this.onChange();
  }

  // Stops the run in flight (its worker ended at once); its remesh() rejects with CANCELLED. The last quad mesh,
  // if any, stays. Returns whether a run was in flight.
  cancel() {
    if (!this.run) return false;
    this.#end();
    this.onChange();
    return true;
  }

  #end() {
    const run = this.run;
    this.run = null;
    run.cancel();
  }

  // The field has a new version (fieldchange): a quad mesh of an earlier one is stale.
  // The panel redraws either way: whether Remesh can work depends on the field's symmetry.
  fieldChanged() {
    if (this.result && !this.stale && this.fieldVersion() !== this.result.version) {
      this.stale = true;
      this.view?.setStale(true);
    }
    this.onChange();
  }

  // Another model: its quad mesh and any run for the previous one go.
  modelChanged() {
    if (this.run) this.#end();
    this.result = null;
    this.stale = false;
    this.error = null;
    this.view?.clear();
    this.onChange();
  }

  #requireResult(what) {
    if (!this.result) throw new Error(`${what}: there is no quad mesh yet (remesh first)`);
    return this.result;
  }

  // The quad mesh's polygons as OBJ text (quad-files.js).
  exportObj() {
    return quadObj(this.#requireResult('exportQuadObj').mesh, { name: this.modelName() });
  }

  // A triangulated copy as a GLB (an ArrayBuffer).
  exportGlb() {
    return quadGlb(this.#requireResult('exportQuadGlb').mesh, { name: `${this.modelName()} quad mesh` });
  }

  dispose() {
    if (this.run) this.#end();
    this.view?.dispose();
  }
}

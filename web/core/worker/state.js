// The core worker's state (one worker per <tangent-field-designer> element, so one state per element): the
// served core, the current field version's derived data, the mesh's Surface, the big model's preview steps,
// the request in flight and how to take its edit back. The op groups (edit-ops.js, load-ops.js, preview-ops.js,
// read-ops.js, hooks.js, synthesis/worker-ops.js) read and set it; dispatch.js runs the requests over it.
// Imports geometry/ for the Surface.
import { Surface } from '../../geometry/surface.js';
import { CoreError } from '../core-error.js';
import { SpareArrays } from '../spare-arrays.js';
import { DerivedField } from './derived-field.js';

export class WorkerState {
  // scope: the worker's global (self), or a stand-in with postMessage (tests).
  constructor(scope) {
    this.scope = scope;
    this.core = null; // the CoreClient, once `init` has loaded it
    this.coreExport = null;
    this.meshSurface = null; // built on first use, per mesh
    this.meshSerial = 0; // one more at every new mesh
    this.deferredFor = null; // the seq of the edit whose update the factor holds beside it, until put in
    // The field's version: one more after every solve the page is told about. Requests for derived read-outs
    // name the version they are for, so a reply never pairs one field with another field's read-outs.
    this.field = this.#derived(0);
    this.spares = new SpareArrays(); // earlier field arrays the page handed back, refilled rather than allocated
    // In a preview worker (progressive-core.js): the coarse stand-in of the page's big mesh, else null.
    this.preview = null;
    this.warming = null;
    this.prepared = null; // the big model's coarse stand-in and map, until its preview opens
    this.previewMade = () => {}; // what a big model's load waits for before factoring
    // The page's count of the requests it sent that rank above a background one (core-proxy.js), shared memory
    // where the page is cross-origin isolated (else null): a long background op gives way when it moves.
    this.interrupts = null;
    this.beginRequest(0);
  }

  // A request starts: its `progress` messages carry its seq (the page routes them to its caller, core-proxy.js).
  // undoEdit: how to take back the edit in flight when the solve after it fails (a factor that does not fit, a
  // field that is not finite), so that the core then holds exactly what it held before; set by each edit.
  // changedIds: the core ids whose entry in the design the edit changed; null: the whole document.
  // mark: the page's interrupt count when it sent this request (core-proxy.js), or undefined.
  beginRequest(seq, mark) {
    this.seq = seq;
    this.mark = mark;
    this.undoEdit = null;
    this.changedIds = null;
  }

  // For the request in flight: a function that says whether the page has sent a request that ranks above it
  // since (the stripe pattern's steps ask it), or null where the page cannot say.
  interruption() {
    const { interrupts, mark } = this;
    if (!interrupts || !Number.isInteger(mark)) return null;
    return () => Atomics.load(interrupts, 0) !== mark;
  }

  progress(value, list = []) {
    this.scope.postMessage({ seq: this.seq, progress: value }, list);
  }

  requireMesh() {
    if (!this.core?.hasMesh) throw new CoreError('no mesh loaded');
  }

  // The mesh's geometry and adjacency (geometry/surface.js), built once per mesh.
  surface() {
    if (!this.meshSurface) {
      const mesh = this.core.mesh();
      this.meshSurface = new Surface(mesh.positions, mesh.triangles, this.core.edges());
    }
    return this.meshSurface;
  }

  // A new mesh is current: the previous one's Surface goes.
  meshChanged() {
    this.meshSurface = null;
    this.meshSerial++;
  }

  // The field has a new version (snapshot.js): what was derived from the previous one goes with it.
  nextField() {
    this.field = this.#derived(this.field.version + 1);
    return this.field;
  }

  #derived(version) {
    return new DerivedField(version, () => this.core, () => this.surface());
  }
}

// The client's calls that open a model (core-client.js composes them): a mesh alone, a whole model at once, or a
// model in steps for a preview (worker/load-ops.js, open-steps.js). Any failure leaves the current model as it
// was. Meshes handed out are copies (slice()): the core's views die at its next mutating call.
// Owns nothing; imports client/checks.js and core-error.js.
import { CoreError } from '../core-error.js';
import { check, guard, prefixed } from './checks.js';

// Base: a class whose instances hold the embind Designer as `designer` (core-client.js).
export const modelCalls = (Base) =>
  class ModelCalls extends Base {
    // bytes: Uint8Array; format: 'glb' | 'gltf' | 'obj' | 'off' | 'ply' | '' (sniff). On failure the core
    // keeps its previous mesh and this throws with the core's message.
    loadMesh(bytes, format) {
      check('load', guard('load', () => this.designer.loadMesh(bytes, format)));
      this.hasMesh = true;
    }

    // The whole model change at once (mesh, settings {boundary, gamma, symmetry, curvatureAlignment}, an
    // autosaved design or null), factored and solved before it replaces the current model; on any failure the
    // current model stays as it was.
    // Returns {settingsError, restoreError} (null or the reason that part was dropped).
    loadModel(bytes, format, settings = null, design = null) {
      const settingsJson = settings ? JSON.stringify(settings) : '';
      const designJson = design ? JSON.stringify(design) : '';
      const out = JSON.parse(guard('load', () => this.designer.loadModel(bytes, format, settingsJson, designJson)));
      if (!out.ok) throw new CoreError(prefixed('load', out.error));
      this.hasMesh = true;
      return { settingsError: out.settingsError, restoreError: out.restoreError };
    }

    // loadModel in steps (big meshes): readModel parses the file ({vertices, faces}) and parsedMesh copies its
    // positions and triangles, so that a preview can start on them; openParsed checks and configures it as the
    // next model, aside ({settingsError, restoreError}); pendingInfo/pendingMesh/pendingDesign read it;
    // commitModel factors, solves and makes it current ({restoreError}: a design the solve could not take).
    readModel(bytes, format) {
      const out = JSON.parse(guard('load', () => this.designer.readModel(bytes, format)));
      if (!out.ok) throw new CoreError(prefixed('load', out.error));
      return { vertices: out.vertices, faces: out.faces };
    }

    parsedMesh() {
      return {
        positions: this.designer.parsedPositions().slice(),
        triangles: this.designer.parsedTriangles().slice(),
      };
    }

    openParsed(settings = null, design = null) {
      const settingsJson = settings ? JSON.stringify(settings) : '';
      const designJson = design ? JSON.stringify(design) : '';
      const out = JSON.parse(guard('load', () => this.designer.openParsed(settingsJson, designJson)));
      if (!out.ok) throw new CoreError(prefixed('load', out.error));
      return { settingsError: out.settingsError, restoreError: out.restoreError };
    }

    commitModel() {
      const out = JSON.parse(guard('load', () => this.designer.commitModel()));
      if (!out.ok) throw new CoreError(prefixed('load', out.error));
      this.hasMesh = true;
      return { restoreError: out.restoreError };
    }

    pendingInfo() {
      return JSON.parse(guard('info', () => this.designer.pendingInfoJson()));
    }

    pendingDesign() {
      return JSON.parse(guard('design', () => this.designer.pendingDesignJson()));
    }

    // Copies (transferable) of the opened model's welded mesh.
    pendingMesh() {
      const d = this.designer;
      return {
        positions: d.pendingPositions().slice(),
        triangles: d.pendingTriangles().slice(),
        edges: d.pendingEdges().slice(),
      };
    }
  };

// The composition root of one <tangent-field-designer>: builds the session (the model), the viewer, the
// panels, the tools, texture synthesis and export, and subscribes them to the session's signals. Nothing
// below this module knows the others exist; everything that connects them is here or in the two action
// tables (panel-actions.js, tool-actions.js).
import { panelActions } from './panel-actions.js';
import { toolActions } from './tool-actions.js';
import { bindUi } from './ui.js';
import { ViewSync } from './view-sync.js';
import { setupExport } from '../export/index.js';
import { baseName } from '../session/documents.js';
import { setupQuad } from '../quad/index.js';
import { Session } from '../session/session.js';
import { setupStripes } from '../stripes/index.js';
import { prepareAtlasAhead, prepareProgramsAhead, setupSynthesis } from '../synthesis/index.js';
import { ToolController } from '../tools/tools.js';
import { setPivotAt } from '../views/camera.js';
import { Viewer } from '../views/viewer.js';

const PROGRESS_LABELS = {
  loadMesh: 'Reading the model…',
  exactFactor: 'Preview shown; computing the exact field…',
  setBoundary: 'Refactoring…',
  setGamma: 'Refactoring…',
  setSymmetry: 'Refactoring…',
  setCurvatureAlignment: 'Solving…',
  applyDesign: 'Applying the design…',
  fieldJson: 'Exporting…',
  exportFlowMap: 'Exporting the flow map…',
  exportGlb: 'Exporting the GLB…',
};

// The session's signals that are the element's public events (docs/js-api.md).
const PUBLIC_EVENTS = ['load', 'fieldchange', 'constraintschange', 'corerestart', 'autosaveconflict', 'error'];

export class Designer {
  // host: the element (events are dispatched on it); root: its shadow root (markup already in place);
  // assetBase: URL of the folder with core-worker.js and wasm/; autosave: storage key or null (off);
  // bench: run the synthesis benchmark when the page asks for it (the app page only); onTool(name): the user
  // picked a tool; onSettings(settings): the design's settings after every change (the element reflects some).
  constructor({ host, root, assetBase, autosave = null, bench = false, onTool = () => {}, onSettings = () => {} }) {
    this.host = host;
    this.onTool = onTool;
    this.onSettings = onSettings;
    this.textureView = false; // the `texture` view is on: synthesize after every model load
    const $ = (sel) => root.querySelector(sel);
    const container = $('#viewport');
    const session = (this.session = new Session({ assetBase, autosave }));
    this.viewer = new Viewer(container);
    this.ui = bindUi(root, host, panelActions(this));
    this.tools = new ToolController(this.viewer, container, toolActions(this), () => session.readonly);
    // Double-click (double-tap) on the model: orbit around that point from now on.
    this.viewer.canvas.addEventListener('dblclick', (e) => setPivotAt(this.viewer, e.clientX, e.clientY));
    this.viewSync = new ViewSync({ session, viewer: this.viewer, ui: this.ui });
    this.viewSync.apply(this.ui.views());
    this.textureApi = {};
    this.synthesis = this.#setupSynthesis($('#side-panel'), bench);
    this.stripes = this.#setupStripes($('#side-panel'));
    this.quad = this.#setupQuad($('#side-panel'), assetBase);
    // The texture and the stripes follow the field drawn.
    this.viewSync.onRefreshed = () => {
      this.synthesis.fieldChanged();
      this.stripes.fieldChanged();
    };
    // The field's frame waits for the texture or the stripes that follow it, whichever is shown.
    this.viewSync.frameMayWait = () => Math.max(this.synthesis.followsWithin(), this.stripes.followsWithin());
    this.exports = setupExport({
      viewer: this.viewer,
      panel: $('#side-panel'),
      call: (op, args) => session.request(op, args, { exclusive: true }),
      modelName: () => baseName(session.modelName),
      onError: (err) => !session.disposed && this.ui.showError(err.message),
      // The one GLB export embeds the stripes when they are shown, else the synthesized texture when there is one.
      texture: this.synthesis,
      stripes: this.stripes,
      symmetry: () => session.field?.symmetry ?? 1,
    });
    this.#subscribe();
  }

  // Texture synthesis (web/synthesis/, docs/texture-synthesis.md): its calls go onto the element.
  #setupSynthesis(panel, bench) {
    const s = this.session;
    return setupSynthesis(this.textureApi, {
      viewer: this.viewer,
      panel,
      bench: bench ? this.host : null,
      onError: (err) => s.fail('texture', err),
      // The Texture panel's GLB button is the Export panel's download (set up just after this).
      downloadGlb: () => this.exports.downloadGlb(),
      computeAtlas: ({ positions, triangles, cornerUVs }, options) =>
        s.request('textureAtlas', [positions, triangles, cornerUVs ?? null, options]),
      // An exemplar may be chosen before the core has started: the analysis waits for it.
      analyzeExemplar: async (spec) => {
        await s.coreStarted;
        return s.request('analyzeExemplar', [spec]);
      },
      getFieldVersion: () => (s.surface && s.field ? this.viewSync.drawnVersion() : undefined),
      isPreviewField: () => !!s.field?.stats?.preview,
      getModel: () =>
        s.surface && s.field
          ? {
              key: `${s.modelKey}#${s.meshSerial}`,
              name: s.modelName,
              positions: s.surface.positions,
              triangles: s.surface.triangles,
              // The mesh's derived geometry (normals, areas, adjacency, angle defects), computed once per mesh.
              surface: s.surface,
              cornerUVs: s.cornerUVs,
              // The field the views draw (the whole field or the Hodge component chosen in the Views panel), as
              // the texture reads it, a copy: synthesis holds it across awaits, and the session's own array goes
              // back to the worker once a newer field replaces it. N = 1: #textureVectorField(); N ≥ 2: the vertex
              // representatives of a line or cross field, which synthesis combs per chart starting from the
              // core's own face representatives.
              ...((s.field.symmetry ?? 1) === 1
                ? this.#textureVectorField()
                : {
                    vertexVectors: this.viewSync.drawnVertexVectors().slice(),
                    faceVectors: s.field.faceVectors.slice(),
                  }),
              fieldVersion: this.viewSync.drawnVersion(),
              symmetry: s.field.symmetry ?? 1,
            }
          : null,
    });
  }

  // A vector field as the texture reads it, a copy: its 1-form, whose Whitney field the texture follows per
  // texel; a big model's preview, known by its vertex vectors alone, by those (linear over each face, as the
  // preview gives it): deriving its 1-form on the page held armadillo-sub2's update 140 ms in one task.
  #textureVectorField() {
    const sync = this.viewSync, known = sync.drawnOneForm({ derive: false });
    if (known || !this.session.field.stats?.preview) return { oneForm: (known ?? sync.drawnOneForm()).slice() };
    return { vertexVectors: sync.drawnVertexVectors().slice() };
  }

  // Stripe patterns (web/stripes/, docs/stripes.md): of the field the views draw, made in the core's worker.
  #setupStripes(panel) {
    const s = this.session;
    return setupStripes({
      viewer: this.viewer,
      panel,
      onError: (err) => s.fail('stripes', err),
      call: async (op, args) => (await s.proxy.call(op, args, [], { background: true })).value,
      notify: (message) => s.proxy?.notify(message),
      getField: () => {
        const drawn = this.viewSync.drawn;
        if (!s.surface || !s.field) return null;
        const derived = drawn?.derived ?? s.field;
        const component = drawn?.name ?? 'whole';
        const symmetry = s.field.symmetry ?? 1;
        const preview = !!s.field.stats?.preview; // a big model's preview field: its stripes wait for the exact one
        return { version: derived.version, component, key: this.viewSync.drawnVersion(), symmetry, surface: s.surface,
          preview };
      },
      // Shown, they take the texture's place; hidden, they give it back.
      onShow: (shown) => this.synthesis.setTextureVisible(!shown && this.synthesis.active),
    });
  }

  // Quad meshes from the cross field (web/quad/): each remesh runs on a worker of its own, never the core's, and
  // is no edit: the session only hands over the mesh and the field as they are.
  #setupQuad(panel, assetBase) {
    const s = this.session;
    return setupQuad({
      viewer: this.viewer,
      panel,
      assetBase,
      symmetry: () => s.field?.symmetry ?? 1,
      fieldVersion: () => s.fieldVersion,
      area: () => s.surface?.area ?? 0,
      modelName: () => baseName(s.modelName),
      onError: (err) => !s.disposed && this.ui.showError(err.message),
      getInput: async () => {
        if (s.field?.stats?.preview) await s.settled(); // the exact field, not a big model's preview of it
        if (!s.surface || !s.field) return null;
        return {
          positions: s.surface.positions.slice(),
          triangles: s.surface.triangles.slice(),
          faceDirections: s.fieldArray('faceVectors').slice(),
          featureEdges: Array.from(s.field.featureEdges ?? []), // vertex pairs, flat: the quads' edges follow them
          symmetry: s.field.symmetry ?? 1,
          version: s.fieldVersion,
        };
      },
    });
  }

  // After a model is shown, as the session warms the design's calls up: the model's texture atlas prepared
  // in the core's worker (synthesis/atlas-ahead.js), then the synthesis programs compiled, or for a model too
  // big for that, once, the texture's CPU half warmed up on a torus (synthesis/warm-up.js: ~0.27 s there; the
  // first texture's atlas choice for bunny00 665 -> 436 ms, under node). Never fails anything: an optimization
  // only.
  #prepareTextureLater() {
    const s = this.session;
    setTimeout(async () => {
      if (s.disposed || !s.surface) return;
      const { positions, triangles } = s.surface;
      const request = (op, args) => s.request(op, args);
      const model = { positions, triangles, cornerUVs: s.cornerUVs };
      const prepared = await prepareAtlasAhead(request, this.synthesis, model).catch(() => null);
      if (prepared && !s.disposed) prepareProgramsAhead(this.synthesis);
      if (prepared !== false || this.textureWarmed || s.disposed) return;
      this.textureWarmed = true;
      s.request('warmUpTexture').catch(() => {});
    }, 0);
  }

  #subscribe() {
    const s = this.session, ui = this.ui, viewer = this.viewer;
    for (const type of PUBLIC_EVENTS) s.on(type, (detail) => this.#dispatch(type, detail));
    s.on('error', ({ message }) => ui.showError(message));
    s.on('banner', ({ message, action }) => ui.showError(message, action));
    s.on('banner-clear', () => ui.clearError());
    s.on('flash', ({ text, ms }) => ui.flash(text, ms));
    s.on('load', () => this.#prepareTextureLater());
    s.on('settings', (settings) => {
      ui.setSettings(settings);
      this.onSettings(settings);
    });
    s.on('history', () => this.viewSync.refreshHistory());
    s.on('selection', (uid) => this.viewSync.selectionChanged(uid));
    s.on('model', (model) => {
      this.viewSync.modelChanged(model);
      this.synthesis.modelChanged(); // the model's UVs and a fresh atlas for the new mesh
      this.stripes.modelChanged();
      this.quad.modelChanged(); // a quad mesh is of one model
    });
    // A big model's mesh goes to the GPU ahead of its field; perf().meshUploads counts the tasks it took.
    s.on('surface', (staged) => {
      staged.ready = this.viewer.stageMesh(staged.surface).then((n) => (s.perf.meshUploads = n));
    });
    s.on('change', () => {
      this.viewSync.refresh();
      this.onSettings(s.settings());
    });
    s.on('fieldchange', () => {
      this.exports.fieldChanged();
      this.quad.fieldChanged(); // a quad mesh of an earlier field is stale
    });
    const ends = new Map();
    s.on('busy', ({ op, done, phase }) => {
      if (phase) return void ends.get(op)?.end.relabel(phase);
      if (!done) {
        ends.set(op, { end: ui.startProgress(PROGRESS_LABELS[op] ?? 'Updating…'), renders: viewer.renderCount });
        return void this.#dispatch('progress', { phase: op, fraction: 0 });
      }
      const started = ends.get(op);
      ends.delete(op);
      started?.end();
      // Frames the page drew while the worker computed: the page never waits for the core.
      if (started && s.perf.lastOp?.op === op)
        s.perf.lastOp.framesDrawnMeanwhile = viewer.renderCount - started.renders;
      this.#dispatch('progress', { phase: op, fraction: 1 });
    });
  }

  #dispatch(type, detail) {
    if (this.session.disposed) return;
    this.host.dispatchEvent(new CustomEvent(type, { detail, bubbles: true, composed: true }));
  }

  start() {
    return this.session.exclusive(() => this.session.start());
  }

  // Ends the worker and frees the WebGL contexts; the element is dead afterwards.
  dispose() {
    if (this.session.disposed) return;
    this.session.dispose();
    this.synthesis.dispose();
    this.stripes.dispose();
    this.quad.dispose();
    this.exports.dispose();
    this.tools.dispose();
    this.ui.dispose();
    this.viewer.dispose();
  }

  // Surfaces any failure of a UI-started action in the banner; the API variants reject instead. The panels
  // are redrawn from the state so an input the core refused shows the value in force again.
  report(promise) {
    return promise.catch((err) => {
      if (this.session.disposed) return;
      this.ui.showError(err.message);
      this.session.changed();
    });
  }

  // Time from a user action to the frame that shows its result (reported through perf()).
  async #timed(name, t0, promise) {
    const result = await promise;
    // The redraw was synchronous; the next animation frame puts it on screen.
    const shown = await new Promise((resolve) => requestAnimationFrame(() => resolve(performance.now())));
    const perf = this.session.perf, op = perf.lastOp ?? {};
    const { workerMs, workerParts, roundTripMs } = op;
    perf[name] = { toFrameMs: shown - t0, workerMs, workerParts, roundTripMs, refresh: perf.refresh };
    return result;
  }

  edit(name, promise) {
    return this.report(this.#timed(name, performance.now(), promise));
  }
}

// Session → views: after every 'change' the field, the constraints and the settings go to the viewer and the
// panels, drawn synchronously; the views that are off get nothing. Owns the view options (which views are on,
// arrow density, streamline spacing, the Hodge component drawn) and what was drawn; what is derived from a
// field for them (the magnitude scale, the singularities, the streamlines, traced in the worker and on the page
// only when read before they arrive, the component of the decomposition c = dα + δβ + h and its energy shares)
// is asked of the field itself (session.field, session/derived-field.js), which keeps it.
//
// The component (views.component, 'whole' by default): with 'whole' the views draw the session's field and
// nothing more is asked of the worker. Otherwise, after each change, the worker is asked in the background for
// `component(version, name)` (and `hodgeShares(version)` for the energy shares, shown while a part is chosen);
// one request of each kind is in flight at a time, and a reply for a field that is no longer current is not
// drawn.
// Until the part of the current field arrives the arrows, colours, flow texture and streamlines keep showing
// what they showed (never a mix of versions); then they all draw it, in the whole field's magnitude scale
// (a small part looks small). The singularity markers stay the whole field's.
//
// Every view is told the field's symmetry N (session.field.symmetry: 1 a vector field, 2 a line field, 4 a cross
// field): for N ≥ 2 the vectors are unit representatives, one of N directions, which the views draw as such.
// Such a field has no 1-form and so no decomposition: the views draw the whole field whatever component is chosen.
import { COMPONENTS } from '../core/field-parts.js';

export class ViewSync {
  constructor({ session, viewer, ui }) {
    this.session = session;
    this.viewer = viewer;
    this.ui = ui;
    this.views = { component: 'whole' };
    this.shown = { singularities: -1, vertexField: null }; // what those views were last given (version / key)
    // The field drawn now: {key, name, fieldVersion, derived (its DerivedField), field: {faceVectors,
    // vertexVectors, scale}}.
    this.drawn = null;
    this.sharesShown = null; // the energy shares last received, which the panel shows until newer ones come
    this.inFlight = { component: false, hodgeShares: false };
    this.requests = { component: 0, hodgeShares: 0 }; // requests sent to the worker (perf().hodgeViews)
    this.onRefreshed = () => {}; // after each redraw (texture synthesis follows the field)
    this.frameMayWait = () => 0; // ms a field's frame may wait for what follows it (0: drawn at once)
    this.panelsOwed = false; // the panels wait to be shown with a frame that waits (refresh)
  }

  // ---- the field the views draw

  // The field of the current version and component, or null while the part is still to come.
  #target() {
    const s = this.session, name = this.#component(), derived = s.field, fieldVersion = s.fieldVersion;
    if (name === 'whole') {
      const { faceVectors, vertexVectors } = derived;
      const field = { faceVectors, vertexVectors, scale: derived.requireMagnitudes() };
      return { key: fieldVersion, name, fieldVersion, derived, field };
    }
    const field = derived.hodgePart(name);
    return field ? { key: `${fieldVersion}:${name}`, name, fieldVersion, derived, field } : null;
  }

  // What the views draw now (the synthesized texture follows it): its per-vertex vectors and a key that changes
  // whenever they do (the session's field version for the whole field).
  drawnVertexVectors() {
    return this.drawn?.field.vertexVectors ?? this.session.field.vertexVectors;
  }

  // The drawn field's 1-form (N = 1): a part's own, or the whole field's (derived from a preview's vectors, or,
  // with derive false, null where it would have to be).
  drawnOneForm({ derive = true } = {}) {
    const d = this.drawn, field = d?.derived ?? this.session.field;
    return d?.field.oneForm ?? (derive ? field.requireOneForm() : field.oneForm ?? null);
  }

  drawnVersion() {
    return this.drawn?.key ?? this.session.fieldVersion;
  }

  // The N of the current field (the parts of its decomposition share it).
  #symmetry() {
    return this.session.field?.symmetry ?? 1;
  }

  // The component drawn: the one chosen, or the whole field when there is no decomposition (N ≥ 2).
  #component() {
    return this.#symmetry() > 1 ? 'whole' : (this.views.component ?? 'whole');
  }

  #draw(target) {
    const f = target.field;
    this.drawn = target;
    const hv = this.session.perf.hodgeViews;
    this.session.perf.hodgeViews = { ...hv, drawn: { component: target.name, fieldVersion: target.fieldVersion } };
    this.viewer.arrows.setField(f.faceVectors, f.vertexVectors, f.scale, this.#symmetry());
    this.#showDerived();
  }

  // ---- the decomposition, asked of the worker only while a part or the shares are shown

  #requestParts() {
    const s = this.session, name = this.#component(), field = s.field;
    if (name === 'whole' || !field || s.disposed) return;
    if (!field.hodgePart(name) && !this.inFlight.component) {
      const ask = () => s.request('component', [field.version, name]);
      this.#ask('component', () => field.requireHodgePart(name, ask), (_, t) => this.#partArrived(t));
    }
    if (!field.energyShares() && !this.inFlight.hodgeShares) {
      const ask = () => s.request('hodgeShares', [field.version]);
      this.#ask('hodgeShares', () => field.requireEnergyShares(ask), (value, t) => {
        this.sharesShown = value.energyShares;
        const roundTripMs = performance.now() - t.t0;
        s.perf.hodge = { decomposeMs: value.decomposeMs, roundTripMs, fieldVersion: t.fieldVersion };
        this.#showShares();
      });
    }
  }

  // One background request (request(): the field's promise of what it asked the worker for); the reply is
  // used only when it is for the field still current.
  #ask(op, request, use) {
    const s = this.session, name = this.views.component;
    const t = { field: s.field, fieldVersion: s.fieldVersion, surface: s.surface, name, t0: performance.now() };
    this.inFlight[op] = true;
    this.requests[op]++;
    s.perf.hodgeViews = { ...s.perf.hodgeViews, requests: { ...this.requests } };
    request()
      .then((value) => {
        if (value && !s.disposed && s.field === t.field && s.surface === t.surface) use(value, t);
      })
      // A restarted worker: the refresh after the restart asks again.
      .catch((err) => void (s.perf.hodgeViews = { ...s.perf.hodgeViews, lastError: `${op}: ${err?.message ?? err}` }))
      .finally(() => {
        this.inFlight[op] = false;
        // Asked meanwhile for another field or part: asked now (not again for the same, should it have failed).
        const otherPart = op === 'component' && this.views.component !== name;
        const moved = s.field !== t.field || s.surface !== t.surface || otherPart;
        if (moved && !s.disposed && s.field) this.#requestParts();
      });
  }

  // The part is the field's now (DerivedField.requireHodgePart).
  #partArrived({ name, ...t }) {
    const s = this.session;
    s.perf.component = { name, roundTripMs: performance.now() - t.t0, fieldVersion: t.fieldVersion };
    if (this.#component() !== name) return;
    this.#draw(this.#target());
    this.#scheduleStreamlines();
    this.viewer.requestRender();
    this.onRefreshed();
  }

  #showShares() {
    const sh = this.sharesShown, on = this.#component() !== 'whole';
    const current = !!sh && sh === this.session.field?.energyShares();
    // The last shares known stay until the new ones come (the panel marks them as of an earlier field).
    this.ui.setViews({ shares: on && sh ? { ...sh, current } : null });
  }

  // ---- streamlines

  #streamlineSpacing() {
    return this.session.surface.radius * (0.01 + 0.008 * (this.views?.streamlineSpacing ?? 5));
  }

  #streamlineLift() {
    return 0.03 * this.session.surface.meanEdge;
  }

  // The field drawn (a part of the current field may still be to come) and its streamlines' options.
  #streamlineTarget() {
    const d = this.drawn, s = this.session;
    const options = { component: d?.name ?? 'whole', spacing: this.#streamlineSpacing(), lift: this.#streamlineLift() };
    return { field: d?.derived ?? s.field, options };
  }

  // Kept by the field drawn, per component and spacing; the view and streamlines() share them.
  currentStreamlines() {
    const { field, options } = this.#streamlineTarget();
    return field.streamlines(options) ?? this.#tracedHere(field, options, () => field.requireStreamlines(options));
  }

  // Traces the field drawn on the page, now, whatever the field keeps.
  traceStreamlinesHere() {
    const { field, options } = this.#streamlineTarget();
    return this.#tracedHere(field, options, () => field.traceStreamlines(options));
  }

  #tracedHere(field, options, trace) {
    const s = this.session, t0 = performance.now();
    const lines = trace();
    s.perf.streamlines = { ms: performance.now() - t0, source: 'page', fieldVersion: s.fieldVersion };
    return lines;
  }

  // The streamlines view asks the worker for the lines of the field it shows; they are drawn when they come
  // (after the frame with the arrows), unless the field, the component, the spacing or the view changed meanwhile.
  #scheduleStreamlines() {
    const s = this.session, viewer = this.viewer, d = this.drawn;
    if (!this.views.streamlines) return void viewer.streamlines.setLines([]);
    if (!d || d.fieldVersion !== s.fieldVersion) return; // the part of this field is still to come
    const spacing = this.#streamlineSpacing(), surface = s.surface, fieldVersion = s.fieldVersion, key = d.key;
    const field = d.derived, options = { component: d.name, spacing };
    const current = () => {
      const same = this.drawn?.key === key && s.surface === surface && this.#streamlineSpacing() === spacing;
      return !s.disposed && this.views.streamlines && same;
    };
    const known = field.streamlines(options);
    if (known) return void viewer.streamlines.setLines(known, this.#symmetry());
    const t0 = performance.now();
    s.proxy
      ?.call('streamlines', [field.version, spacing, this.#streamlineLift(), d.name], [], { background: true })
      .then(({ value: lines, workerMs }) => {
        if (!lines || !current()) return;
        field.keepStreamlines(options, lines);
        const component = d.name;
        s.perf.streamlines = { ms: performance.now() - t0, workerMs, source: 'worker', fieldVersion, component };
        viewer.streamlines.setLines(lines, this.#symmetry());
        viewer.requestRender();
      })
      .catch(() => {}); // a restarted worker: the refresh after the restart asks again
  }

  // The views that are on get the current field, once per field version; the others get nothing.
  #showDerived() {
    const { viewer, views, shown, session: s } = this;
    if (views.singularities && shown.singularities !== s.fieldVersion) {
      viewer.singularities.setSingularities(s.currentSingularities(), this.#symmetry());
      shown.singularities = s.fieldVersion;
    }
    const d = this.drawn;
    if (!d) return;
    if ((views.colorMap || views.lic) && shown.vertexField !== d.key) {
      const options = { symmetry: this.#symmetry(), faceVectors: d.field.faceVectors };
      viewer.setVertexField(d.field.vertexVectors, d.field.scale, options);
      shown.vertexField = d.key;
    }
    this.ui.setLegend(views.colorMap || views.arrows ? d.field.scale.top : null);
  }

  // A new mesh: the surface, before its first field is shown.
  modelChanged({ info, surface }) {
    this.drawn = null;
    this.shown.featureEdges = null;
    this.sharesShown = null;
    this.viewer.setMesh(surface);
    this.ui.setHasBoundary(info.boundaryLoops > 0);
  }

  // Pushes the current field, constraints and settings to the view and the panels, and draws.
  refresh() {
    const { viewer, session: s } = this;
    if (!s.field || !s.surface) return;
    const t0 = performance.now();
    const target = this.#target();
    if (target) this.#draw(target);
    this.#showDerived();
    viewer.handles.setConstraints(s.table.entries());
    viewer.handles.setSelected(s.selected);
    this.#showDesignTopology();
    const t1 = performance.now();
    // The texture's update shown with the field in one frame when it follows within a frame or two, and the
    // panels with them: with software GL a change of the panels is a raster and a read-back of their tiles in the
    // GPU process (15-32 ms for bunny00's side panel) that the texture's update waited for.
    const wait = this.frameMayWait();
    if (wait > 0) {
      if (!this.panelsOwed) viewer.afterRender.push(() => this.#showPanels());
      this.panelsOwed = true;
      viewer.deferFrame(wait);
    } else {
      this.#showPanels();
      viewer.renderNow();
    }
    const t2 = performance.now();
    // drawnAt: when the change's draw was issued (what bench:web times an exact field landing by).
    s.perf.refresh = { updateViewsMs: t1 - t0, renderMs: t2 - t1, drawnAt: t2 };
    this.#scheduleStreamlines();
    this.#requestParts();
    this.#showShares();
    this.onRefreshed();
  }

  // The panels' part of refresh(): the constraints, settings, status, history, and what the prescribed indices
  // and features leave to the field (the Field panel), from the state as it is when they are shown.
  #showPanels() {
    const { ui, session: s } = this;
    this.panelsOwed = false;
    if (!s.field || !s.surface || s.disposed) return;
    const { angle } = s.topology.features();
    ui.setFeatures({ angle, count: s.field.featureEdges ? this.shown.featureEdgeCount : null, folds: s.info?.folds });
    ui.setSingularitySummary(s.topology.summary());
    ui.setConstraints(s.table.views(), s.selected);
    ui.setSettings(s.settings());
    ui.setStatus({ name: s.modelName, info: s.info, stats: s.field.stats });
    this.refreshHistory();
  }

  // The prescribed singularities (the design's, always drawn) and the feature edges in use (their lines rebuilt
  // only when they changed: a stroke's solve sends the same edges again).
  #showDesignTopology() {
    const { viewer, session: s } = this, N = this.#symmetry();
    const prescribed = s.table.views().filter((c) => c.type === 'singularity');
    viewer.singularities.setPrescribed(prescribed.map(({ id, vertex, index }) => ({ id, vertex, index })), N);
    viewer.singularities.setSelected(s.selected);
    const { edges } = s.topology.features();
    const pairs = s.field.featureEdges, last = this.shown.featureEdges;
    if (!pairs || !last || pairs.length !== last.length || pairs.some((v, k) => v !== last[k])) {
      viewer.features.setEdges(edges);
      this.shown.featureEdges = pairs;
    }
    // A big model's preview field knows no feature edges: the count waits for the exact one (#showPanels).
    this.shown.featureEdgeCount = edges.length;
  }

  refreshHistory() {
    const h = this.session.history;
    const undo = h.peekUndo(), redo = h.peekRedo();
    const labels = { undoLabel: undo?.label ?? '', redoLabel: redo?.label ?? '' };
    this.ui.setHistory({ canUndo: !!undo, canRedo: !!redo, ...labels });
  }

  selectionChanged(selected) {
    this.viewer.handles.setSelected(selected);
    this.viewer.singularities.setSelected(selected);
    this.ui.setConstraints(this.session.table.views(), selected);
    this.viewer.requestRender();
  }

  apply(views) {
    const before = this.views.component ?? 'whole';
    this.views = { ...this.views, ...views };
    const v = this.views, viewer = this.viewer, s = this.session;
    viewer.arrows.setOptions({ visible: v.arrows, density: v.arrowDensity, scaled: v.arrowsScaled });
    let redrawn = false;
    if (s.field && s.surface && (v.component ?? 'whole') !== before) {
      // Another component: drawn now when known (the whole field always is), else asked for.
      const target = this.#target();
      if (target) {
        this.#draw(target);
        redrawn = true;
      }
      this.#requestParts();
      this.#showShares();
    }
    // The views turned on get the current field first (the markers are built when the view shows).
    if (s.field) this.#showDerived();
    viewer.setColorMap(v.colorMap);
    viewer.singularities.setVisible(v.singularities);
    viewer.lic.setVisible(v.lic);
    if (s.field && s.surface) this.#scheduleStreamlines();
    viewer.requestRender();
    if (redrawn) this.onRefreshed();
  }

  // From the API: the panel's controls follow, and the views read them back.
  set(views) {
    const rest = { ...views };
    delete rest.shares; // the panel's read-out, not an option
    if ('component' in rest && !COMPONENTS.includes(rest.component)) {
      const known = COMPONENTS.map((c) => `'${c}'`).join(', ');
      throw new Error(`setViews: unknown component ${JSON.stringify(rest.component)}; one of ${known}`);
    }
    this.ui.setViews(rest);
    this.apply(this.ui.views());
    return { ...this.views };
  }
}

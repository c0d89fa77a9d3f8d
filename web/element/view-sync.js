// Session → views: after every 'change' the field, the constraints and the settings go to the viewer and the
// panels, drawn synchronously; the views that are off get nothing. Owns the view options (which views are on,
// arrow density, streamline spacing) and what is derived per field for them: the magnitude scale, the
// singularity markers, the streamlines (traced in the worker, on the page only when read before they arrive).
import { magnitudeScale } from '../views/colormap.js';
import { traceStreamlines } from '../geometry/streamlines.js';

export class ViewSync {
  constructor({ session, viewer, ui }) {
    this.session = session;
    this.viewer = viewer;
    this.ui = ui;
    this.views = {};
    this.streamlineCache = null; // {version, spacing, surface, lines, source: 'worker' | 'page'}
    this.shown = { singularities: -1, vertexField: -1 }; // the field versions those views were last given
    this.onRefreshed = () => {}; // after each redraw (texture synthesis follows the field)
  }

  #streamlineSpacing() {
    return this.session.surface.radius * (0.01 + 0.008 * (this.views?.streamlineSpacing ?? 5));
  }

  #streamlineLift() {
    return 0.03 * this.session.surface.meanEdge;
  }

  // Cached per field version and spacing; the view and streamlines() share them.
  currentStreamlines() {
    const s = this.session, spacing = this.#streamlineSpacing(), c = this.streamlineCache;
    if (c && c.version === s.fieldVersion && c.spacing === spacing && c.surface === s.surface) return c.lines;
    const lines = this.traceStreamlinesHere();
    this.streamlineCache = { version: s.fieldVersion, spacing, surface: s.surface, lines, source: 'page' };
    return lines;
  }

  // Traces on the page, now, whatever the cache holds.
  traceStreamlinesHere() {
    const s = this.session, t0 = performance.now();
    const lines = traceStreamlines(s.surface, s.field.vertexVectors, { spacing: this.#streamlineSpacing(), lift: this.#streamlineLift() });
    s.perf.streamlines = { ms: performance.now() - t0, source: 'page', fieldVersion: s.fieldVersion };
    return lines;
  }

  // The streamlines view asks the worker for the lines of the field it shows; they are drawn when they come
  // (after the frame with the arrows), unless the field, the spacing or the view changed meanwhile.
  #scheduleStreamlines() {
    const s = this.session, viewer = this.viewer;
    if (!this.views.streamlines) return void viewer.streamlines.setLines([]);
    const spacing = this.#streamlineSpacing(), surface = s.surface, fieldVersion = s.fieldVersion;
    const c = this.streamlineCache;
    const current = () =>
      !s.disposed && this.views.streamlines && s.fieldVersion === fieldVersion && s.surface === surface && this.#streamlineSpacing() === spacing;
    if (c && c.version === fieldVersion && c.spacing === spacing && c.surface === surface) return void viewer.streamlines.setLines(c.lines);
    const t0 = performance.now();
    s.proxy
      ?.call('streamlines', [s.field.version, spacing, this.#streamlineLift()], [], { background: true })
      .then(({ value: lines, workerMs }) => {
        if (!lines || !current()) return;
        this.streamlineCache = { version: fieldVersion, spacing, surface, lines, source: 'worker' };
        s.perf.streamlines = { ms: performance.now() - t0, workerMs, source: 'worker', fieldVersion };
        viewer.streamlines.setLines(lines);
        viewer.requestRender();
      })
      .catch(() => {}); // a restarted worker: the refresh after the restart asks again
  }

  // One magnitude scale per field for the arrows, the surface colours and the legend.
  #fieldScale() {
    const field = this.session.field;
    field.scale ??= magnitudeScale(field.vertexVectors);
    return field.scale;
  }

  // The views that are on get the current field, once per field version; the others get nothing.
  #showDerived() {
    const { viewer, views, shown, session: s } = this;
    if (views.singularities && shown.singularities !== s.fieldVersion) {
      viewer.singularities.setSingularities(s.currentSingularities());
      shown.singularities = s.fieldVersion;
    }
    if ((views.colorMap || views.lic) && shown.vertexField !== s.fieldVersion) {
      viewer.setVertexField(s.field.vertexVectors, this.#fieldScale());
      shown.vertexField = s.fieldVersion;
    }
    // Arrows and the surface map share one magnitude scale (viridis, top at the 98th percentile): one legend.
    this.ui.setLegend(views.colorMap || views.arrows ? this.#fieldScale().top : null);
  }

  // A new mesh: the surface, before its first field is shown.
  modelChanged({ info, surface }) {
    this.streamlineCache = null;
    this.viewer.setMesh(surface);
    this.ui.setHasBoundary(info.boundaryLoops > 0);
  }

  // Pushes the current field, constraints and settings to the view and the panels; draws synchronously.
  refresh() {
    const { viewer, ui, session: s } = this;
    if (!s.field || !s.surface) return;
    const t0 = performance.now();
    viewer.arrows.setField(s.field.faceVectors, s.field.vertexVectors, this.#fieldScale());
    this.#showDerived();
    viewer.handles.setConstraints(s.table.entries());
    viewer.handles.setSelected(s.selected);
    ui.setConstraints(s.constraintList(), s.selected);
    ui.setSettings(s.settings());
    ui.setStatus({ name: s.modelName, info: s.info, stats: s.field.stats });
    this.refreshHistory();
    const t1 = performance.now();
    viewer.renderNow();
    s.perf.refresh = { updateViewsMs: t1 - t0, renderMs: performance.now() - t1 };
    this.#scheduleStreamlines();
    this.onRefreshed();
  }

  refreshHistory() {
    const h = this.session.history;
    this.ui.setHistory({ canUndo: !!h.peekUndo(), canRedo: !!h.peekRedo(), undoLabel: h.peekUndo()?.label ?? '', redoLabel: h.peekRedo()?.label ?? '' });
  }

  selectionChanged(selected) {
    this.viewer.handles.setSelected(selected);
    this.ui.setConstraints(this.session.constraintList(), selected);
    this.viewer.requestRender();
  }

  apply(views) {
    this.views = { ...this.views, ...views };
    const v = this.views, viewer = this.viewer, s = this.session;
    viewer.arrows.setOptions({ visible: v.arrows, density: v.arrowDensity, scaled: v.arrowsScaled });
    // The views turned on get the current field first (the markers are built when the view shows).
    if (s.field) this.#showDerived();
    viewer.setColorMap(v.colorMap);
    viewer.singularities.setVisible(v.singularities);
    viewer.lic.setVisible(v.lic);
    if (s.field) this.#scheduleStreamlines();
    viewer.requestRender();
  }

  // From the API: the panel's controls follow, and the views read them back.
  set(views) {
    this.ui.setViews(views);
    this.apply(this.ui.views());
    return { ...this.views };
  }
}

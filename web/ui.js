// DOM side of one designer: toolbar, side panels, constraint list and selection editor, error banner, drop
// target, progress indicator and status line. The markup is the element's (template.js, in its shadow root);
// this module binds it, reports user intent through the callbacks it is given, and renders the state it is
// handed. Keyboard shortcuts act while the focus is inside the element (or, on the app page, anywhere).

const TOOL_KEYS = { o: 'orbit', e: 'select', s: 'stroke', v: 'vector', r: 'source', g: 'sink', b: 'vortex' };
const SWATCH = { stroke: '#ff7a1a', vector: '#fbbf24', edge: '#ff7a1a', source: '#ef4444', sink: '#22c55e', vortex: '#3b82f6' };
const PROGRESS_DELAY_MS = 200; // shorter operations show no indicator at all

function fmtMs(ms) {
  if (typeof ms !== 'number' || !Number.isFinite(ms)) return '–';
  return ms < 10 ? ms.toFixed(2) : ms < 100 ? ms.toFixed(1) : ms.toFixed(0);
}

function fmtNum(x) {
  if (typeof x !== 'number') return String(x);
  return Math.abs(x) >= 1e4 || (x !== 0 && Math.abs(x) < 1e-2) ? x.toExponential(0) : String(+x.toPrecision(4));
}

function isTyping(target) {
  return target instanceof HTMLInputElement || target instanceof HTMLSelectElement || target instanceof HTMLTextAreaElement;
}

// root: the shadow root; host: the element (keyboard events reach it from inside the shadow tree).
export function bindUi(root, host, actions) {
  const $ = (sel) => root.querySelector(sel);
  const $$ = (sel) => root.querySelectorAll(sel);
  const focused = () => root.activeElement;
  const fileInput = $('#file-input');
  const designInput = $('#design-input');
  const banner = $('#error-banner');
  const bannerMsg = banner.querySelector('.message');
  const status = $('#status');
  const list = $('#constraint-list');
  const emptyNote = $('#constraints-empty');
  const viewport = $('#viewport');
  const dropOverlay = $('#drop-overlay');
  const progress = $('#progress');
  const strength = $('#strength');
  const weight = $('#weight');
  let flashTimer = 0, flashText = null;
  let statusText = 'Loading…';
  let orientation = 'ccw';
  let selectedUid = null;

  // ---- files
  fileInput.accept = actions.accept;
  $('#open-button').addEventListener('click', () => fileInput.click());
  fileInput.addEventListener('change', () => {
    const files = [...fileInput.files];
    fileInput.value = ''; // picking the same file again must fire change again
    if (files.length) openFiles(files);
  });
  $('#save-design').addEventListener('click', () => actions.onSaveDesign());
  $('#load-design').addEventListener('click', () => designInput.click());
  designInput.addEventListener('change', () => {
    const [file] = designInput.files;
    designInput.value = '';
    if (file) actions.onLoadDesign(file);
  });
  $('#export-field').addEventListener('click', () => actions.onExportField());

  // A .gltf may come with its .bin files; the first mesh-like file is the model, the rest are its resources.
  // A lone .json is a design.
  function openFiles(files) {
    const isModel = (f) => /\.(glb|gltf|obj|off|ply)$/i.test(f.name);
    const main = files.find(isModel);
    if (!main && files.length === 1 && /\.json$/i.test(files[0].name)) return actions.onLoadDesign(files[0]);
    const model = main ?? files[0];
    actions.onOpen(model, files.filter((f) => f !== model));
  }

  // Drag and drop anywhere over the viewport.
  let dragDepth = 0;
  viewport.addEventListener('dragenter', (e) => {
    if (!e.dataTransfer?.types.includes('Files')) return;
    e.preventDefault();
    dragDepth++;
    dropOverlay.hidden = false;
  });
  viewport.addEventListener('dragover', (e) => {
    if (!e.dataTransfer?.types.includes('Files')) return;
    e.preventDefault();
    e.dataTransfer.dropEffect = 'copy';
  });
  viewport.addEventListener('dragleave', () => {
    if (--dragDepth <= 0) (dragDepth = 0), (dropOverlay.hidden = true);
  });
  viewport.addEventListener('drop', (e) => {
    e.preventDefault();
    dragDepth = 0;
    dropOverlay.hidden = true;
    const files = [...(e.dataTransfer?.files ?? [])];
    if (files.length) openFiles(files);
  });

  // ---- tools and their options
  for (const btn of $$('[data-tool]')) btn.addEventListener('click', () => setTool(btn.dataset.tool));
  function setTool(tool) {
    for (const b of $$('[data-tool]')) b.setAttribute('aria-pressed', String(b.dataset.tool === tool));
    for (const el of $$('.tool-options [data-for]')) el.hidden = !el.dataset.for.split(' ').includes(tool);
    actions.onTool(tool);
  }
  for (const btn of $$('[data-orientation]')) {
    btn.addEventListener('click', () => setOrientation(btn.dataset.orientation));
  }
  function setOrientation(o) {
    orientation = o;
    for (const b of $$('[data-orientation]')) b.setAttribute('aria-pressed', String(b.dataset.orientation === o));
  }

  // ---- undo / redo
  $('#undo').addEventListener('click', () => actions.onUndo());
  $('#redo').addEventListener('click', () => actions.onRedo());

  const onKey = (e) => {
    const mod = e.ctrlKey || e.metaKey;
    const key = e.key.toLowerCase();
    if (mod && !e.altKey && (key === 'z' || key === 'y')) {
      if (isTyping(e.target) && e.target.type !== 'checkbox' && e.target.type !== 'range') return; // the field's own undo
      e.preventDefault();
      if (key === 'y' || e.shiftKey) actions.onRedo();
      else actions.onUndo();
      return;
    }
    if (mod && !e.altKey && key === 's') {
      e.preventDefault();
      actions.onSaveDesign();
      return;
    }
    if (isTyping(e.target) || mod || e.altKey) return;
    if (TOOL_KEYS[key]) setTool(TOOL_KEYS[key]);
    else if (key === 'escape') selectedUid != null ? actions.onSelect(null) : setTool('orbit');
    else if (key === 'f') setOrientation(orientation === 'ccw' ? 'cw' : 'ccw');
    else if ((key === 'delete' || key === 'backspace') && selectedUid != null) {
      e.preventDefault();
      actions.onRemove(selectedUid);
    }
  };
  // Keys typed inside the element; the app page also forwards the rest of the page's (listenTo(window)).
  host.addEventListener('keydown', onKey);
  const pageKey = (e) => e.composedPath().includes(host) || onKey(e);
  let pageTarget = null;
  function listenTo(target) {
    pageTarget = target;
    target.addEventListener('keydown', pageKey);
  }

  // ---- field settings
  const boundarySelect = $('#boundary');
  const angleInput = $('#boundary-angle');
  function boundaryChoice() {
    if (boundarySelect.value !== 'angle') return boundarySelect.value;
    const deg = Number(angleInput.value);
    return { angle: ((Number.isFinite(deg) ? deg : 0) * Math.PI) / 180 };
  }
  boundarySelect.addEventListener('change', () => {
    $('#boundary-angle-row').hidden = boundarySelect.value !== 'angle';
    actions.onBoundary(boundaryChoice());
  });
  angleInput.addEventListener('change', () => actions.onBoundary(boundaryChoice()));
  $('#gamma').addEventListener('change', (e) => actions.onGamma(Number(e.target.value)));

  // ---- views
  const viewInputs = ['show-arrows', 'arrow-density', 'arrow-scaled', 'show-streamlines', 'streamline-spacing'];
  for (const id of [...viewInputs, 'show-colormap', 'show-singularities']) {
    $(`#${id}`).addEventListener('input', () => actions.onViews(views()));
  }
  function views() {
    return {
      arrows: $('#show-arrows').checked,
      arrowDensity: Number($('#arrow-density').value),
      arrowsScaled: $('#arrow-scaled').checked,
      streamlines: $('#show-streamlines').checked,
      streamlineSpacing: Number($('#streamline-spacing').value),
      colorMap: $('#show-colormap').checked,
      singularities: $('#show-singularities').checked,
    };
  }
  function setViews(v) {
    if ('arrows' in v) $('#show-arrows').checked = v.arrows;
    if ('arrowDensity' in v) $('#arrow-density').value = String(v.arrowDensity);
    if ('arrowsScaled' in v) $('#arrow-scaled').checked = v.arrowsScaled;
    if ('streamlines' in v) $('#show-streamlines').checked = v.streamlines;
    if ('streamlineSpacing' in v) $('#streamline-spacing').value = String(v.streamlineSpacing);
    if ('colorMap' in v) $('#show-colormap').checked = v.colorMap;
    if ('singularities' in v) $('#show-singularities').checked = v.singularities;
  }

  // ---- constraints list and selection editor
  banner.querySelector('.dismiss').addEventListener('click', () => (banner.hidden = true));
  list.addEventListener('click', (e) => {
    const li = e.target.closest('[data-constraint-id]');
    if (!li) return;
    const uid = Number(li.dataset.constraintId);
    if (e.target.closest('button.delete')) actions.onRemove(uid);
    else actions.onSelect(uid);
  });
  $('#clear-all').addEventListener('click', () => actions.onClear());
  $('#sel-delete').addEventListener('click', () => selectedUid != null && actions.onRemove(selectedUid));
  $('#sel-weight').addEventListener('change', (e) => selectedUid != null && actions.onEditWeight(selectedUid, Number(e.target.value)));
  $('#sel-strength').addEventListener('change', (e) => selectedUid != null && actions.onEditStrength(selectedUid, Number(e.target.value)));

  function describe(c) {
    switch (c.type) {
      case 'stroke': return `${c.points.length} pts · s ${fmtNum(c.strength)} · w ${fmtNum(c.weight)}`;
      case 'vector': return `face ${c.face} · |v| ${fmtNum(Math.hypot(...c.vector))} · w ${fmtNum(c.weight)}`;
      case 'edge': return `${c.edge[0]}→${c.edge[1]} = ${fmtNum(c.value)} · w ${fmtNum(c.weight)}`;
      case 'source':
      case 'sink': return `vertex ${c.vertex} · s ${fmtNum(c.strength)}`;
      case 'vortex': return `face ${c.face} · ${c.strength >= 0 ? 'CCW' : 'CW'} ${fmtNum(Math.abs(c.strength))}`;
      default: return '';
    }
  }

  // constraints: [{id, type, ...spec}] in the page's order; selected: id or null.
  function setConstraints(constraints, selected) {
    selectedUid = selected;
    list.replaceChildren(
      ...constraints.map((c) => {
        const li = document.createElement('li');
        li.dataset.constraintId = String(c.id);
        li.classList.toggle('selected', c.id === selected);
        const label = document.createElement('span');
        label.className = 'label';
        const sw = document.createElement('span');
        sw.className = 'swatch';
        sw.style.background = SWATCH[c.type] ?? '#999';
        label.append(sw, `${c.type[0].toUpperCase()}${c.type.slice(1)} #${c.id}`);
        const detail = document.createElement('span');
        detail.className = 'detail';
        detail.textContent = describe(c);
        const del = document.createElement('button');
        del.className = 'delete';
        del.type = 'button';
        del.title = `Delete ${c.type} #${c.id}`;
        del.setAttribute('aria-label', `Delete ${c.type} ${c.id}`);
        del.textContent = '×';
        li.append(label, detail, del);
        return li;
      }),
    );
    emptyNote.hidden = constraints.length > 0;
    const sel = constraints.find((c) => c.id === selected);
    const panel = $('#selection-panel');
    panel.hidden = !sel;
    if (!sel) return;
    $('#selection-title').textContent = `${sel.type[0].toUpperCase()}${sel.type.slice(1)} #${sel.id}`;
    const hasWeight = 'weight' in sel, hasStrength = 'strength' in sel;
    $('#sel-weight-row').hidden = !hasWeight;
    $('#sel-strength-row').hidden = !hasStrength;
    // Never overwrite a number the user is typing.
    if (hasWeight && focused() !== $('#sel-weight')) $('#sel-weight').value = String(sel.weight);
    if (hasStrength && focused() !== $('#sel-strength')) $('#sel-strength').value = String(sel.strength);
  }

  // ---- banner, status, progress
  function showError(message) {
    bannerMsg.textContent = message;
    banner.hidden = false;
  }

  function renderStatus() {
    status.textContent = flashText ?? statusText;
  }

  // model: {name, info, stats}
  function setStatus({ name, info, stats = {} }) {
    if (!info) return;
    statusText = [
      name,
      `V ${info.vertices}`,
      `E ${info.edges}`,
      `F ${info.faces}`,
      `genus ${info.genus}`,
      `boundary loops ${info.boundaryLoops}`,
      `factor ${fmtMs(stats.factorMs)} ms`,
      `update ${fmtMs(stats.updateMs)} ms`,
      `solve ${fmtMs(stats.solveMs)} ms`,
    ].join('  ·  ');
    const problems = (info.problems || []).map((p) => (typeof p === 'string' ? p : JSON.stringify(p)));
    status.title = problems.length ? `Mesh notes:\n${problems.join('\n')}` : '';
    status.classList.toggle('has-problems', problems.length > 0);
    renderStatus();
  }

  function flash(text, ms = 2500) {
    clearTimeout(flashTimer);
    flashText = text;
    renderStatus();
    flashTimer = setTimeout(() => {
      flashText = null;
      renderStatus();
    }, ms);
  }

  // Returns a function that ends the indication. Shows nothing for operations shorter than 200 ms.
  function startProgress(label) {
    const t0 = performance.now();
    let ticker = 0;
    const show = setTimeout(() => {
      progress.hidden = false;
      host.classList.add('busy');
      const update = () => (progress.querySelector('.label').textContent = `${label} ${((performance.now() - t0) / 1000).toFixed(1)} s`);
      update();
      ticker = setInterval(update, 100);
    }, PROGRESS_DELAY_MS);
    return () => {
      clearTimeout(show);
      clearInterval(ticker);
      progress.hidden = true;
      host.classList.remove('busy');
    };
  }

  function setSettings({ boundary, gamma }) {
    const isAngle = typeof boundary !== 'string';
    boundarySelect.value = isAngle ? 'angle' : boundary;
    $('#boundary-angle-row').hidden = !isAngle;
    if (isAngle && focused() !== angleInput) angleInput.value = String(+((boundary.angle * 180) / Math.PI).toFixed(6));
    if (focused() !== $('#gamma')) $('#gamma').value = String(gamma);
  }

  function setHasBoundary(has) {
    $('#boundary-row').hidden = !has;
    $('#boundary-note').hidden = !has;
  }

  function setHistory({ canUndo, canRedo, undoLabel, redoLabel }) {
    $('#undo').disabled = !canUndo;
    $('#redo').disabled = !canRedo;
    $('#undo').title = canUndo ? `Undo ${undoLabel} (Ctrl+Z)` : 'Undo (Ctrl+Z)';
    $('#redo').title = canRedo ? `Redo ${redoLabel} (Ctrl+Shift+Z)` : 'Redo (Ctrl+Shift+Z)';
  }

  function setLegend(max) {
    $('#legend').hidden = max == null;
    if (max != null) $('#legend-max').textContent = `≥ ${fmtNum(max)}`;
  }

  function toolOptions() {
    const s = Number(strength.value);
    return {
      strength: Number.isFinite(s) && s > 0 ? s : 1,
      weight: Number(weight.value),
      orientation,
    };
  }

  function dispose() {
    clearTimeout(flashTimer);
    host.removeEventListener('keydown', onKey);
    pageTarget?.removeEventListener('keydown', pageKey);
  }

  setTool('orbit');
  return {
    dispose,
    listenTo,
    showError,
    setConstraints,
    setStatus,
    startProgress,
    setSettings,
    setHasBoundary,
    setHistory,
    setLegend,
    setViews,
    views,
    flash,
    toolOptions,
    setTool,
  };
}

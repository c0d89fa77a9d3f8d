// DOM side of one designer: toolbar, side panels, constraint list and selection editor, error banner, drop
// target, progress indicator and status line. The markup is the element's (template.js, in its shadow root);
// this module binds it, reports user intent through the callbacks it is given, and renders the state it is
// handed. Keyboard shortcuts act while the focus is inside the element (or, on the app page, anywhere).
import { VIEW_PRESETS } from '../views/camera.js';
import { bindHelp } from './help.js';

const TOOL_KEYS = { o: 'orbit', e: 'select', s: 'stroke', v: 'vector', r: 'source', g: 'sink', b: 'vortex' };
const PRESET_KEYS = { 1: 'front', 3: 'side', 7: 'top' };
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
  const bannerAction = banner.querySelector('.action');
  let bannerRun = null;
  const status = $('#status');
  const list = $('#constraint-list');
  const emptyNote = $('#constraints-empty');
  const viewport = $('#viewport');
  const dropOverlay = $('#drop-overlay');
  const progress = $('#progress');
  // Cancel stops the operation in flight by replacing the core (core-proxy.js); Escape does the same while busy.
  progress.querySelector('.cancel')?.addEventListener('click', () => actions.onCancel?.());
  const strength = $('#strength');
  const weight = $('#weight');
  let flashTimer = 0, flashText = null;
  let statusText = 'Loading…';
  let orientation = 'ccw';
  let selectedUid = null;

  // ---- files
  fileInput.accept = actions.accept;
  // Small screens: the panels are drawers (a bottom sheet on phones) that this button opens and closes
  // (element.css decides, by the element's own size, whether they are drawers at all).
  const panelsToggle = $('#panels-toggle');
  panelsToggle.addEventListener('click', () => {
    const open = panelsToggle.getAttribute('aria-expanded') !== 'true';
    panelsToggle.setAttribute('aria-expanded', String(open));
    $('.root').toggleAttribute('data-panels-open', open);
  });
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

  // ---- camera and help
  $('#frame-button').addEventListener('click', () => actions.onFrame('home'));
  $('#screenshot-button').addEventListener('click', () => actions.onScreenshot());
  for (const btn of $$('[data-view]')) {
    if (VIEW_PRESETS[btn.dataset.view]) btn.addEventListener('click', () => actions.onFrame(btn.dataset.view));
  }
  const help = bindHelp($('#help'), $('#hint'), actions.hintKey ?? null);
  $('#help-button').addEventListener('click', () => help.toggle());
  viewport.addEventListener('pointerdown', () => help.dismissHint(), { capture: true });

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
    if (e.key === 'F1' || ((e.key === '?' || key === 'h') && !isTyping(e.target) && !mod && !e.altKey)) {
      e.preventDefault();
      help.toggle();
      return;
    }
    if (isTyping(e.target) || mod || e.altKey) return;
    if (key === 'escape' && help.isOpen) help.close();
    else if (TOOL_KEYS[key]) setTool(TOOL_KEYS[key]);
    else if (key === 'escape' && !progress.hidden) actions.onCancel?.();
    else if (key === 'escape') selectedUid != null ? actions.onSelect(null) : setTool('orbit');
    else if (key === 'f' || e.key === 'Home') e.preventDefault(), actions.onFrame('home');
    else if (PRESET_KEYS[e.key]) actions.onFrame(PRESET_KEYS[e.key]);
    else if (key === 'x') setOrientation(orientation === 'ccw' ? 'cw' : 'ccw');
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

  // ---- numbers: a value outside its box's range is shown invalid and never silently replaced
  // Range and parse only: a step is a spinner increment, not a rule (0.15 is a fine strength).
  const invalid = (input) => {
    const v = input.validity;
    return v.badInput || v.rangeUnderflow || v.rangeOverflow || input.value.trim() === '' || !Number.isFinite(Number(input.value));
  };
  for (const input of $$('input[type="number"]')) {
    input.addEventListener('input', () => input.setAttribute('aria-invalid', String(invalid(input))));
  }
  // The number in `input`, or an Error naming the box and the value when it is not a valid one.
  function checkedNumber(input, what) {
    const bad = invalid(input);
    input.setAttribute('aria-invalid', String(bad));
    if (!bad) return Number(input.value);
    const range = input.min !== '' ? ` (at least ${input.min})` : '';
    throw new Error(`${what} must be a number${range}; the box shows "${input.value}"`);
  }
  const guarded = (fn) => (e) => {
    try {
      fn(e);
    } catch (err) {
      showError(err.message);
    }
  };

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
  angleInput.addEventListener('change', guarded(() => (checkedNumber(angleInput, 'The boundary angle'), actions.onBoundary(boundaryChoice()))));
  $('#gamma').addEventListener('change', guarded((e) => actions.onGamma(checkedNumber(e.target, 'Smoothness γ'))));

  // ---- views
  const viewInputs = ['show-arrows', 'arrow-density', 'arrow-scaled', 'show-streamlines', 'streamline-spacing'];
  for (const id of [...viewInputs, 'show-lic', 'show-colormap', 'show-singularities']) {
    $(`#${id}`).addEventListener('input', () => actions.onViews(views()));
  }
  function views() {
    return {
      arrows: $('#show-arrows').checked,
      arrowDensity: Number($('#arrow-density').value),
      arrowsScaled: $('#arrow-scaled').checked,
      streamlines: $('#show-streamlines').checked,
      streamlineSpacing: Number($('#streamline-spacing').value),
      lic: $('#show-lic').checked,
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
    if ('lic' in v) $('#show-lic').checked = !!v.lic;
    if ('colorMap' in v) $('#show-colormap').checked = v.colorMap;
    if ('singularities' in v) $('#show-singularities').checked = v.singularities;
  }

  // ---- constraints list and selection editor
  banner.querySelector('.dismiss').addEventListener('click', () => clearError());
  bannerAction.addEventListener('click', () => {
    const run = bannerRun;
    clearError();
    run?.();
  });
  list.addEventListener('click', (e) => {
    const li = e.target.closest('[data-constraint-id]');
    if (!li) return;
    const uid = Number(li.dataset.constraintId);
    if (e.target.closest('button.delete')) actions.onRemove(uid);
    else actions.onSelect(uid);
  });
  $('#clear-all').addEventListener('click', () => actions.onClear());
  $('#sel-delete').addEventListener('click', () => selectedUid != null && actions.onRemove(selectedUid));
  $('#sel-weight').addEventListener('change', guarded((e) => selectedUid != null && actions.onEditWeight(selectedUid, checkedNumber(e.target, 'The weight'))));
  $('#sel-strength').addEventListener('change', guarded((e) => selectedUid != null && actions.onEditStrength(selectedUid, checkedNumber(e.target, 'The strength'))));

  function describe(c) {
    switch (c.type) {
      case 'stroke': return `${c.points.length} points · strength ${fmtNum(c.strength)} · weight ${fmtNum(c.weight)}`;
      case 'vector': return `face ${c.face} · size ${fmtNum(Math.hypot(...c.vector))} · weight ${fmtNum(c.weight)}`;
      case 'edge': return `${c.edge[0]}→${c.edge[1]} = ${fmtNum(c.value)} · weight ${fmtNum(c.weight)}`;
      case 'source':
      case 'sink': return `vertex ${c.vertex} · strength ${fmtNum(c.strength)}`;
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
  // action: {label, run} — a button next to the message (e.g. apply a design made for another mesh anyway).
  function showError(message, action = null) {
    bannerMsg.textContent = message;
    bannerAction.hidden = !action;
    bannerAction.textContent = action?.label ?? '';
    bannerRun = action?.run ?? null;
    banner.hidden = false;
  }

  // After the next success: an error that no longer describes the state must not stay up.
  function clearError() {
    banner.hidden = true;
    bannerRun = null;
  }

  // An in-element question (no window.confirm: it would block every designer on the page). Resolves true
  // when the user chose `ok`, false on Cancel or Escape.
  let confirmDone = null;
  const confirmBox = $('#confirm');
  function confirmChoice(message, ok) {
    confirmDone?.(false);
    $('#confirm-message').textContent = message;
    $('#confirm-ok').textContent = ok;
    confirmBox.hidden = false;
    $('#confirm-ok').focus();
    return new Promise((resolve) => {
      confirmDone = (yes) => {
        confirmDone = null;
        confirmBox.hidden = true;
        resolve(yes);
      };
    });
  }
  $('#confirm-ok').addEventListener('click', () => confirmDone?.(true));
  $('#confirm-cancel').addEventListener('click', () => confirmDone?.(false));
  confirmBox.addEventListener('keydown', (e) => {
    if (e.key === 'Escape') e.stopPropagation(), confirmDone?.(false);
  });

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

  // Throws (naming the box and what it shows) when the strength is not a valid number: never coerced.
  function toolOptions() {
    const s = checkedNumber(strength, 'The strength');
    if (!(s > 0)) {
      strength.setAttribute('aria-invalid', 'true');
      throw new Error(`The strength must be above 0; the box shows "${strength.value}"`);
    }
    return { strength: s, weight: Number(weight.value), orientation };
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
    clearError,
    help,
    confirm: confirmChoice,
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

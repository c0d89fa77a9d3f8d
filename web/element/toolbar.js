// The toolbar: the tools and their options (strength, how closely to follow, the vortex turning, a prescribed
// singularity's index, whether the Feature tool adds or removes), undo and redo, the camera buttons and the
// ☰ Panels toggle of small screens. The file buttons are files.js's; what
// does not fit in one row goes into the ⋯ menu (toolbar-overflow.js).
import { VIEW_PRESETS } from '../views/camera.js';
import { indexLabel } from '../views/singularity-style.js';
import { fieldPhrase, keepsConstraint } from '../session/symmetry.js';
import { checkedNumber } from './numbers.js';
import { bindOverflow } from './toolbar-overflow.js';

// The tools whose constraint a line or cross field cannot have (core/symmetry.js).
const POINT_TOOLS = ['source', 'sink', 'vortex'];

// $, $$: querySelector(All) in the shadow root; flash(text): a passing message in the status line.
export function bindToolbar($, $$, actions, flash) {
  const strength = $('#strength');
  const weight = $('#weight');
  let orientation = 'ccw';
  const overflow = bindOverflow($('.toolbar'));

  // Small screens: the panels are drawers (a bottom sheet on phones) that this button opens and closes
  // (element.css decides, by the element's own size, whether they are drawers at all).
  const panelsToggle = $('#panels-toggle');
  panelsToggle.addEventListener('click', () => {
    const open = panelsToggle.getAttribute('aria-expanded') !== 'true';
    panelsToggle.setAttribute('aria-expanded', String(open));
    $('.root').toggleAttribute('data-panels-open', open);
  });

  // ---- tools and their options
  for (const btn of $$('[data-tool]')) btn.addEventListener('click', () => setTool(btn.dataset.tool));
  const toolButton = (tool) => $(`.segmented [data-tool="${tool}"]`);
  function setTool(tool) {
    // A key or the `tool` attribute may ask for a tool the field's symmetry rules out: say why, keep the current.
    if (toolButton(tool)?.disabled) return void flash(toolButton(tool).title);
    for (const b of $$('[data-tool]')) b.setAttribute('aria-pressed', String(b.dataset.tool === tool));
    for (const el of $$('.tool-options [data-for]')) el.hidden = !el.dataset.for.split(' ').includes(tool);
    overflow.fit(); // this tool's options may need room: refit now, not a frame later
    actions.onTool(tool);
  }
  // The Feature tool adds or removes (Alt or Shift at the press removes whatever this says).
  let featureMode = 'add';
  for (const btn of $$('[data-feature-mode]'))
    btn.addEventListener('click', () => setFeatureMode(btn.dataset.featureMode));
  function setFeatureMode(mode) {
    featureMode = mode;
    for (const b of $$('[data-feature-mode]')) b.setAttribute('aria-pressed', String(b.dataset.featureMode === mode));
  }

  // A prescribed singularity's index, k/N: +1/N, -1/N, +2/N, -2/N, ... +1, -1 (the options follow N; the choice
  // keeps its sign and, where it can, its size).
  const indexSelect = $('#singularity-index');
  let indexN = 0;
  function setIndexChoices(n) {
    if (n === indexN) return;
    const was = indexN ? Number(indexSelect.value) / indexN : 1 / n;
    indexN = n;
    const options = [];
    for (let k = 1; k <= n; k++) {
      for (const sign of [1, -1]) {
        const o = document.createElement('option');
        o.value = String(sign * k);
        o.textContent = indexLabel((sign * k) / n, n);
        options.push(o);
      }
    }
    indexSelect.replaceChildren(...options);
    const k = Math.sign(was) * Math.min(n, Math.max(1, Math.round(Math.abs(was) * n)));
    indexSelect.value = String(k);
  }

  for (const btn of $$('[data-orientation]'))
    btn.addEventListener('click', () => setOrientation(btn.dataset.orientation));
  function setOrientation(o) {
    orientation = o;
    for (const b of $$('[data-orientation]')) b.setAttribute('aria-pressed', String(b.dataset.orientation === o));
  }

  // Sources, sinks and vortices are vector-field notions: their tools are off for a line or cross field (N ≥ 2),
  // with the reason as their tooltip; a tool in use that goes off gives way to orbit.
  const baseTitles = new Map(POINT_TOOLS.map((tool) => [tool, toolButton(tool).title]));
  function setSymmetry(n) {
    setIndexChoices(n);
    for (const tool of POINT_TOOLS) {
      const btn = toolButton(tool), off = !keepsConstraint(tool, n);
      btn.disabled = off;
      btn.title = off
        ? `${btn.textContent}: not for ${fieldPhrase(n)} — its directions have no sign, so it has no sources, ` +
          'sinks or vortices (switch Symmetry to Vector)'
        : baseTitles.get(tool);
      if (off && btn.getAttribute('aria-pressed') === 'true') setTool('orbit');
    }
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

  setIndexChoices(1);

  // ---- undo / redo
  $('#undo').addEventListener('click', () => actions.onUndo());
  $('#redo').addEventListener('click', () => actions.onRedo());
  function setHistory({ canUndo, canRedo, undoLabel, redoLabel }) {
    $('#undo').disabled = !canUndo;
    $('#redo').disabled = !canRedo;
    $('#undo').title = canUndo ? `Undo ${undoLabel} (Ctrl+Z)` : 'Undo (Ctrl+Z)';
    $('#redo').title = canRedo ? `Redo ${redoLabel} (Ctrl+Shift+Z)` : 'Redo (Ctrl+Shift+Z)';
  }

  // ---- camera
  $('#frame-button').addEventListener('click', () => actions.onFrame('home'));
  $('#screenshot-button').addEventListener('click', () => actions.onScreenshot());
  for (const btn of $$('[data-view]')) {
    if (VIEW_PRESETS[btn.dataset.view]) btn.addEventListener('click', () => actions.onFrame(btn.dataset.view));
  }

  return {
    setTool,
    setSymmetry,
    flipOrientation: () => setOrientation(orientation === 'ccw' ? 'cw' : 'ccw'),
    toolOptions,
    // The index a Singularity click places (k/N of the field's N).
    singularityIndex: () => Number(indexSelect.value) / indexN,
    featureRemoving: () => featureMode === 'remove',
    setHistory,
    dispose: () => overflow.dispose(),
  };
}

// The toolbar: the tools and their options (strength, how closely to follow, the vortex turning), undo and
// redo, the camera buttons and the ☰ Panels toggle of small screens. The file buttons are files.js's; what
// does not fit in one row goes into the ⋯ menu (toolbar-overflow.js).
import { VIEW_PRESETS } from '../views/camera.js';
import { checkedNumber } from './numbers.js';
import { bindOverflow } from './toolbar-overflow.js';

// $, $$: querySelector(All) in the shadow root.
export function bindToolbar($, $$, actions) {
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
  function setTool(tool) {
    for (const b of $$('[data-tool]')) b.setAttribute('aria-pressed', String(b.dataset.tool === tool));
    for (const el of $$('.tool-options [data-for]')) el.hidden = !el.dataset.for.split(' ').includes(tool);
    overflow.fit(); // this tool's options may need room: refit now, not a frame later
    actions.onTool(tool);
  }
  for (const btn of $$('[data-orientation]')) btn.addEventListener('click', () => setOrientation(btn.dataset.orientation));
  function setOrientation(o) {
    orientation = o;
    for (const b of $$('[data-orientation]')) b.setAttribute('aria-pressed', String(b.dataset.orientation === o));
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
    flipOrientation: () => setOrientation(orientation === 'ccw' ? 'cw' : 'ccw'),
    toolOptions,
    setHistory,
    dispose: () => overflow.dispose(),
  };
}

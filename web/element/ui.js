// DOM side of one designer: binds the markup of template.js (in the element's shadow root) and composes the
// pieces — the toolbar (toolbar.js, with its ⋯ overflow menu), the file buttons and drop target (files.js),
// the side panels (panels.js), the banner, confirmation, status line and progress (status.js) and the help
// (help.js). They report user intent through `actions` and render the state they are handed. Keyboard
// shortcuts act while the focus is inside the element (or, on the app page, anywhere).
import { bindFiles } from './files.js';
import { bindHelp } from './help.js';
import { isTyping, watchNumbers } from './numbers.js';
import { bindPanels } from './panels.js';
import { bindStatus } from './status.js';
import { bindToolbar } from './toolbar.js';

const TOOL_KEYS = {
  o: 'orbit',
  e: 'select',
  s: 'stroke',
  v: 'vector',
  r: 'source',
  g: 'sink',
  b: 'vortex',
  i: 'singularity',
  k: 'feature',
};
const PRESET_KEYS = { 1: 'front', 3: 'side', 7: 'top' };

// root: the shadow root; host: the element (keyboard events reach it from inside the shadow tree).
export function bindUi(root, host, actions) {
  const $ = (sel) => root.querySelector(sel);
  const $$ = (sel) => root.querySelectorAll(sel);
  const status = bindStatus($, host, { onCancel: () => actions.onCancel?.() });
  const panels = bindPanels($, () => root.activeElement, actions, status.showError);
  const toolbar = bindToolbar($, $$, actions, (text) => status.flash(text, 5000));
  bindFiles($, actions);
  watchNumbers($$('input[type="number"]'));

  const help = bindHelp($('#help'), $('#hint'), actions.hintKey ?? null);
  $('#help-button').addEventListener('click', () => help.toggle());
  $('#viewport').addEventListener('pointerdown', () => help.dismissHint(), { capture: true });

  const onKey = (e) => {
    const mod = e.ctrlKey || e.metaKey;
    const key = e.key.toLowerCase();
    if (mod && !e.altKey && (key === 'z' || key === 'y')) {
      // A text box's own undo.
      if (isTyping(e.target) && e.target.type !== 'checkbox' && e.target.type !== 'range') return;
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
    const selected = panels.selected;
    if (key === 'escape' && help.isOpen) help.close();
    else if (TOOL_KEYS[key]) toolbar.setTool(TOOL_KEYS[key]);
    else if (key === 'escape' && status.busy) actions.onCancel?.();
    else if (key === 'escape') selected != null ? actions.onSelect(null) : toolbar.setTool('orbit');
    else if (key === 'f' || e.key === 'Home') {
      e.preventDefault();
      actions.onFrame('home');
    }
    else if (PRESET_KEYS[e.key]) actions.onFrame(PRESET_KEYS[e.key]);
    else if (key === 'x') toolbar.flipOrientation();
    else if ((key === 'delete' || key === 'backspace') && selected != null) {
      e.preventDefault();
      actions.onRemove(selected);
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

  function dispose() {
    status.dispose();
    toolbar.dispose();
    host.removeEventListener('keydown', onKey);
    pageTarget?.removeEventListener('keydown', pageKey);
  }

  toolbar.setTool('orbit');
  return {
    dispose,
    listenTo,
    showError: status.showError,
    clearError: status.clearError,
    help,
    confirm: status.confirm,
    setConstraints: panels.setConstraints,
    setStatus: status.setStatus,
    startProgress: status.startProgress,
    setSettings: (settings) => {
      panels.setSettings(settings);
      toolbar.setSymmetry(settings.symmetry ?? 1);
    },
    setHasBoundary: panels.setHasBoundary,
    setFeatures: panels.setFeatures,
    setSingularitySummary: panels.setSingularitySummary,
    setHistory: toolbar.setHistory,
    setLegend: panels.setLegend,
    setViews: panels.setViews,
    views: panels.views,
    flash: status.flash,
    toolOptions: toolbar.toolOptions,
    singularityIndex: toolbar.singularityIndex,
    featureRemoving: toolbar.featureRemoving,
    setTool: toolbar.setTool,
  };
}

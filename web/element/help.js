// The help overlay (?, H, F1 or the ? button) and the first-run hint of one designer. The overlay is built
// from the tables below: every tool, every shortcut and every mouse or touch gesture the studio knows.
export const HELP_TOOLS = [
  ['Orbit', 'O', 'Turn, pan and zoom the view. Drag to turn; right-drag or Shift+drag to pan; wheel or pinch to zoom.'],
  ['Select', 'E', 'Click a constraint handle to edit its weight or strength, or delete it.'],
  ['Stroke', 'S', 'Drag across the surface: the field follows the stroke, in the direction you drew it.'],
  ['Vector', 'V', 'Drag on a triangle: the field’s direction and size there.'],
  ['Source', 'R', 'Click: the field flows out of the nearest vertex. Vector fields only.'],
  ['Sink', 'G', 'Click: the field flows into the nearest vertex. Vector fields only.'],
  [
    'Vortex',
    'B',
    'Click: the field turns around the triangle (X flips counter-clockwise / clockwise). Vector fields only.',
  ],
  [
    'Singularity',
    'I',
    'Click near a vertex: a prescribed singularity there, of the index chosen in the toolbar (a multiple of ' +
      '1/N). Drag a placed one (ringed) to move it; drag from empty surface for a +1/N, \u22121/N pair.',
  ],
  [
    'Feature',
    'K',
    'Click an edge, or drag along edges: sharp features the field follows. Remove (or Alt or Shift held): ' +
      'they stop being features. The Field panel sets the angle over which edges are features.',
  ],
];

export const HELP_SHORTCUTS = [
  ['F or Home', 'Frame the model (also the Frame button)'],
  ['1 / 3 / 7', 'Front, side and top view'],
  ['X', 'Flip the vortex turning (counter-clockwise ↔ clockwise)'],
  ['Ctrl+Z / Ctrl+Shift+Z, Ctrl+Y', 'Undo / redo'],
  ['Ctrl+S', 'Save the design'],
  ['Delete / Backspace', 'Delete the selected constraint or prescribed singularity'],
  ['Escape', 'Deselect, then back to Orbit; closes this help'],
  ['? / H / F1', 'This help'],
];

export const HELP_GESTURES = [
  ['Drag', 'Orbit (or the active tool on the model)'],
  ['Right-drag, Shift+drag, two-finger drag', 'Pan'],
  ['Wheel, pinch', 'Zoom'],
  ['Double-click / double-tap on the model', 'Orbit around that point'],
  ['Alt+drag, Shift+drag (Feature tool)', 'Remove feature edges instead of adding them'],
  ['Drop a file on the view', 'Open a mesh (.glb, .gltf, .obj, .off, .ply) or load a design (.json)'],
  ['☰ Panels (small screens)', 'Open or close the settings and constraint drawers (a bottom sheet on phones)'],
  [
    '⋯ (narrower windows)',
    'The toolbar buttons that do not fit in its row: ↑ ↓ to move, Enter to choose, Escape to close',
  ],
];

function table(caption, rows) {
  const section = document.createElement('section');
  const h = document.createElement('h3');
  h.textContent = caption;
  const t = document.createElement('table');
  for (const cells of rows) {
    const tr = t.insertRow();
    cells.forEach((text, k) => {
      const cell = document.createElement(k === 0 ? 'th' : 'td');
      if (k === 1 && cells.length === 3) cell.className = 'key';
      cell.textContent = text;
      tr.append(cell);
    });
  }
  section.append(h, t);
  return section;
}

// overlay: the empty #help element; hint: #hint; storage key for "the hint was seen" (null: never stored).
export function bindHelp(overlay, hint, hintKey) {
  const body = overlay.querySelector('.help-body');
  body.replaceChildren(
    table('Tools', HELP_TOOLS),
    table('Shortcuts', HELP_SHORTCUTS),
    table('Mouse and touch', HELP_GESTURES),
  );
  const close = () => (overlay.hidden = true);
  const open = () => {
    overlay.hidden = false;
    overlay.querySelector('.close').focus();
    dismissHint();
  };
  overlay.querySelector('.close').addEventListener('click', close);
  overlay.addEventListener('keydown', (e) => {
    if (e.key === 'Escape') {
      e.stopPropagation();
      close();
    }
  });

  let seen = false;
  try {
    seen = hintKey != null && localStorage.getItem(hintKey) === '1';
  } catch {
    // storage blocked (sandboxed frame): show the hint every time
  }
  hint.hidden = seen;
  function dismissHint() {
    if (hint.hidden) return;
    hint.hidden = true;
    try {
      if (hintKey != null) localStorage.setItem(hintKey, '1');
    } catch {
      // nothing to remember it in
    }
  }
  hint.querySelector('.close').addEventListener('click', dismissHint);
  return {
    open,
    close,
    toggle: () => (overlay.hidden ? open() : close()),
    get isOpen() {
      return !overlay.hidden;
    },
    dismissHint,
  };
}

// DOM side of the page: toolbar, constraint list, error banner, drop target and status line. The markup is
// static in index.html; this module only binds it and renders state it is handed.

const $ = (sel) => document.querySelector(sel);

function fmtMs(ms) {
  if (typeof ms !== 'number' || !Number.isFinite(ms)) return '–';
  return ms < 10 ? ms.toFixed(2) : ms < 100 ? ms.toFixed(1) : ms.toFixed(0);
}

export function bindUi({ accept, onOpen, onTool, onRemove, onBoundary, onGamma, onArrows }) {
  const fileInput = $('#file-input');
  const banner = $('#error-banner');
  const bannerMsg = banner.querySelector('.message');
  const status = $('#status');
  const list = $('#constraint-list');
  const emptyNote = $('#constraints-empty');
  const viewport = $('#viewport');
  const dropOverlay = $('#drop-overlay');
  const strength = $('#strength');
  const weight = $('#weight');
  let busy = null;
  let flashTimer = 0;

  fileInput.accept = accept;
  $('#open-button').addEventListener('click', () => fileInput.click());
  fileInput.addEventListener('change', () => {
    const files = [...fileInput.files];
    fileInput.value = ''; // picking the same file again must fire change again
    if (files.length) openFiles(files);
  });

  // A .gltf may come with its .bin files; the first mesh-like file is the model, the rest are its resources.
  function openFiles(files) {
    const isModel = (f) => /\.(glb|gltf|obj|off|ply)$/i.test(f.name);
    const main = files.find(isModel) ?? files[0];
    onOpen(main, files.filter((f) => f !== main));
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

  for (const btn of document.querySelectorAll('[data-tool]')) {
    btn.addEventListener('click', () => setTool(btn.dataset.tool));
  }
  function setTool(tool) {
    for (const b of document.querySelectorAll('[data-tool]')) b.setAttribute('aria-pressed', String(b.dataset.tool === tool));
    onTool(tool);
  }
  // Keyboard: S for stroke, O (or Escape) for orbit, when not typing in a field.
  window.addEventListener('keydown', (e) => {
    if (e.target instanceof HTMLInputElement || e.target instanceof HTMLSelectElement || e.ctrlKey || e.metaKey || e.altKey) return;
    if (e.key === 's' || e.key === 'S') setTool('stroke');
    else if (e.key === 'o' || e.key === 'O' || e.key === 'Escape') setTool('orbit');
  });

  $('#boundary').addEventListener('change', (e) => onBoundary(e.target.value));
  $('#gamma').addEventListener('change', (e) => onGamma(Number(e.target.value)));
  $('#show-arrows').addEventListener('change', (e) => onArrows(e.target.checked));

  banner.querySelector('.dismiss').addEventListener('click', () => (banner.hidden = true));

  list.addEventListener('click', (e) => {
    const btn = e.target.closest('button.delete');
    if (btn) onRemove(Number(btn.closest('[data-constraint-id]').dataset.constraintId));
  });

  function showError(message) {
    bannerMsg.textContent = message;
    banner.hidden = false;
  }

  function setConstraints(constraints) {
    list.replaceChildren(
      ...constraints.map((c) => {
        const li = document.createElement('li');
        li.dataset.constraintId = String(c.id);
        const label = document.createElement('span');
        label.className = 'label';
        label.textContent = `${c.type[0].toUpperCase()}${c.type.slice(1)} #${c.id}`;
        const detail = document.createElement('span');
        detail.className = 'detail';
        detail.textContent = `${c.points.length} pts · s ${c.strength} · w ${c.weight.toExponential(0)}`;
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
  }

  function setStatus(state) {
    if (busy) return;
    const info = state.info;
    if (!info) return;
    let stats = {};
    try {
      stats = state.core.stats();
    } catch {
      // Status is cosmetic; a failing stats call must not mask the real error.
    }
    const parts = [
      state.modelName,
      `V ${info.vertices}`,
      `E ${info.edges}`,
      `F ${info.faces}`,
      `factor ${fmtMs(stats.factorMs)} ms`,
      `update ${fmtMs(stats.updateMs)} ms`,
      `solve ${fmtMs(stats.solveMs)} ms`,
    ];
    status.textContent = parts.join('  ·  ');
    const problems = (info.problems || []).map((p) => (typeof p === 'string' ? p : JSON.stringify(p)));
    status.title = problems.length ? `Mesh notes:\n${problems.join('\n')}` : '';
    status.classList.toggle('has-problems', problems.length > 0);
  }

  function setBusy(text) {
    busy = text;
    if (text) status.textContent = text;
    document.body.classList.toggle('busy', !!text);
  }

  function flash(text) {
    clearTimeout(flashTimer);
    const prev = status.textContent;
    status.textContent = text;
    flashTimer = setTimeout(() => {
      if (status.textContent === text) status.textContent = prev;
    }, 2500);
  }

  function setSettings({ boundary, gamma }) {
    // {angle} has no preset entry; the disabled "angle" option shows that one is set.
    $('#boundary').value = typeof boundary === 'string' ? boundary : 'angle';
    $('#gamma').value = String(gamma);
  }

  function strokeOptions() {
    const s = Number(strength.value);
    return { strength: Number.isFinite(s) && s > 0 ? s : 1, weight: Number(weight.value) };
  }

  return { showError, setConstraints, setStatus, setBusy, setSettings, flash, strokeOptions };
}

// SPDX-License-Identifier: GPL-2.0-or-later
// The "Quad mesh" section of the side panel: show, the target (a number of quads or an edge length), Remesh and
// Cancel, the run's stage and progress, the statistics of the last quad mesh (how many faces are quads, its
// irregular vertices against the field's singularities, how well its edges follow the field, how far it lies
// from the model, its shape, flipped faces, the time), and the OBJ and GLB downloads. Built here and appended to
// the given container; every control goes through the controller, as the API's calls do. Imports dom.js,
// session/ (the download) and its own folder.
import { el, grouped, setText } from '../dom.js';
import { downloadBlob } from '../session/documents.js';
import { DEFAULT_TARGET, QUAD_REFUSAL } from './controller.js';

const STALE = 'The design changed since; Remesh again.';
const REMESH_TITLE = 'A quad mesh whose edges follow the cross field, its irregular vertices at its singularities';
const percent = (x, digits = 1) => `${(100 * x).toFixed(digits)} %`;
const degrees = (x) => `${x.toFixed(1)}°`;
const seconds = (ms) => (ms < 1000 ? `${Math.round(ms)} ms` : `${(ms / 1000).toFixed(1)} s`);
const threeSignificant = (x) => Number(x.toPrecision(3));

// The statistics (the core's statsJson) as the panel's lines; where the field's singularities crowd closer than a
// quad, a line saying so, and where the grid folded there (polygons left, flipped faces) what helps.
export function statsLines(s) {
  const near = s.irregularVertices > 0 ? `, ${percent(s.irregularNearSingularity, 0)} near one` : '';
  const folded = s.flippedFaces > 0 || s.quads < s.faces;
  const advice = folded ? ': smaller quads, or fewer features, give cleaner quads' : '';
  const crowded = s.crowdedSingularities > 0 ?
    [`Singularities closer than a quad: ${s.crowdedSingularities}${advice}`] :
    [];
  return [
    `Quads: ${grouped(s.quads)} of ${grouped(s.faces)} faces (${percent(s.quadShare, 2)})`,
    `Irregular vertices: ${s.irregularVertices} (field singularities: ${s.fieldSingularities}${near})`,
    `Edges off the field: median ${degrees(s.edgeAngleMedianDeg)}, p90 ${degrees(s.edgeAngleP90Deg)}`,
    `Hausdorff: ${percent(s.hausdorffRelative, 2)} of the diagonal`,
    `Aspect: median ${s.aspectMedian.toFixed(2)}`,
    `Flipped: ${s.flippedFaces}, degenerate: ${s.degenerateFaces}${s.manifold ? '' : ', not manifold'}`,
    ...crowded,
    `Time: ${seconds(s.ms)}`,
  ];
}

// controller: a QuadController; area(): the model's surface area (to turn a quad count into an edge length and
// back when the target's kind changes); onError(err): a failure outside the panel's own status line.
export function mountQuadPanel(controller, container, { area = () => 0, onError = (e) => console.error(e) } = {}) {
  const show = el('input', { id: 'quad-show', type: 'checkbox' });
  const mode = el('select', { id: 'quad-target-mode', title: 'Size the quads by their number or their edge length' });
  mode.append(el('option', { value: 'quads', text: 'Quads' }), el('option', { value: 'edgeLength', text: 'Edge' }));
  const size = el('input', { id: 'quad-target', type: 'number', min: '0', step: 'any' });
  const remesh = el('button', { id: 'quad-remesh', type: 'button', text: 'Remesh' });
  const cancel = el('button', { id: 'quad-cancel', type: 'button', text: 'Cancel', title: 'Stop the remeshing' });
  const progress = el('progress', { id: 'quad-progress', max: '1', value: '0' });
  const stage = el('span', { id: 'quad-stage', class: 'note' });
  const running = el('div', { id: 'quad-running' }, progress, stage);
  const status = el('p', { id: 'quad-status', class: 'note' });
  const stats = el('div', { id: 'quad-stats', class: 'note' });
  const obj = el('button', {
    id: 'quad-export-obj',
    type: 'button',
    text: 'OBJ',
    title: 'Download the quad mesh as OBJ (its polygons as they are)',
  });
  const glb = el('button', {
    id: 'quad-export-glb',
    type: 'button',
    text: 'GLB',
    title: 'Download the quad mesh as GLB (each quad split into two triangles)',
  });
  const section = el(
    'details',
    { id: 'quad-panel' },
    el('summary', { text: 'Quad mesh' }),
    el('label', { class: 'check', title: 'Draw the quad mesh over the model' }, show, ' Show'),
    el('label', {}, mode, ' ', size),
    el('div', { class: 'buttons' }, remesh, ' ', cancel),
    running,
    status,
    stats,
    el('div', { class: 'buttons', title: 'Download the last quad mesh' }, 'Export ', obj, ' ', glb),
  );
  container.append(section);

  const targetValue = () => {
    const t = controller.state().target;
    return t.quads ?? t.edgeLength;
  };
  // The other kind of target for the same surface: a quad is about edge × edge.
  const convert = (t, to) => {
    if (to in t) return t;
    const A = area();
    if (to === 'quads') return { quads: A > 0 ? Math.max(1, Math.round(A / t.edgeLength ** 2)) : DEFAULT_TARGET.quads };
    return { edgeLength: A > 0 ? threeSignificant(Math.sqrt(A / t.quads)) : 1 };
  };
  // A Remesh refused for what the box holds: the status line says why while the box stays marked.
  let refused = false;
  // Takes the target, or marks the box with why not (kept as typed, never silently replaced); `remeshing`: for a
  // Remesh, which an invalid target then refuses in the status line. Returns whether the target was taken.
  const setTarget = (target, remeshing = false) => {
    size.removeAttribute('aria-invalid');
    refused = false;
    try {
      controller.setTarget(target);
      return true;
    } catch (err) {
      size.setAttribute('aria-invalid', 'true');
      size.title = err.message;
      refused = remeshing;
      refresh();
      return false;
    }
  };
  const readSize = () => (mode.value === 'quads' ? { quads: Number(size.value) } : { edgeLength: Number(size.value) });
  const download = (extension, type, make) => {
    try {
      const name = `${controller.modelName()}.quad.${extension}`;
      downloadBlob(name, new Blob([make()], { type }));
    } catch (err) {
      onError(err);
    }
  };
  const listeners = [
    [show, 'change', () => controller.setVisible(show.checked)],
    [mode, 'change', () => setTarget(convert(controller.state().target, mode.value))],
    [size, 'change', () => setTarget(readSize())],
    // The box as typed first: a target it cannot take is not run, nor the last one in its place. The panel shows
    // the outcome (the refusal, the core's words); the rejection has nowhere else to go.
    [remesh, 'click', () => {
      if (setTarget(readSize(), true)) controller.remesh().catch(() => {});
    }],
    [cancel, 'click', () => controller.cancel()],
    [obj, 'click', () => download('obj', 'model/obj', () => controller.exportObj())],
    [glb, 'click', () => download('glb', 'model/gltf-binary', () => controller.exportGlb())],
  ];
  for (const [target, type, fn] of listeners) target.addEventListener(type, fn);

  const refresh = () => {
    const s = controller.state();
    show.checked = s.visible;
    mode.value = 'quads' in s.target ? 'quads' : 'edgeLength';
    if (!size.hasAttribute('aria-invalid')) {
      if (section.getRootNode().activeElement !== size) size.value = String(targetValue());
      size.title = mode.value === 'quads' ? 'About this many quads' : "Quad edge length, in the model's units";
    }
    cancel.disabled = !s.running;
    running.hidden = !s.running;
    progress.value = s.fraction;
    setText(stage, s.running ? `${s.stage ?? ''} ${percent(s.fraction, 0)}` : '');
    const cross = controller.symmetry() === 4;
    remesh.title = cross ? REMESH_TITLE : `${QUAD_REFUSAL}: choose Cross (N = 4) in the Field panel`;
    const error = refused && !s.running ? size.title : s.error;
    const idle = s.stale ? STALE : s.hasResult ? '' : 'No quad mesh yet.';
    setText(status, error || (s.running ? 'Remeshing; the design stays editable.' : idle));
    status.classList.toggle('error', !!error);
    stats.replaceChildren(...(s.stats ? statsLines(s.stats).map((line) => el('div', { text: line })) : []));
    stats.classList.toggle('stale', s.stale);
    obj.disabled = glb.disabled = !s.hasResult;
  };
  refresh();
  return {
    refresh,
    dispose() {
      for (const [target, type, fn] of listeners) target.removeEventListener(type, fn);
      section.remove();
    },
  };
}

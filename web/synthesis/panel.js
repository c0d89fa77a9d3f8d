// SPDX-License-Identifier: GPL-2.0-or-later
// The "Texture" section of the side panel: exemplar picker (procedural ones or a PNG/JPEG of the user's), feature
// scale, atlas resolution, magnitude-driven scale, synthesize / off, PNG and GLB export, and a status line with
// the last synthesis times. Built here (no markup in index.html) and appended to the given container. The GLB
// button is the one GLB export's (downloadGlb, export/index.js): the model with the field and this texture.
import { canvasElement, el } from '../dom.js';
import { downloadBlob } from '../session/documents.js';

const fmt = (ms) => (ms < 10 ? ms.toFixed(1) : ms.toFixed(0));

export function mountSynthesisPanel(
  controller,
  container,
  { onError = (e) => console.error(e), modelName = () => 'model', downloadGlb = null } = {},
) {
  const exemplar = el('select', { id: 'tex-exemplar', title: 'The exemplar the texture is synthesized from' });
  for (const name of controller.proceduralNames()) exemplar.append(el('option', { value: name, text: name }));
  exemplar.append(el('option', { value: 'image', text: 'Image…' }));
  const file = el('input', { id: 'tex-file', type: 'file', accept: 'image/png,image/jpeg', hidden: '' });
  const preview = el('canvas', { id: 'tex-preview', width: '48', height: '48', title: 'Current exemplar' });
  preview.style.cssText = 'width:48px;height:48px;border:1px solid #555;display:block;margin:2px 0 4px';
  const scale = el('input', { id: 'tex-scale', type: 'range', min: '-1', max: '3', step: '0.25', value: '1' });
  const resolution = el('select', { id: 'tex-resolution', title: 'Atlas resolution (texels per side)' });
  resolution.append(el('option', { value: 'auto', text: 'auto' }));
  for (const r of [256, 512, 1024]) resolution.append(el('option', { value: String(r), text: String(r) }));
  resolution.value = 'auto';
  const autoScale = el('input', { id: 'tex-scale-auto', type: 'checkbox', checked: '' });
  const autoUpdate = el('input', { id: 'tex-auto-update', type: 'checkbox', checked: '' });
  const progress = el('progress', { id: 'tex-progress', max: '1', value: '0', hidden: '' });
  progress.style.cssText = 'width:100%;height:6px';
  const byMagnitude = el('input', { id: 'tex-magnitude', type: 'checkbox' });
  const go = el('button', {
    id: 'tex-synthesize',
    type: 'button',
    text: 'Synthesize',
    title: 'Synthesize the texture along the field; it follows every later field change',
  });
  const off = el('button', { id: 'tex-off', type: 'button', text: 'Off', title: 'Back to the plain surface' });
  const png = el('button', {
    id: 'tex-png',
    type: 'button',
    text: 'PNG',
    title: 'Download the synthesized atlas texture',
  });
  const glb = el('button', {
    id: 'tex-glb',
    type: 'button',
    text: 'GLB',
    title:
      'Download the model with the texture, the field and its flow map (binary glTF; the same file as Export › GLB)',
  });
  glb.hidden = !downloadGlb;
  const status = el('p', { id: 'tex-status', class: 'note', text: 'No texture yet.' });

  const section = el(
    'details',
    { id: 'texture-panel', open: '' },
    el('summary', { text: 'Texture' }),
    el('label', { title: 'Exemplar' }, 'Exemplar ', exemplar),
    preview,
    file,
    el(
      'label',
      { title: 'Texture feature size on the surface (log2; 0 = one exemplar pixel per atlas texel)' },
      'Scale ',
      scale,
    ),
    el(
      'label',
      { class: 'check', title: 'Feature size chosen from the model and the exemplar' },
      autoScale,
      ' auto scale',
    ),
    el('label', {}, 'Atlas ', resolution),
    el(
      'label',
      { class: 'check', title: 'Larger features where the field is stronger (paper, Sec. 6.3)' },
      byMagnitude,
      ' scale by magnitude',
    ),
    el(
      'label',
      { class: 'check', title: 'Resynthesize after every field change (a quick preview while edits come fast)' },
      autoUpdate,
      ' update texture automatically',
    ),
    el('div', { class: 'buttons' }, go, ' ', off, ' ', png, ' ', glb),
    progress,
    status,
  );
  container.append(section);

  const options = () => ({
    resolution: resolution.value === 'auto' ? 'auto' : Number(resolution.value),
    featureScale: autoScale.checked ? 'auto' : 2 ** Number(scale.value),
    magnitudeExponent: byMagnitude.checked ? 1 : 0,
  });

  // The exemplar's thumbnail is drawn when the exemplar changes, not at every refresh: a 2D canvas is drawn by
  // the GPU process, and while a synthesis keeps that busy a drawImage waited for it (923 ms over three
  // texture updates of an 832k-face model with software GL).
  let shownExemplar = null;
  function showPreview() {
    const info = controller.exemplar?.tables;
    if (!info || info === shownExemplar) return;
    shownExemplar = info;
    // The picker shows the exemplar in use, also when it was set through the API.
    const label = controller.exemplar.label;
    if (controller.proceduralNames().includes(label)) exemplar.value = label;
    else {
      let custom = exemplar.querySelector('option[data-custom]');
      if (!custom) {
        custom = el('option', { 'data-custom': '' });
        exemplar.insertBefore(custom, exemplar.lastChild);
      }
      custom.value = 'custom';
      custom.textContent = label;
      exemplar.value = 'custom';
    }
    drawThumbnail(info);
  }

  function drawThumbnail(info) {
    const ctx = preview.getContext('2d');
    const img = new ImageData(new Uint8ClampedArray(info.rgba8), info.size, info.size);
    const c = canvasElement(info.size, info.size);
    c.getContext('2d').putImageData(img, 0, 0);
    ctx.imageSmoothingEnabled = true;
    ctx.drawImage(c, 0, 0, 48, 48);
  }

  // Until an exemplar is chosen or a texture made, the one a synthesis would use (analysed in the core's worker
  // once it has started, and kept for that synthesis).
  controller
    .defaultExemplar()
    .then((tables) => !controller.exemplar && !shownExemplar && drawThumbnail(tables))
    .catch(() => {});

  function showStats() {
    const p = controller.progressShown;
    progress.hidden = !p;
    if (p) {
      progress.value = p.fraction;
      status.textContent = `${p.preview ? 'Preview' : 'Synthesizing'}… ${Math.round(100 * p.fraction)}%`;
      return;
    }
    const s = controller.synthesisStats();
    if (!s) {
      // Active but stale with nothing running: a new model while automatic updates are off.
      if (controller.active && controller.stale)
        status.textContent = 'No texture for this model yet: Synthesize makes one.';
      else status.textContent = controller.active ? 'Synthesizing…' : 'No texture yet.';
      return;
    }
    // The controls show the options in use, also when they were set through the API.
    if (!s.autoResolution && [256, 512, 1024].includes(s.atlas.resolution))
      resolution.value = String(s.atlas.resolution);
    autoScale.checked = !!s.autoFeatureScale;
    const log2Scale = Math.log2(s.featureScale);
    if (log2Scale >= Number(scale.min) && log2Scale <= Number(scale.max)) scale.value = String(log2Scale);
    byMagnitude.checked = s.magnitudeExponent > 0;
    const levels = s.levels.map((l) => `${l.size}²:${fmt(l.ms)}`).join(' ');
    const notes = `${s.preview ? ' · preview' : ''}${controller.stale ? ' · field changed' : ''}`;
    const atlas = `${s.atlas.resolution}² ${s.atlas.source} atlas`;
    status.textContent = `${s.exemplar?.label ?? ''} · ${atlas} · ${fmt(s.totalMs)} ms (${levels})${notes}`;
    const analysisMs = fmt(s.exemplar?.analysisMs ?? 0);
    status.title = `atlas: ${s.atlas.reason}\nanalysis: ${analysisMs} ms${s.exemplar?.cached ? ' (cached)' : ''}`;
  }

  const busy = (on) => {
    for (const b of [go, png, glb]) b.disabled = on;
    if (on) status.textContent = 'Synthesizing…';
  };
  const run = async (fn) => {
    busy(true);
    try {
      await fn();
    } catch (err) {
      onError(err);
    } finally {
      busy(false);
      showStats();
      showPreview();
    }
  };

  exemplar.addEventListener('change', () => {
    if (exemplar.value === 'image') return file.click();
    if (exemplar.value === 'custom') return;
    run(() => controller.setExemplar(exemplar.value));
  });
  file.addEventListener('change', () => {
    const f = file.files?.[0];
    file.value = '';
    if (f) run(() => controller.setExemplar(f));
  });
  go.addEventListener('click', () => run(() => controller.synthesize(options())));
  off.addEventListener('click', () => run(() => controller.clearTexture()));
  scale.addEventListener('input', () => (autoScale.checked = false));
  autoUpdate.addEventListener('change', () => controller.setAutoUpdate(autoUpdate.checked));
  for (const input of [scale, autoScale, resolution, byMagnitude]) {
    input.addEventListener('change', () => {
      if (controller.active) run(() => controller.synthesize(options()));
    });
  }
  png.addEventListener('click', () =>
    run(async () =>
      downloadBlob(`${modelName()}-texture.png`, await controller.exportTexturePNG({ magnification: 2 })),
    ),
  );
  glb.addEventListener('click', () => run(() => downloadGlb()));

  const refresh = () => {
    showStats();
    showPreview();
  };
  return { refresh };
}

// SPDX-License-Identifier: GPL-2.0-or-later
// The "Export" section of the side panel: flow map size / convention / bits, anisotropy strength and
// rotation, the Flow map and GLB downloads, the quad meshers' files (.sing, .rosy, .sharp), and the material
// preview with its presets. Built here and appended to the given container; `actions` receives what the user
// chose.
import { el, setText } from '../dom.js';

function select(id, title, values, value) {
  const s = el('select', { id, title });
  for (const [v, text] of values) s.append(el('option', { value: String(v), text }));
  s.value = String(value);
  return s;
}

export function mountExportPanel(container, actions) {
  const { options, presets, onOptions, onFlowMap, onGlb, onRawField, onSing, onRosy, onSharp, onPreview } = actions;
  const size = select(
    'export-size',
    'Flow map texels per side',
    [256, 512, 1024, 2048, 4096].map((n) => [n, String(n)]),
    options.size,
  );
  const convention = select(
    'export-convention',
    'gltf: G = 0.5 + 0.5·dv (three.js, Babylon.js, Unreal through glTF). ' +
      'opengl: G = 0.5 − 0.5·dv (Unity, Blender, Godot flip v on import)',
    [['gltf', 'glTF'], ['opengl', 'OpenGL (v flipped)']],
    options.convention,
  );
  const bits = select('export-bits', 'Bits per channel', [[8, '8-bit'], [16, '16-bit']], options.bits);
  const strength = el('input', {
    id: 'export-strength',
    type: 'number',
    min: '0',
    max: '1',
    step: '0.05',
    value: String(options.strength),
  });
  const rotation = el('input', {
    id: 'export-rotation',
    type: 'number',
    step: '15',
    value: String((options.rotation * 180) / Math.PI),
  });
  const flowMap = el('button', {
    id: 'export-flowmap',
    type: 'button',
    text: 'Flow map',
    title: "Download the flow map PNG (the field in the model's UV square)",
  });
  const glbTitle =
    'Download the model with the field: TANGENT along it, _FIELD, KHR_materials_anisotropy, flow map, design ' +
    'and the synthesized texture (when one is shown) inside';
  const glb = el('button', { id: 'export-glb', type: 'button', text: 'GLB', title: glbTitle });
  // Line and cross fields only: all N directions per face, as Directional's tools (and quad remeshers fed by
  // them) read them (docs/export.md).
  const rawField = el('button', {
    id: 'export-rawfield',
    type: 'button',
    text: 'Cross-field file',
    hidden: true,
    title:
      'Download the field as a raw field (.rawfield: "N numF", then the N directions of each face), the format ' +
      'Directional reads, for quad remeshing',
  });
  // The quad meshers' files (docs/export.md): what Directional and QuadWild read.
  const sing = el('button', {
    id: 'export-sing',
    type: 'button',
    text: '.sing',
    title: "Download the field's singularities, prescribed and placed alike, as Directional's .sing",
  });
  const rosyTitle = "Download the cross field as QuadWild's .rosy (one direction per face)";
  const rosy = el('button', { id: 'export-rosy', type: 'button', text: '.rosy', title: rosyTitle });
  const sharp = el('button', {
    id: 'export-sharp',
    type: 'button',
    text: '.sharp',
    title: "Download the feature edges the field follows (and the border) as QuadWild's .sharp",
  });
  const preview = select(
    'export-preview',
    'Show the exported material (physical, anisotropic along the field) under a studio environment',
    [['', 'off'], ...presets.map((p) => [p, p])],
    '',
  );

  const section = el(
    'details',
    { id: 'export-panel' },
    el('summary', { text: 'Export' }),
    el('label', {}, 'Size ', size),
    el('label', {}, 'Convention ', convention),
    el('label', {}, 'Bits ', bits),
    el('label', { title: 'KHR_materials_anisotropy strength (0..1)' }, 'Anisotropy ', strength),
    el('label', { title: 'Rotation of the highlights from the field direction, degrees' }, 'Rotation° ', rotation),
    el('div', { class: 'buttons' }, flowMap, ' ', glb, ' ', rawField),
    el('div', { class: 'buttons', id: 'export-quad', title: 'Files for quad meshers' }, sing, ' ', rosy, ' ', sharp),
    el('label', {}, 'Material preview ', preview),
  );
  container.append(section);

  const listeners = [
    [size, 'change', () => onOptions({ size: Number(size.value) })],
    [convention, 'change', () => onOptions({ convention: convention.value })],
    [bits, 'change', () => onOptions({ bits: Number(bits.value) })],
    [strength, 'change', () => onOptions({ strength: Math.min(1, Math.max(0, Number(strength.value) || 0)) })],
    [rotation, 'change', () => onOptions({ rotation: ((Number(rotation.value) || 0) * Math.PI) / 180 })],
    [flowMap, 'click', () => onFlowMap()],
    [glb, 'click', () => onGlb()],
    [rawField, 'click', () => onRawField()],
    [sing, 'click', () => onSing()],
    [rosy, 'click', () => onRosy()],
    [sharp, 'click', () => onSharp()],
    [preview, 'change', () => onPreview(preview.value || null)],
  ];
  for (const [target, type, fn] of listeners) target.addEventListener(type, fn);

  return {
    setOptions(o) {
      size.value = String(o.size);
      convention.value = o.convention;
      bits.value = String(o.bits);
      strength.value = String(o.strength);
      rotation.value = String((o.rotation * 180) / Math.PI);
    },
    // N >= 2: the GLB is an anisotropy GLB (the direction has no sign, which KHR_materials_anisotropy does not
    // see), and the raw field applies.
    setSymmetry(n) {
      rawField.hidden = n < 2;
      // .rosy holds a cross field alone: disabled otherwise, with the reason where the user looks.
      rosy.disabled = n !== 4;
      rosy.title = n === 4 ? rosyTitle : `${rosyTitle}; a .rosy holds a cross field (N = 4): choose Cross`;
      setText(glb, n === 2 ? 'Anisotropy GLB' : 'GLB');
      const combed =
        `the ${n === 2 ? 'line' : 'cross'} field combed to one direction per region ` +
        '(KHR_materials_anisotropy does not see its sign)';
      glb.title = n >= 2 ? `${glbTitle}; ${combed}` : glbTitle;
    },
    setPreview(preset) {
      preview.value = preset ?? '';
    },
    dispose() {
      for (const [target, type, fn] of listeners) target.removeEventListener(type, fn);
      section.remove();
    },
  };
}

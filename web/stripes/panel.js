// SPDX-License-Identifier: GPL-2.0-or-later
// The "Stripes" section of the side panel: show, profile, stripes per unit length (or the model's default),
// spacing by the field's magnitude (vector fields), the spacing adapted to the field, stripes across the field,
// the lines' width, the two colours, and a status line with the pattern's times. Built here and appended to the
// given container; every control goes through the controller's setStripes, as the API's calls do. Imports dom.js
// and its own folder.
import { el } from '../dom.js';
import { PROFILE_LABELS, PROFILES, TWO_FAMILY_PROFILES } from './profiles.js';

const fmt = (ms) => (ms < 10 ? ms.toFixed(1) : ms.toFixed(0));

export function mountStripesPanel(controller, container, { onError = (e) => console.error(e) } = {}) {
  const show = el('input', { id: 'stripes-show', type: 'checkbox' });
  const profile = el('select', { id: 'stripes-profile', title: 'How the phase is drawn' });
  for (const name of PROFILES) profile.append(el('option', { value: name, text: PROFILE_LABELS[name] }));
  const frequency = el('input', {
    id: 'stripes-frequency',
    type: 'number',
    min: '0',
    step: 'any',
    title: 'Stripes per unit length of the model (empty: about 40 across the model)',
  });
  const magnitude = el('input', {
    id: 'stripes-magnitude',
    type: 'range',
    min: '0',
    max: '1',
    step: '0.05',
    value: '0',
    title: 'Denser stripes where the field is stronger (0: even spacing; vector fields)',
  });
  const adapt = el('input', {
    id: 'stripes-adapt',
    type: 'checkbox',
    title: 'The spacing gives way so that the stripes follow the field exactly (off: even spacing)',
  });
  const across = el('input', {
    id: 'stripes-across',
    type: 'checkbox',
    title: "A vector or line field's stripes across it instead of along it (a cross field has both)",
  });
  const width = el('input', {
    id: 'stripes-width',
    type: 'range',
    min: '0.02',
    max: '1',
    step: '0.02',
    title: "The lines' width, a share of a period (stripes' dark bands, grid lines, mortar, threads)",
  });
  const light = el('input', { id: 'stripes-light', type: 'color', title: 'Light colour' });
  const dark = el('input', { id: 'stripes-dark', type: 'color', title: 'Dark colour' });
  const status = el('p', { id: 'stripes-status', class: 'note', text: 'Stripes follow the field exactly.' });
  const section = el(
    'details',
    { id: 'stripes-panel' },
    el('summary', { text: 'Stripes' }),
    el('label', { class: 'check', title: 'Stripe pattern along the field (Knöppel et al. 2015)' }, show, ' Show'),
    el('label', {}, 'Profile ', profile),
    el('label', {}, 'Per unit ', frequency),
    el('label', {}, 'By magnitude ', magnitude),
    el('label', { class: 'check' }, adapt, ' follow the field exactly'),
    el('label', { class: 'check' }, across, ' across the field'),
    el('label', {}, 'Line width ', width),
    el('label', {}, 'Colours ', light, ' ', dark),
    status,
  );
  container.append(section);

  const set = (opts) => controller.setStripes(opts).catch(onError);
  show.addEventListener('change', () => set({ visible: show.checked }));
  profile.addEventListener('change', () => set({ profile: profile.value }));
  frequency.addEventListener('change', () => {
    const v = frequency.value.trim();
    set({ frequency: v === '' ? null : Number(v) });
  });
  magnitude.addEventListener('change', () => set({ magnitudeSpacing: Number(magnitude.value) }));
  adapt.addEventListener('change', () => set({ adaptSpacing: adapt.checked }));
  across.addEventListener('change', () => set({ across: across.checked }));
  width.addEventListener('change', () => set({ width: Number(width.value) }));
  light.addEventListener('change', () => set({ light: light.value }));
  dark.addEventListener('change', () => set({ dark: dark.value }));

  const refresh = () => {
    const s = controller.state(), symmetry = controller.getField()?.symmetry ?? 1;
    show.checked = s.visible;
    for (const o of profile.options) o.disabled = symmetry === 4 && !TWO_FAMILY_PROFILES.includes(o.value);
    profile.value = s.profile;
    if (section.getRootNode().activeElement !== frequency) frequency.value = String(s.frequency);
    magnitude.value = String(s.magnitudeSpacing);
    magnitude.disabled = symmetry !== 1;
    adapt.checked = s.adaptSpacing;
    across.checked = s.across;
    across.disabled = symmetry === 4;
    width.value = String(s.width);
    light.value = s.light;
    dark.value = s.dark;
    if (s.error) status.textContent = s.error;
    else if (s.stats?.zeroField)
      status.textContent = 'The field is zero everywhere: draw a stroke or drop a source for the stripes to follow.';
    else if (s.stats) {
      const t = s.stats;
      // A frequency fitted to the surface's loops is not the one asked for: say so.
      const fitted = t.loopFit && t.loopFit !== 1
        ? ` ${(s.frequency * t.loopFit).toPrecision(3)} per unit, fitted so that whole stripes go round its loops.`
        : '';
      status.textContent = `${t.families === 2 ? 'Two families' : 'One family'}: ${t.iterations} steps, ` +
        `${fmt(t.workerMs)} ms in the worker, ${fmt(t.roundTripMs)} ms in all.${fitted}`;
    }
  };
  refresh();
  return { refresh };
}

// The side panels: field settings (symmetry, curvature alignment, boundary, smoothness, the feature angle, what
// the prescribed singularities leave to the field), the views and their legend, and the constraint list with the
// selection editor. Reports user intent through `actions` and renders the state it
// is handed; a box the user is typing in is never overwritten.
import { setText } from '../dom.js';
import { checkedNumber, fmtNum, guarded } from './numbers.js';
import { alignsToCurvature } from '../session/symmetry.js';
import { indexLabel, PRESCRIBED_RING } from '../views/singularity-style.js';

const SWATCH = {
  stroke: '#ff7a1a',
  vector: '#fbbf24',
  edge: '#ff7a1a',
  source: '#ef4444',
  sink: '#22c55e',
  vortex: '#3b82f6',
  singularity: PRESCRIBED_RING,
};
const VIEW_INPUTS = [
  'show-arrows',
  'arrow-density',
  'arrow-scaled',
  'show-streamlines',
  'streamline-spacing',
  'show-lic',
  'show-colormap',
  'show-singularities',
  'view-component',
];
const SHARE_PARTS = ['exact', 'coexact', 'harmonic'];

const title = (type) => `${type[0].toUpperCase()}${type.slice(1)}`;

// An index as a fraction in lowest terms over the smallest N up to 6 that writes it exactly ("3/2", "−1/4").
function fraction(x, plus = '') {
  const n = [1, 2, 3, 4, 5, 6].find((k) => Math.abs(x * k - Math.round(x * k)) < 1e-9) ?? 6;
  const label = indexLabel(x, n);
  return label.startsWith('+') ? `${plus}${label.slice(1)}` : label;
}

// What the prescribed singularities leave to the field, in words ({mode, eulerCharacteristic, prescribedIndex,
// freeIndex}); '' when none are prescribed.
export function singularitySummaryText(summary) {
  if (!summary || summary.mode === 'none') return '';
  const { eulerCharacteristic: chi, prescribedIndex: p, freeIndex: free } = summary;
  const head = `χ = ${chi}, prescribed ${fraction(p)}`;
  if (summary.mode === 'exact') return `${head}: the field has these singularities and no other.`;
  return `${head}: the field places ${fraction(free, '+')} itself.`;
}

function describe(c) {
  switch (c.type) {
    case 'stroke': return `${c.points.length} points · strength ${fmtNum(c.strength)} · weight ${fmtNum(c.weight)}`;
    case 'vector': return `face ${c.face} · size ${fmtNum(Math.hypot(...c.vector))} · weight ${fmtNum(c.weight)}`;
    case 'edge': return `${c.edge[0]}→${c.edge[1]} = ${fmtNum(c.value)} · weight ${fmtNum(c.weight)}`;
    case 'source':
    case 'sink': return `vertex ${c.vertex} · strength ${fmtNum(c.strength)}`;
    case 'vortex': return `face ${c.face} · ${c.strength >= 0 ? 'CCW' : 'CW'} ${fmtNum(Math.abs(c.strength))}`;
    case 'singularity': return `vertex ${c.vertex} · index ${fraction(c.index, '+')}`;
    default: return '';
  }
}

function listItem(c) {
  const li = document.createElement('li');
  li.dataset.constraintId = String(c.id);
  const label = document.createElement('span');
  label.className = 'label';
  const sw = document.createElement('span');
  sw.className = 'swatch';
  sw.style.background = SWATCH[c.type] ?? '#999';
  label.append(sw, `${title(c.type)} #${c.id}`);
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
}

// The list's rows made to show `constraints` (in that order), each kept while its text stays the same: every
// edit and selection came with the whole list, and a list rebuilt each time had the page lay all of it out
// again (300 constraints: ~30 ms an edit, in the view's next read of its size). rows: id → {li, text}, the
// caller's, updated here.
function syncRows(list, rows, constraints, selected) {
  const wanted = new Map();
  for (const c of constraints) {
    const text = `${c.type}|${describe(c)}`;
    let row = rows.get(c.id);
    if (!row || row.text !== text) row = { li: listItem(c), text };
    row.li.classList.toggle('selected', c.id === selected);
    wanted.set(c.id, row);
  }
  let next = list.firstChild;
  for (const { li } of wanted.values()) {
    if (li === next) next = next.nextSibling;
    else list.insertBefore(li, next);
  }
  while (next) {
    const after = next.nextSibling;
    next.remove();
    next = after;
  }
  rows.clear();
  for (const [id, row] of wanted) rows.set(id, row);
}

// $: querySelector in the shadow root; focused(): the shadow root's active element; showError: the banner.
export function bindPanels($, focused, actions, showError) {
  const guard = (fn) => guarded(showError, fn);
  let selectedUid = null;

  // ---- field settings
  const boundarySelect = $('#boundary');
  const angleInput = $('#boundary-angle');
  const gamma = $('#gamma');
  function boundaryChoice() {
    if (boundarySelect.value !== 'angle') return boundarySelect.value;
    const deg = Number(angleInput.value);
    return { angle: ((Number.isFinite(deg) ? deg : 0) * Math.PI) / 180 };
  }
  boundarySelect.addEventListener('change', () => {
    $('#boundary-angle-row').hidden = boundarySelect.value !== 'angle';
    actions.onBoundary(boundaryChoice());
  });
  angleInput.addEventListener(
    'change',
    guard(() => {
      checkedNumber(angleInput, 'The boundary angle');
      return actions.onBoundary(boundaryChoice());
    }),
  );
  gamma.addEventListener('change', guard((e) => actions.onGamma(checkedNumber(e.target, 'Smoothness γ'))));
  const featureAngle = $('#feature-angle');
  featureAngle.addEventListener(
    'change',
    guard((e) => actions.onFeatureAngle(checkedNumber(e.target, 'The feature angle'))),
  );

  const exactSingularities = $('#exact-singularities');
  exactSingularities.addEventListener('change', () => actions.onExactSingularities(exactSingularities.checked));

  // features: {angle, count, folds} (count: the edges in use, null while unknown; folds: the model's
  // info.folds, which say why a faceted curved surface starts without features); summary: singularitySummaryText's.
  function setFeatures({ angle, count, folds }) {
    if (Number.isFinite(angle) && focused() !== featureAngle) featureAngle.value = String(angle);
    const note = $('#feature-count');
    note.hidden = count == null;
    let text = count === 1 ? '1 feature edge' : `${count} feature edges`;
    if (count === 0 && angle === 0 && folds?.suggestedFeatureAngle === 0 && folds.sharpEdges > 0) {
      const [sharp, long] = [folds.sharpShare, folds.longCurveShare].map((x) => Math.round(100 * x));
      text += ` (a curved surface of facets: ${sharp} % of its folds sharp, ${long} % of those on long lines)`;
    }
    setText(note, text);
  }
  function setSingularitySummary(summary) {
    const text = singularitySummaryText(summary), note = $('#singularity-summary');
    note.hidden = !text;
    setText(note, text);
  }

  // ---- symmetry and curvature alignment: the checkbox turns the alignment on at the strength in the box.
  const symmetry = $('#symmetry');
  const align = $('#curvature-align');
  const alignStrength = $('#curvature-strength');
  const alignment = () => (align.checked ? checkedNumber(alignStrength, 'The curvature alignment strength') : 0);
  symmetry.addEventListener('change', () => actions.onSymmetry(Number(symmetry.value)));
  align.addEventListener('change', guard(() => actions.onCurvatureAlignment(alignment())));
  alignStrength.addEventListener('change', guard(() => align.checked && actions.onCurvatureAlignment(alignment())));

  // n: 1..6; the selector names 1, 2 and 4 and shows any other N the API set as 'N = n'.
  function setSymmetry(n, strength) {
    const other = $('#symmetry-other');
    const named = [...symmetry.options].some((o) => o !== other && o.value === String(n));
    other.hidden = named;
    if (!named) Object.assign(other, { value: String(n), textContent: `N = ${n}` });
    symmetry.value = String(n);
    const available = alignsToCurvature(n);
    const row = $('#curvature-row');
    align.disabled = !available;
    alignStrength.disabled = !available;
    row.title = available
      ? 'Pulls the field toward principal curvature directions: the usual start for quad remeshing and hatching'
      : 'Only for line and cross fields (an even symmetry): principal curvature directions have no sign and come ' +
        'in pairs at right angles';
    align.checked = strength > 0;
    if (strength > 0 && focused() !== alignStrength) alignStrength.value = String(strength);
  }

  // A line or cross field has an energy of its own (core/direction/): a free boundary, no γ, no decomposition.
  // Their controls stay, greyed, with the reason, and come back with a vector field.
  const VECTOR_ONLY = ['#boundary', '#boundary-angle', '#gamma', '#view-component'];
  const vectorTitles = new Map(VECTOR_ONLY.map((sel) => [sel, $(sel).closest('label').title]));
  const VECTOR_ONLY_REASON =
    'For vector fields only: a line or cross field has a free boundary, no γ and no Hodge decomposition.';
  function setVectorOnly(n) {
    for (const sel of VECTOR_ONLY) {
      $(sel).disabled = n > 1;
      $(sel).closest('label').title = n > 1 ? `${VECTOR_ONLY_REASON} ${vectorTitles.get(sel)}` : vectorTitles.get(sel);
    }
  }

  function setSettings({ boundary, gamma: g, symmetry: n = 1, curvatureAlignment = 0, exactSingularities: x = false }) {
    exactSingularities.checked = x;
    const isAngle = typeof boundary !== 'string';
    boundarySelect.value = isAngle ? 'angle' : boundary;
    $('#boundary-angle-row').hidden = !isAngle;
    if (isAngle && focused() !== angleInput) angleInput.value = String(+((boundary.angle * 180) / Math.PI).toFixed(6));
    if (focused() !== gamma) gamma.value = String(g);
    setSymmetry(n, curvatureAlignment);
    setVectorOnly(n);
  }

  function setHasBoundary(has) {
    $('#boundary-row').hidden = !has;
    $('#boundary-note').hidden = !has;
  }

  // ---- views
  for (const id of VIEW_INPUTS) $(`#${id}`).addEventListener('input', () => actions.onViews(views()));
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
      component: $('#view-component').value,
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
    if ('component' in v) $('#view-component').value = v.component;
    if ('shares' in v) showShares(v.shares);
  }
  // The energy share of each part of the decomposition ({exact, coexact, harmonic, current}; null: hidden);
  // dimmed while they are an earlier field's.
  function showShares(shares) {
    const box = $('#component-shares');
    box.hidden = !shares;
    if (!shares) return;
    box.classList.toggle('stale', !shares.current);
    for (const part of SHARE_PARTS) {
      const x = shares[part];
      const text = Number.isFinite(x) ? `${(100 * x).toFixed(1)} %` : '–';
      box.querySelector(`[data-share="${part}"]`).textContent = text;
    }
  }

  function setLegend(max) {
    $('#legend').hidden = max == null;
    if (max != null) setText($('#legend-max'), `≥ ${fmtNum(max)}`);
  }

  // ---- constraint list and selection editor
  const list = $('#constraint-list');
  const rows = new Map(); // the list's rows by constraint id (syncRows)
  list.addEventListener('click', (e) => {
    const li = e.target.closest('[data-constraint-id]');
    if (!li) return;
    const uid = Number(li.dataset.constraintId);
    if (e.target.closest('button.delete')) actions.onRemove(uid);
    else actions.onSelect(uid);
  });
  $('#clear-all').addEventListener('click', () => actions.onClear());
  $('#sel-delete').addEventListener('click', () => selectedUid != null && actions.onRemove(selectedUid));
  $('#sel-weight').addEventListener(
    'change',
    guard((e) => selectedUid != null && actions.onEditWeight(selectedUid, checkedNumber(e.target, 'The weight'))),
  );
  $('#sel-strength').addEventListener(
    'change',
    guard((e) => selectedUid != null && actions.onEditStrength(selectedUid, checkedNumber(e.target, 'The strength'))),
  );

  // constraints: [{id, type, ...spec}] in the page's order; selected: id or null.
  function setConstraints(constraints, selected) {
    selectedUid = selected;
    syncRows(list, rows, constraints, selected);
    $('#constraints-empty').hidden = constraints.length > 0;
    const sel = constraints.find((c) => c.id === selected);
    $('#selection-panel').hidden = !sel;
    if (!sel) return;
    $('#selection-title').textContent = `${title(sel.type)} #${sel.id}`;
    const hasWeight = 'weight' in sel, hasStrength = 'strength' in sel;
    $('#sel-weight-row').hidden = !hasWeight;
    $('#sel-strength-row').hidden = !hasStrength;
    if (hasWeight && focused() !== $('#sel-weight')) $('#sel-weight').value = String(sel.weight);
    if (hasStrength && focused() !== $('#sel-strength')) $('#sel-strength').value = String(sel.strength);
  }

  return {
    setSettings,
    setFeatures,
    setSingularitySummary,
    setHasBoundary,
    views,
    setViews,
    setLegend,
    setConstraints,
    get selected() {
      return selectedUid;
    },
  };
}

// The values of the element's attributes, parsed (element.js): an attribute's text is the element's to read, and
// a bad one is refused with what it holds (the `error` event, code 'attribute'). The setting values themselves
// are still the core's to check.

const VIEW_NAMES = ['arrows', 'streamlines', 'lic', 'magnitude', 'singularities', 'texture', 'stripes'];
export const DEFAULT_VIEWS = 'arrows';

export function parseBoundary(text) {
  const t = String(text).trim();
  if (['free', 'tangential', 'normal'].includes(t)) return t;
  const angle = Number(t);
  if (t !== '' && Number.isFinite(angle)) return { angle };
  throw new Error(`boundary must be free, tangential, normal or an angle in radians (got "${text}")`);
}

// A number attribute's value (kind: its property, attr: its name): symmetry a whole number 1..6 (what the
// core takes; the panel names 1, 2 and 4), gamma and curvature-alignment ≥ 0.
export function parseSetting(kind, attr, text) {
  const x = Number(text);
  if (kind === 'symmetry' && !(Number.isInteger(x) && x >= 1 && x <= 6))
    throw new Error(`symmetry must be a whole number from 1 to 6 (got "${text}")`);
  if (kind !== 'symmetry' && !(x >= 0)) throw new Error(`${attr} must be a number ≥ 0 (got "${text}")`);
  return x;
}

export function parseViews(text) {
  const names = String(text).split(/\s+/).filter(Boolean);
  const unknown = names.filter((n) => !VIEW_NAMES.includes(n));
  if (unknown.length) throw new Error(`unknown view "${unknown[0]}" (views: ${VIEW_NAMES.join(' ')})`);
  return new Set(names);
}

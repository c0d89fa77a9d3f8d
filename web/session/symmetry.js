// The symmetry N of the designed field — 1 a vector field, 2 a line field, 4 a cross field (the core takes 1..6)
// — in the page's words: what each is called, which constraints only a vector field can have, and the refusals
// of what is not made for N ≥ 2 yet. One place for them: the session's SetSymmetry command, the panels and the
// synthesis all say the same. (The core's worker has its own words for its one refusal: core/core-export.js.)
// Imports nothing.

// A source, sink or vortex has a sign and a flux, an edge value is a line integral: notions of a vector field,
// which a line or cross field (directions without sign) has none of. The core refuses them for N ≥ 2.
export const VECTOR_ONLY_TYPES = ['source', 'sink', 'vortex', 'edge'];

const NAMES = { 1: 'Vector', 2: 'Line', 4: 'Cross' };

// 'Vector', 'Line', 'Cross', or 'N = 3' for the symmetries the panel has no name for.
export const symmetryName = (n) => NAMES[n] ?? `N = ${n}`;

// 'Line field' / 'a line field', or 'Symmetry N = 3' / 'a field of symmetry 3'.
export const fieldTitle = (n) => (NAMES[n] ? `${NAMES[n]} field` : `Symmetry N = ${n}`);
export const fieldPhrase = (n) => (NAMES[n] ? `a ${NAMES[n].toLowerCase()} field` : `a field of symmetry ${n}`);

export const keepsConstraint = (type, n) => !(n >= 2 && VECTOR_ONLY_TYPES.includes(type));

// A design's constraint under symmetry n: as its type allows, and a prescribed singularity only while its index
// is a multiple of 1/n (+1/4 means nothing to a line field).
export function keepsSpec(spec, n) {
  if (spec.type !== 'singularity') return keepsConstraint(spec.type, n);
  return Math.abs(spec.index * n - Math.round(spec.index * n)) < 1e-9;
}

// Principal curvature directions are lines (no sign) and come in perpendicular pairs: a field can be pulled
// towards them only when its own N is even.
export const alignsToCurvature = (n) => n >= 2 && n % 2 === 0;

const PLURAL = { source: 'sources', sink: 'sinks', vortex: 'vortices', edge: 'edge constraints',
  singularity: 'singularities' };
const SINGULAR = { edge: 'edge constraint' };

// [{type}] → '2 sources and 1 vortex' (types in first-seen order).
export function countedTypes(constraints) {
  const counts = new Map();
  for (const { type } of constraints) counts.set(type, (counts.get(type) ?? 0) + 1);
  const counted = (type, n) => (n === 1 ? (SINGULAR[type] ?? type) : (PLURAL[type] ?? `${type}s`));
  const parts = [...counts].map(([type, n]) => `${n} ${counted(type, n)}`);
  return parts.length > 1 ? `${parts.slice(0, -1).join(', ')} and ${parts.at(-1)}` : (parts[0] ?? '');
}

// Texture synthesis follows a vector field, and a line or cross field combed for the atlas (one sign, or one of
// the cross's two families, per region: geometry/chart-comb.js); other N it refuses with this reason.
export const TEXTURE_SYMMETRIES = [1, 2, 4];
export const textureRefusal = (n) =>
  `texture synthesis follows vector, line and cross fields (N = 1, 2, 4), not ${fieldPhrase(n)}; ` +
  'switch to Vector, Line or Cross';

// Constraint specs in the design format (docs/design-format.md, the one schema) from the public API's and the
// tools' arguments. Nothing here checks a value: the core validates every spec once, with the mesh at hand,
// and its refusal names the bad field. Arrays are made plain (a Float64Array would not survive JSON).
const iterable = (v) => v != null && typeof v === 'object' && typeof v[Symbol.iterator] === 'function';
const list = (v) => (iterable(v) ? Array.from(v) : v);

const point = (p) => ({ face: p?.face, bary: list(p?.bary) });

export const strokeSpec = (points, { strength, weight }) => ({
  type: 'stroke',
  points: Array.isArray(points) ? points.map(point) : points,
  strength,
  weight,
});

export const vectorSpec = (face, vector, { weight }) => ({ type: 'vector', face, vector: list(vector), weight });

export const edgeSpec = (edge, value, { weight }) => ({ type: 'edge', edge: list(edge), value, weight });

// type: 'source' | 'sink' (at a vertex) or 'vortex' (in a face).
export const pointSpec = (type, where, strength) => ({
  type,
  ...(type === 'vortex' ? { face: where } : { vertex: where }),
  strength,
});

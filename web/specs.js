// Checked design-format specs (docs/design-format.md) from the arguments of the public API and the tools.
// Each throws a readable Error naming the bad argument; indices are checked against the session's mesh.

// Number(null), Number('') and Number(false) are 0: a missing value must not become face 0 or weight 0.
function numeric(x) {
  return x === null || x === undefined || x === '' || typeof x === 'boolean' ? NaN : Number(x);
}

export function finite(x, what) {
  const v = numeric(x);
  if (!Number.isFinite(v)) throw new Error(`${what} must be a finite number (got ${x})`);
  return v;
}

function index(x, what, count) {
  const v = numeric(x);
  if (!Number.isInteger(v) || v < 0 || v >= count) throw new Error(`${what} ${x} is out of range (0…${count - 1})`);
  return v;
}

function vec3(v, what) {
  const a = Array.from(v ?? [], numeric);
  if (a.length !== 3 || !a.every(Number.isFinite)) throw new Error(`${what} must be 3 finite numbers`);
  return a;
}

const faceIndex = (s, f) => index(f, 'face', s.info.faces);
const vertexIndex = (s, v) => index(v, 'vertex', s.info.vertices);

function points(s, list) {
  if (!Array.isArray(list) || list.length < 2) throw new Error('a stroke needs at least 2 points');
  const nF = s.info.faces;
  return list.map((p, k) => {
    const face = numeric(p?.face);
    const bary = Array.from(p?.bary ?? [], numeric);
    if (!Number.isInteger(face) || face < 0 || face >= nF) throw new Error(`stroke point ${k}: face ${p?.face} out of range`);
    if (bary.length !== 3 || !bary.every(Number.isFinite)) throw new Error(`stroke point ${k}: bary must be 3 finite numbers`);
    return { face, bary };
  });
}

export const strokeSpec = (s, list, { strength, weight }) => ({
  type: 'stroke',
  points: points(s, list),
  strength: finite(strength, 'strength'),
  weight: finite(weight, 'weight'),
});

export const vectorSpec = (s, face, vector, { weight }) => ({
  type: 'vector',
  face: faceIndex(s, face),
  vector: vec3(vector, 'vector'),
  weight: finite(weight, 'weight'),
});

export function edgeSpec(s, edge, value, { weight }) {
  const [i, j] = Array.from(edge ?? [], numeric);
  return { type: 'edge', edge: [vertexIndex(s, i), vertexIndex(s, j)], value: finite(value, 'value'), weight: finite(weight, 'weight') };
}

// type: 'source' | 'sink' (at a vertex) or 'vortex' (in a face).
export function pointSpec(s, type, where, strength) {
  const at = type === 'vortex' ? { face: faceIndex(s, where) } : { vertex: vertexIndex(s, where) };
  return { type, ...at, strength: finite(strength, 'strength') };
}

export function boundarySpec(bc) {
  if (typeof bc === 'string') return bc;
  if (bc && typeof bc === 'object') return structuredClone(bc);
  throw new Error(`boundary must be 'free', 'tangential', 'normal' or {angle} (got ${JSON.stringify(bc)})`);
}

export function gammaSpec(gamma) {
  if (!(Number.isFinite(gamma) && gamma >= 0)) throw new Error(`gamma must be a number ≥ 0 (got ${gamma})`);
  return gamma;
}

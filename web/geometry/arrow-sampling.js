// Arrow anchors spaced by the screen, not by the mesh: dart throwing by surface area (faces drawn with
// probability ∝ area, a uniform point inside), kept when no earlier point lies within the spacing. The result
// is a Poisson-disk set whose count follows the surface area and the spacing alone, whatever the resolution.
// Deterministic: the same surface, spacing and region give the same points.

// Candidates per expected sample: enough that the greedy pass fills the surface to near its maximal density.
const CANDIDATES_PER_SAMPLE = 6;

// Small, fast, seedable generator (mulberry32): the sample set must not change between identical calls.
export function randomSequence(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = a;
    t = Math.imul(t ^ (t >>> 15), t | 1);
    t ^= t + Math.imul(t ^ (t >>> 7), t | 61);
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

// Greedy Poisson-disk coverage holds about 0.7 A / r² points at spacing r.
export const POISSON_PACKING = 0.7;

// surface: Surface (surface.js). spacing: minimum distance between samples (model units).
// faces (optional): the faces to sample (e.g. those in view); all faces otherwise.
// maxSamples caps the work when a caller asks for a spacing far below what the region needs.
// Returns {faces: Int32Array, bary: Float64Array (3 per sample), points: Float64Array (3 per sample)}.
export function sampleSurface(surface, spacing, { faces = null, seed = 1, maxSamples = 50_000 } = {}) {
  const list = faces ?? Int32Array.from({ length: surface.nF }, (_, f) => f);
  const cdf = new Float64Array(list.length);
  let area = 0;
  for (let i = 0; i < list.length; i++) cdf[i] = area += surface.areas[list[i]];
  const empty = { faces: new Int32Array(0), bary: new Float64Array(0), points: new Float64Array(0) };
  if (!(area > 0) || !(spacing > 0)) return empty;
  const expected = Math.min(maxSamples, (POISSON_PACKING * area) / (spacing * spacing));
  const candidates = Math.ceil(CANDIDATES_PER_SAMPLE * expected) + 16;
  const random = randomSequence(seed);
  const P = surface.positions, T = surface.triangles;
  const r2 = spacing * spacing;
  // Hash grid with cells of the spacing: a candidate only has to look at the 27 cells around it.
  const cells = new Map();
  const key = (ix, iy, iz) => (ix * 73856093) ^ (iy * 19349663) ^ (iz * 83492791);
  const outF = [], outB = [], outP = [];
  for (let c = 0; c < candidates && outF.length < maxSamples; c++) {
    const f = list[upperBound(cdf, random() * area)];
    let u = random(), v = random();
    if (u + v > 1) (u = 1 - u), (v = 1 - v);
    const w = 1 - u - v;
    const a = 3 * T[3 * f], b = 3 * T[3 * f + 1], d = 3 * T[3 * f + 2];
    const x = w * P[a] + u * P[b] + v * P[d];
    const y = w * P[a + 1] + u * P[b + 1] + v * P[d + 1];
    const z = w * P[a + 2] + u * P[b + 2] + v * P[d + 2];
    const ix = Math.floor(x / spacing), iy = Math.floor(y / spacing), iz = Math.floor(z / spacing);
    if (occupied(cells, key, ix, iy, iz, x, y, z, r2)) continue;
    const k = key(ix, iy, iz);
    let cell = cells.get(k);
    if (!cell) cells.set(k, (cell = []));
    cell.push(x, y, z);
    outF.push(f);
    outB.push(w, u, v);
    outP.push(x, y, z);
  }
  return { faces: Int32Array.from(outF), bary: Float64Array.from(outB), points: Float64Array.from(outP) };
}

function occupied(cells, key, ix, iy, iz, x, y, z, r2) {
  for (let dx = -1; dx <= 1; dx++)
    for (let dy = -1; dy <= 1; dy++)
      for (let dz = -1; dz <= 1; dz++) {
        const cell = cells.get(key(ix + dx, iy + dy, iz + dz));
        if (!cell) continue;
        for (let i = 0; i < cell.length; i += 3) {
          const ex = cell[i] - x, ey = cell[i + 1] - y, ez = cell[i + 2] - z;
          if (ex * ex + ey * ey + ez * ez < r2) return true;
        }
      }
  return false;
}

// First index i with cdf[i] > x (cdf ascending).
function upperBound(cdf, x) {
  let lo = 0, hi = cdf.length - 1;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (cdf[mid] > x) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

// Model units per screen pixel at the orbit pivot (a perspective camera): the scale that turns the arrow
// spacing and length, chosen in pixels, into distances on the surface.
export function worldPerPixel(camera, pivot, heightPx) {
  const d = camera.position.distanceTo(pivot);
  return (2 * d * Math.tan((camera.fov * Math.PI) / 360)) / Math.max(1, heightPx);
}

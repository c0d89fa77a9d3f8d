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
export function sampleSurface(surface, spacing, options = {}) {
  const sampler = new SurfaceSampler(surface, spacing, options);
  sampler.step(Infinity);
  return sampler.result();
}

// sampleSurface in steps, for a caller that must not hold its thread for long (views/arrows-view.js prepare:
// ~100 ms at 832k faces): step(n) throws up to n more darts and says whether it is done; result() is then
// exactly sampleSurface's.
export class SurfaceSampler {
  constructor(surface, spacing, { faces = null, seed = 1, maxSamples = 50_000 } = {}) {
    // Face k of the region: list[k], or k itself when the region is the whole surface, whose running sums of
    // areas the surface holds (a list of every face and their sums took ~150 ms at 832k faces).
    const list = (this.list = faces);
    let cdf = surface.areaCdf;
    if (list) {
      cdf = new Float64Array(list.length);
      let sum = 0;
      for (let i = 0; i < list.length; i++) cdf[i] = sum += surface.areas[list[i]];
    }
    this.area = cdf.length ? cdf[cdf.length - 1] : 0;
    this.search = new AreaSearch(cdf);
    this.surface = surface;
    this.spacing = spacing;
    this.maxSamples = maxSamples;
    this.count = 0;
    this.c = 0;
    const usable = this.area > 0 && spacing > 0;
    const expected = usable ? Math.min(maxSamples, (POISSON_PACKING * this.area) / (spacing * spacing)) : 0;
    this.candidates = usable ? Math.ceil(CANDIDATES_PER_SAMPLE * expected) + 16 : 0;
    this.random = randomSequence(seed);
    // Hash grid with cells of the spacing: a candidate only looks at the samples hashed to the 27 cells around
    // it. Flat chains in typed arrays: cells that share a bucket only add distance checks, so the result is that
    // of an exact grid (a Map of arrays took ~70 ms for 18k candidates before V8 had optimized it).
    const capacity = Math.min(maxSamples, this.candidates);
    let buckets = 16;
    while (buckets < 2 * capacity) buckets *= 2;
    this.grid = { head: new Int32Array(buckets).fill(-1), next: new Int32Array(capacity), mask: buckets - 1 };
    this.outF = new Int32Array(capacity);
    this.outB = new Float64Array(3 * capacity);
    this.outP = new Float64Array(3 * capacity);
  }

  get done() {
    return this.c >= this.candidates || this.count >= this.maxSamples;
  }

  step(darts) {
    const { list, search, area, random, grid, outF, outB, outP, spacing, maxSamples } = this;
    const P = this.surface.positions, T = this.surface.triangles;
    const r2 = spacing * spacing;
    const end = Math.min(this.candidates, this.c + darts);
    let count = this.count, c = this.c;
    for (; c < end && count < maxSamples; c++) {
      const at = search.upperBound(random() * area);
      const f = list ? list[at] : at;
      let u = random(), v = random();
      if (u + v > 1) {
        u = 1 - u;
        v = 1 - v;
      }
      const w = 1 - u - v;
      const a = 3 * T[3 * f], b = 3 * T[3 * f + 1], d = 3 * T[3 * f + 2];
      const x = w * P[a] + u * P[b] + v * P[d];
      const y = w * P[a + 1] + u * P[b + 1] + v * P[d + 1];
      const z = w * P[a + 2] + u * P[b + 2] + v * P[d + 2];
      const ix = Math.floor(x / spacing), iy = Math.floor(y / spacing), iz = Math.floor(z / spacing);
      if (occupied(grid, outP, ix, iy, iz, x, y, z, r2)) continue;
      const k = bucketOf(grid, ix, iy, iz);
      grid.next[count] = grid.head[k];
      grid.head[k] = count;
      outF[count] = f;
      outB[3 * count] = w;
      outB[3 * count + 1] = u;
      outB[3 * count + 2] = v;
      outP[3 * count] = x;
      outP[3 * count + 1] = y;
      outP[3 * count + 2] = z;
      count++;
    }
    this.count = count;
    this.c = c;
    return this.done;
  }

  result() {
    const n = this.count;
    return { faces: this.outF.slice(0, n), bary: this.outB.slice(0, 3 * n), points: this.outP.slice(0, 3 * n) };
  }
}

const bucketOf = (grid, ix, iy, iz) =>
  (Math.imul(ix, 73856093) ^ Math.imul(iy, 19349663) ^ Math.imul(iz, 83492791)) & grid.mask;

function occupied(grid, points, ix, iy, iz, x, y, z, r2) {
  for (let dx = -1; dx <= 1; dx++)
    for (let dy = -1; dy <= 1; dy++)
      for (let dz = -1; dz <= 1; dz++) {
        for (let i = grid.head[bucketOf(grid, ix + dx, iy + dy, iz + dz)]; i >= 0; i = grid.next[i]) {
          const ex = points[3 * i] - x, ey = points[3 * i + 1] - y, ez = points[3 * i + 2] - z;
          if (ex * ex + ey * ey + ez * ez < r2) return true;
        }
      }
  return false;
}

// The first index i with cdf[i] > x, over running sums in ascending order, in two levels: every BLOCK-th sum
// first (a small array that stays in cache), then within one block. A plain binary search over the 832k sums of
// a scan missed the cache on most of its 20 steps.
const BLOCK = 64;
class AreaSearch {
  constructor(cdf) {
    this.cdf = cdf;
    const nb = Math.ceil(cdf.length / BLOCK);
    this.last = new Float64Array(nb); // the last sum of each block
    for (let b = 0; b < nb; b++) this.last[b] = cdf[Math.min(cdf.length, (b + 1) * BLOCK) - 1];
  }

  upperBound(x) {
    const b = upperBound(this.last, x, 0, this.last.length);
    return upperBound(this.cdf, x, b * BLOCK, Math.min(this.cdf.length, (b + 1) * BLOCK));
  }
}

// First index i in [lo, hi) with a[i] > x, or hi − 1 (a ascending).
function upperBound(a, x, lo, hi) {
  hi -= 1;
  while (lo < hi) {
    const mid = (lo + hi) >> 1;
    if (a[mid] > x) hi = mid;
    else lo = mid + 1;
  }
  return lo;
}

// Model units per screen pixel at the orbit pivot (a perspective camera): the scale that turns the arrow
// spacing and length, chosen in pixels, into distances on the surface.
export function worldPerPixel(camera, pivot, heightPx) {
  return worldPerPixelAt(camera, camera.position.distanceTo(pivot), heightPx);
}

// The same at a given distance from the camera.
export function worldPerPixelAt(camera, distance, heightPx) {
  return (2 * distance * Math.tan((camera.fov * Math.PI) / 360)) / Math.max(1, heightPx);
}

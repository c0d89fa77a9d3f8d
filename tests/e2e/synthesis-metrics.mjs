// Measurements of synthesized textures, done in the test process on arrays read back from the page (the checks
// do not trust the page's own arithmetic). Images are RGBA8 arrays, row 0 = atlas v = 0; coordinates and
// Jacobians are RGBA32F arrays as the synthesizer stores them (see web/synthesis/shaders.js).
import { deflateSync } from 'node:zlib';

const luminance = (px, i) => 0.299 * px[i] + 0.587 * px[i + 1] + 0.114 * px[i + 2];

// Dominant orientation of the stripes in an image, from the structure tensor of the luminance gradient: the
// luminance is smoothed with a Gaussian (sigma 1 pixel) and differentiated with Scharr's rotation-invariant
// 3x3 kernels (plain central differences bend the estimate towards the diagonals), over interior pixels and an
// optional mask. Degrees in [0, 180), measured from +x towards +y (row index); also the tensor's anisotropy
// (λ1 − λ2) / (λ1 + λ2) in [0, 1].
export function stripeOrientation(pixels, width, height, mask = null) {
  const lum = new Float64Array(width * height);
  for (let p = 0; p < width * height; p++) lum[p] = luminance(pixels, 4 * p);
  const g = [0.054, 0.244, 0.403, 0.244, 0.054];
  const blur = (src, dx, dy) => {
    const out = new Float64Array(width * height);
    for (let y = 0; y < height; y++)
      for (let x = 0; x < width; x++) {
        let s = 0, w = 0;
        for (let t = -2; t <= 2; t++) {
          const xx = x + t * dx, yy = y + t * dy;
          if (xx < 0 || yy < 0 || xx >= width || yy >= height) continue;
          s += g[t + 2] * src[yy * width + xx];
          w += g[t + 2];
        }
        out[y * width + x] = s / w;
      }
    return out;
  };
  const L = blur(blur(lum, 1, 0), 0, 1);
  const at = (x, y) => L[y * width + x];
  let jxx = 0, jyy = 0, jxy = 0;
  for (let y = 3; y < height - 3; y++)
    for (let x = 3; x < width - 3; x++) {
      if (mask && !mask[y * width + x]) continue;
      const gx = 3 * (at(x + 1, y - 1) - at(x - 1, y - 1) + at(x + 1, y + 1) - at(x - 1, y + 1)) + 10 * (at(x + 1, y) - at(x - 1, y));
      const gy = 3 * (at(x - 1, y + 1) - at(x - 1, y - 1) + at(x + 1, y + 1) - at(x + 1, y - 1)) + 10 * (at(x, y + 1) - at(x, y - 1));
      jxx += gx * gx;
      jyy += gy * gy;
      jxy += gx * gy;
    }
  const gradientAngle = 0.5 * Math.atan2(2 * jxy, jxx - jyy); // direction of strongest change
  let stripe = ((gradientAngle * 180) / Math.PI + 90) % 180;
  if (stripe < 0) stripe += 180;
  const root = Math.hypot(jxx - jyy, 2 * jxy);
  return { degrees: stripe, anisotropy: root / (jxx + jyy || 1) };
}

// Smallest difference between two orientations (mod 180), in degrees.
export function orientationError(a, b) {
  const d = Math.abs((((a - b) % 180) + 180) % 180);
  return Math.min(d, 180 - d);
}

// Fraction of texel pairs (right and up neighbours, both inside the atlas) whose synthesized coordinates are
// continuous: S[p + e] ≈ S[p] + J(p) e on the torus, within `tolerance` exemplar pixels.
export function coordinateCoherence(coords, jac, width, height, exemplarSize, tolerance = 0.5) {
  const m = exemplarSize;
  const wrap = (d) => d - m * Math.round(d / m);
  let good = 0, total = 0;
  for (let y = 0; y < height; y++)
    for (let x = 0; x < width; x++) {
      const i = 4 * (y * width + x);
      if (coords[i + 3] === 0) continue;
      for (const [dx, dy] of [[1, 0], [0, 1]]) {
        if (x + dx >= width || y + dy >= height) continue;
        const j = 4 * ((y + dy) * width + x + dx);
        if (coords[j + 3] === 0) continue;
        const ex = coords[i] + jac[i] * dx + jac[i + 2] * dy;
        const ey = coords[i + 1] + jac[i + 1] * dx + jac[i + 3] * dy;
        total++;
        if (Math.hypot(wrap(coords[j] - ex), wrap(coords[j + 1] - ey)) <= tolerance) good++;
      }
    }
  return total ? good / total : 0;
}

// Joint RGB histogram (bins per channel) of an RGBA8 image, normalised; optional pixel mask.
export function colourHistogram(pixels, bins = 8, mask = null) {
  const h = new Float64Array(bins * bins * bins);
  let n = 0;
  for (let p = 0; p < pixels.length / 4; p++) {
    if (mask && !mask[p]) continue;
    const q = (c) => Math.min(bins - 1, Math.floor((pixels[4 * p + c] * bins) / 256));
    h[(q(0) * bins + q(1)) * bins + q(2)]++;
    n++;
  }
  return h.map((v) => v / (n || 1));
}

// Total-variation distance between two normalised histograms, in [0, 1].
export function histogramDistance(a, b) {
  let d = 0;
  for (let i = 0; i < a.length; i++) d += Math.abs(a[i] - b[i]);
  return d / 2;
}

// Bilinear colour of a toroidal RGBA8 exemplar (m x m) at continuous coordinates (pixel i spans [i, i+1)).
function exemplarColour(ex, m, cx, cy, out) {
  const x = cx - 0.5, y = cy - 0.5;
  const x0 = Math.floor(x), y0 = Math.floor(y), fx = x - x0, fy = y - y0;
  const w = (i) => ((i % m) + m) % m;
  for (let ch = 0; ch < 3; ch++) {
    const a = ex[4 * (w(y0) * m + w(x0)) + ch], b = ex[4 * (w(y0) * m + w(x0 + 1)) + ch];
    const c = ex[4 * (w(y0 + 1) * m + w(x0)) + ch], d = ex[4 * (w(y0 + 1) * m + w(x0 + 1)) + ch];
    out[ch] = (a * (1 - fx) + b * fx) * (1 - fy) + (c * (1 - fx) + d * fx) * fy;
  }
  return out;
}

// Neighbourhood energy of a synthesized coordinate field (LH05's objective, evaluated independently): for sampled
// texels p and exemplar offsets d in a 5x5 square (exemplar pixels), the texel q = p + round(J(p)^-1 d) says the
// colour at that spot is the exemplar's at S[q] + d - J(p) (q - p); the exemplar around S[p] says it is the colour
// at S[p] + d. Mean squared difference (0..255 scale) over all offsets and samples: 0 inside a coherent patch,
// small across good seams, large for incoherent coordinates.
export function neighbourhoodEnergy(coords, jac, width, height, exemplar, m, { samples = 2000, seed = 1 } = {}) {
  let rng = seed >>> 0 || 1;
  const rand = () => ((rng = (Math.imul(rng, 1664525) + 1013904223) >>> 0) / 4294967296);
  const a = [0, 0, 0], b = [0, 0, 0];
  let total = 0, count = 0;
  for (let s = 0; s < samples; s++) {
    const x = Math.floor(rand() * width), y = Math.floor(rand() * height);
    const i = 4 * (y * width + x);
    if (coords[i + 3] === 0) continue;
    const [j00, j10, j01, j11] = [jac[i], jac[i + 1], jac[i + 2], jac[i + 3]];
    const det = j00 * j11 - j01 * j10;
    if (!(Math.abs(det) > 0)) continue;
    for (let dy = -2; dy <= 2; dy++)
      for (let dx = -2; dx <= 2; dx++) {
        const qx = Math.min(width - 1, Math.max(0, x + Math.round((j11 * dx - j01 * dy) / det)));
        const qy = Math.min(height - 1, Math.max(0, y + Math.round((-j10 * dx + j00 * dy) / det)));
        const k = 4 * (qy * width + qx);
        if (coords[k + 3] === 0) continue;
        const bx = j00 * (qx - x) + j01 * (qy - y), by = j10 * (qx - x) + j11 * (qy - y);
        exemplarColour(exemplar, m, coords[k] + dx - bx, coords[k + 1] + dy - by, a);
        exemplarColour(exemplar, m, coords[i] + dx, coords[i + 1] + dy, b);
        total += ((a[0] - b[0]) ** 2 + (a[1] - b[1]) ** 2 + (a[2] - b[2]) ** 2) / 3;
        count++;
      }
  }
  return count ? total / count : NaN;
}

// The same coordinate field with every texel's coordinate replaced by a uniformly random one (the baseline the
// synthesized textures are compared with).
export function randomCoordinates(coords, m, seed = 7) {
  let rng = seed >>> 0 || 1;
  const rand = () => ((rng = (Math.imul(rng, 1664525) + 1013904223) >>> 0) / 4294967296);
  const out = Float32Array.from(coords);
  for (let i = 0; i < out.length; i += 4) {
    out[i] = rand() * m;
    out[i + 1] = rand() * m;
  }
  return out;
}

// The exemplar's colours at the given coordinates, bilinear (a smooth image for orientation measurements).
export function exemplarImage(coords, exemplar, m) {
  const out = new Uint8Array(coords.length), c = [0, 0, 0];
  for (let i = 0; i < coords.length; i += 4) {
    if (coords[i + 3] === 0) continue;
    exemplarColour(exemplar, m, coords[i], coords[i + 1], c);
    for (let ch = 0; ch < 3; ch++) out[i + ch] = Math.round(c[ch]);
    out[i + 3] = 255;
  }
  return out;
}

// The exemplar's colours at the given coordinates, nearest pixel (what readColour({nearest: true}) shows).
export function colourAt(coords, exemplar, m) {
  const out = new Uint8Array(coords.length);
  for (let i = 0; i < coords.length; i += 4) {
    const x = ((Math.floor(coords[i]) % m) + m) % m, y = ((Math.floor(coords[i + 1]) % m) + m) % m;
    for (let ch = 0; ch < 3; ch++) out[i + ch] = exemplar[4 * (y * m + x) + ch];
    out[i + 3] = 255;
  }
  return out;
}

// RGBA8 pixels (row 0 at the bottom, as WebGL reads them) to PNG bytes, rows flipped so the image shows v up.
export function encodePng(pixels, width, height, { flipY = true } = {}) {
  const raw = Buffer.alloc((4 * width + 1) * height);
  for (let y = 0; y < height; y++) {
    const src = flipY ? height - 1 - y : y;
    raw[y * (4 * width + 1)] = 0;
    Buffer.from(pixels.buffer, pixels.byteOffset + 4 * width * src, 4 * width).copy(raw, y * (4 * width + 1) + 1);
  }
  const crcTable = new Int32Array(256).map((_, n) => {
    let c = n;
    for (let k = 0; k < 8; k++) c = c & 1 ? 0xedb88320 ^ (c >>> 1) : c >>> 1;
    return c;
  });
  const crc = (buf) => {
    let c = -1;
    for (const b of buf) c = crcTable[(c ^ b) & 0xff] ^ (c >>> 8);
    return (c ^ -1) >>> 0;
  };
  const chunk = (type, data) => {
    const len = Buffer.alloc(4);
    len.writeUInt32BE(data.length);
    const td = Buffer.concat([Buffer.from(type, 'ascii'), data]);
    const c = Buffer.alloc(4);
    c.writeUInt32BE(crc(td));
    return Buffer.concat([len, td, c]);
  };
  const ihdr = Buffer.alloc(13);
  ihdr.writeUInt32BE(width, 0);
  ihdr.writeUInt32BE(height, 4);
  ihdr[8] = 8;
  ihdr[9] = 6;
  return Buffer.concat([
    Buffer.from([0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a]),
    chunk('IHDR', ihdr),
    chunk('IDAT', deflateSync(raw)),
    chunk('IEND', Buffer.alloc(0)),
  ]);
}

// ------------------------------------------------------------------------------------------ on a mesh
// Colour the renderer shows at atlas position (x, y) (texel units): the texel's coordinate continued with its
// Jacobian, bilinear exemplar read. Returns null outside the synthesized area.
export function colourAtAtlas(coords, jac, R, exemplar, m, x, y, out = [0, 0, 0]) {
  const tx = Math.min(R - 1, Math.max(0, Math.floor(x))), ty = Math.min(R - 1, Math.max(0, Math.floor(y)));
  const i = 4 * (ty * R + tx);
  if (coords[i + 3] === 0) return null;
  const dx = x - tx - 0.5, dy = y - ty - 0.5;
  return exemplarColour(exemplar, m, coords[i] + jac[i] * dx + jac[i + 2] * dy, coords[i + 1] + jac[i + 1] * dx + jac[i + 3] * dy, out);
}

const colourDistance = (a, b) => Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);

// Colour jumps across the atlas's seams: for every mesh edge whose two faces have different UVs at its ends,
// points along the edge are looked up in both charts; mean colour distance (0..255 per channel, Euclidean).
// For comparison `local`: mean colour distance between atlas points one texel apart inside the charts.
export function seamJumps(coords, jac, R, exemplar, m, triangles, cornerUVs, { samples = 5 } = {}) {
  const nF = triangles.length / 3;
  const edges = new Map();
  for (let f = 0; f < nF; f++)
    for (let k = 0; k < 3; k++) {
      const a = triangles[3 * f + k], b = triangles[3 * f + ((k + 1) % 3)];
      const key = a < b ? `${a},${b}` : `${b},${a}`;
      if (!edges.has(key)) edges.set(key, []);
      edges.get(key).push(f);
    }
  const uvOf = (f, v) => {
    for (let k = 0; k < 3; k++) if (triangles[3 * f + k] === v) return [cornerUVs[6 * f + 2 * k] * R, cornerUVs[6 * f + 2 * k + 1] * R];
    return null;
  };
  const ca = [0, 0, 0], cb = [0, 0, 0];
  let seamSum = 0, seamCount = 0, seamEdges = 0;
  for (const [key, faces] of edges) {
    if (faces.length !== 2) continue;
    const [vi, vj] = key.split(',').map(Number);
    const [f, g] = faces;
    const fi = uvOf(f, vi), fj = uvOf(f, vj), gi = uvOf(g, vi), gj = uvOf(g, vj);
    if (Math.hypot(fi[0] - gi[0], fi[1] - gi[1]) < 1e-4 && Math.hypot(fj[0] - gj[0], fj[1] - gj[1]) < 1e-4) continue;
    seamEdges++;
    for (let s = 1; s <= samples; s++) {
      const t = s / (samples + 1);
      const a = colourAtAtlas(coords, jac, R, exemplar, m, fi[0] + t * (fj[0] - fi[0]), fi[1] + t * (fj[1] - fi[1]), ca);
      const b = colourAtAtlas(coords, jac, R, exemplar, m, gi[0] + t * (gj[0] - gi[0]), gi[1] + t * (gj[1] - gi[1]), cb);
      if (!a || !b) continue;
      seamSum += colourDistance(a, b);
      seamCount++;
    }
  }
  // Local variation: pairs one texel apart, both inside chart triangles.
  const covered = new Uint8Array(R * R);
  for (let f = 0; f < nF; f++) {
    const p = [0, 1, 2].map((k) => [cornerUVs[6 * f + 2 * k] * R, cornerUVs[6 * f + 2 * k + 1] * R]);
    const x0 = Math.max(0, Math.floor(Math.min(p[0][0], p[1][0], p[2][0]))), x1 = Math.min(R - 1, Math.ceil(Math.max(p[0][0], p[1][0], p[2][0])));
    const y0 = Math.max(0, Math.floor(Math.min(p[0][1], p[1][1], p[2][1]))), y1 = Math.min(R - 1, Math.ceil(Math.max(p[0][1], p[1][1], p[2][1])));
    const area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    if (!area) continue;
    for (let y = y0; y <= y1; y++)
      for (let x = x0; x <= x1; x++) {
        const cx = x + 0.5, cy = y + 0.5;
        const l1 = ((p[2][0] - cx) * (p[0][1] - cy) - (p[0][0] - cx) * (p[2][1] - cy)) / area;
        const l2 = ((p[0][0] - cx) * (p[1][1] - cy) - (p[1][0] - cx) * (p[0][1] - cy)) / area;
        if (l1 >= 0 && l2 >= 0 && l1 + l2 <= 1) covered[y * R + x] = 1;
      }
  }
  let localSum = 0, localCount = 0;
  for (let y = 1; y < R - 1; y++)
    for (let x = 1; x < R - 1; x++) {
      if (!covered[y * R + x] || !covered[y * R + x + 1]) continue;
      const a = colourAtAtlas(coords, jac, R, exemplar, m, x + 0.5, y + 0.5, ca);
      const b = colourAtAtlas(coords, jac, R, exemplar, m, x + 1.5, y + 0.5, cb);
      if (!a || !b) continue;
      localSum += colourDistance(a, b);
      localCount++;
    }
  return { seamEdges, seam: seamCount ? seamSum / seamCount : NaN, local: localCount ? localSum / localCount : NaN, covered };
}

// Stripe direction against the field on a mesh: windows of `win`^2 atlas texels, all inside chart triangles
// (`covered`), each measured with the structure tensor of `image` (RGBA8 over the atlas); the stripe tangent in
// atlas coordinates is carried to the surface with the UV map of the face under the window centre and compared
// with the field there (vertexVectors interpolated with the centre's barycentrics). Returns per-window errors.
export function fieldAlignment(image, R, covered, positions, triangles, cornerUVs, vertexVectors, { win = 16, step = 8, minAnisotropy = 0.5 } = {}) {
  const nF = triangles.length / 3;
  // The face under each texel centre.
  const faceOf = new Int32Array(R * R).fill(-1);
  const baryOf = new Float32Array(3 * R * R);
  for (let f = 0; f < nF; f++) {
    const p = [0, 1, 2].map((k) => [cornerUVs[6 * f + 2 * k] * R, cornerUVs[6 * f + 2 * k + 1] * R]);
    const area = (p[1][0] - p[0][0]) * (p[2][1] - p[0][1]) - (p[2][0] - p[0][0]) * (p[1][1] - p[0][1]);
    if (!area) continue;
    const x0 = Math.max(0, Math.floor(Math.min(p[0][0], p[1][0], p[2][0]))), x1 = Math.min(R - 1, Math.ceil(Math.max(p[0][0], p[1][0], p[2][0])));
    const y0 = Math.max(0, Math.floor(Math.min(p[0][1], p[1][1], p[2][1]))), y1 = Math.min(R - 1, Math.ceil(Math.max(p[0][1], p[1][1], p[2][1])));
    for (let y = y0; y <= y1; y++)
      for (let x = x0; x <= x1; x++) {
        const cx = x + 0.5, cy = y + 0.5;
        const l1 = ((p[2][0] - cx) * (p[0][1] - cy) - (p[0][0] - cx) * (p[2][1] - cy)) / area;
        const l2 = ((p[0][0] - cx) * (p[1][1] - cy) - (p[1][0] - cx) * (p[0][1] - cy)) / area;
        if (l1 >= 0 && l2 >= 0 && l1 + l2 <= 1) {
          faceOf[y * R + x] = f;
          baryOf.set([1 - l1 - l2, l1, l2], 3 * (y * R + x));
        }
      }
  }
  const results = [];
  const sub = new Uint8Array(4 * win * win);
  for (let y0 = 0; y0 + win <= R; y0 += step)
    for (let x0 = 0; x0 + win <= R; x0 += step) {
      let inside = true;
      for (let y = y0; y < y0 + win && inside; y++) for (let x = x0; x < x0 + win; x++) if (!covered[y * R + x]) { inside = false; break; }
      if (!inside) continue;
      const c = (y0 + win / 2) * R + x0 + win / 2;
      const f = faceOf[c];
      if (f < 0) continue;
      for (let y = 0; y < win; y++) sub.set(image.subarray(4 * ((y0 + y) * R + x0), 4 * ((y0 + y) * R + x0 + win)), 4 * y * win);
      const o = stripeOrientation(sub, win, win);
      if (o.anisotropy < minAnisotropy) continue;
      // Stripe tangent in atlas texels -> surface, through the face's G = dX/d(uv).
      const t = [Math.cos((o.degrees * Math.PI) / 180), Math.sin((o.degrees * Math.PI) / 180)];
      const P = [0, 1, 2].map((k) => [0, 1, 2].map((d) => positions[3 * triangles[3 * f + k] + d]));
      const Q = [0, 1, 2].map((k) => [cornerUVs[6 * f + 2 * k], cornerUVs[6 * f + 2 * k + 1]]);
      const e1 = [0, 1, 2].map((d) => P[1][d] - P[0][d]), e2 = [0, 1, 2].map((d) => P[2][d] - P[0][d]);
      const du1 = Q[1][0] - Q[0][0], dv1 = Q[1][1] - Q[0][1], du2 = Q[2][0] - Q[0][0], dv2 = Q[2][1] - Q[0][1];
      const det = du1 * dv2 - du2 * dv1;
      const G1 = [0, 1, 2].map((d) => (e1[d] * dv2 - e2[d] * dv1) / det), G2 = [0, 1, 2].map((d) => (e2[d] * du1 - e1[d] * du2) / det);
      const ts = [0, 1, 2].map((d) => G1[d] * t[0] + G2[d] * t[1]);
      const b = baryOf.subarray(3 * c, 3 * c + 3);
      const v = [0, 1, 2].map((d) => b[0] * vertexVectors[3 * triangles[3 * f] + d] + b[1] * vertexVectors[3 * triangles[3 * f + 1] + d] + b[2] * vertexVectors[3 * triangles[3 * f + 2] + d]);
      const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
      const nl = Math.hypot(...n);
      const vn = (v[0] * n[0] + v[1] * n[1] + v[2] * n[2]) / (nl * nl);
      const vt = [0, 1, 2].map((d) => v[d] - vn * n[d]);
      const cos = Math.abs(ts[0] * vt[0] + ts[1] * vt[1] + ts[2] * vt[2]) / (Math.hypot(...ts) * Math.hypot(...vt));
      if (!Number.isFinite(cos)) continue;
      results.push({ x: x0, y: y0, errorDegrees: (Math.acos(Math.min(1, cos)) * 180) / Math.PI, anisotropy: o.anisotropy });
    }
  return results;
}

// Mean stripe period (pixels) across horizontal stripes, in `strips` vertical strips of the image: per column,
// the luminance profile along y minus its mean, period = 2 * length / sign changes.
export function stripePeriods(pixels, width, height, strips = 4) {
  const out = [];
  for (let s = 0; s < strips; s++) {
    const x0 = Math.floor((s * width) / strips), x1 = Math.floor(((s + 1) * width) / strips);
    let sum = 0, n = 0;
    for (let x = x0 + 2; x < x1 - 2; x++) {
      const prof = [];
      for (let y = 0; y < height; y++) prof.push(luminance(pixels, 4 * (y * width + x)));
      const mean = prof.reduce((a, b) => a + b, 0) / height;
      let changes = 0;
      for (let y = 1; y < height; y++) if ((prof[y] - mean) * (prof[y - 1] - mean) < 0) changes++;
      if (changes) {
        sum += (2 * height) / changes;
        n++;
      }
    }
    out.push(n ? sum / n : NaN);
  }
  return out;
}

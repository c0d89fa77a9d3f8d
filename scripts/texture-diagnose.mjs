// Splits the stripe-direction deviation of an exported GLB by cause (issue 8): reads a bundle written by
// tests/e2e/texture-measure.spec.mjs with TVF_MEASURE=1 TVF_DIAGNOSE=1 (<name>-diag.json and GLBs) and prints the
// area-weighted mean deviation and share within 10° per bin of: distance to chart seams and to singularities (in
// stripe periods), atlas anisotropy and density, face size vs the period, and the field's turning per period;
// plus two floors: an analytic stripe texture painted into the same atlas at the same image size and period,
// and the measure's own smoothing applied to the field itself.
// Usage: node scripts/texture-diagnose.mjs <dir> <name> [glb suffix, e.g. -2048]
import { readFileSync } from 'node:fs';
import { readGlb, stripeAlignment, seamJumpRatio, pixelLength } from '../tests/e2e/surface-texture-metrics.mjs';

const [dir, name, suffix = ''] = process.argv.slice(2);
const diag = JSON.parse(readFileSync(`${dir}/${name}-diag.json`, 'utf8'));
const glb = readGlb(readFileSync(`${dir}/${name}${suffix}.glb`));
const { positions, triangles, faceVectors, singularities, cornerUVs } = diag;
const nF = triangles.length / 3;
const P = (v) => [positions[3 * v], positions[3 * v + 1], positions[3 * v + 2]];
const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.hypot(...a);

const magnification = glb.image.width / diag.stats.resolution;
const synthPeriod = 16 * diag.stats.featureScale * magnification * pixelLength(glb);
// PERIOD_SCALE: the floors at another feature size (the synthesized texture is measured at its own period).
const period = synthPeriod * Number(process.env.PERIOD_SCALE || 1);
const align = stripeAlignment(glb, Float64Array.from(faceVectors), synthPeriod);
const seams = seamJumpRatio(glb, Int32Array.from(triangles));
console.log(JSON.stringify({ name, image: glb.image.width, atlas: diag.stats.resolution, featureScale: diag.stats.featureScale, period: +period.toFixed(5), mean: +align.meanDegrees.toFixed(2), within10: +align.shareWithin10.toFixed(3), seamRatio: +seams.ratio.toFixed(3) }));

// Per-face geometry.
const area = new Float64Array(nF), centroid = [], normal = [];
for (let f = 0; f < nF; f++) {
  const [a, b, c] = [0, 1, 2].map((k) => P(triangles[3 * f + k]));
  const n = cross(sub(b, a), sub(c, a));
  area[f] = norm(n) / 2;
  normal.push(n.map((x) => x / (norm(n) || 1)));
  centroid.push([0, 1, 2].map((k) => (a[k] + b[k] + c[k]) / 3));
}
// Face adjacency and seam faces.
const edgeMap = new Map();
for (let f = 0; f < nF; f++)
  for (let k = 0; k < 3; k++) {
    const a = triangles[3 * f + k], b = triangles[3 * f + ((k + 1) % 3)];
    const key = a < b ? `${a},${b}` : `${b},${a}`;
    if (!edgeMap.has(key)) edgeMap.set(key, []);
    edgeMap.get(key).push({ f, a, b, k });
  }
const adj = Array.from({ length: nF }, () => []);
const seamFace = new Uint8Array(nF);
const uvOf = (f, v) => {
  for (let k = 0; k < 3; k++) if (triangles[3 * f + k] === v) return [cornerUVs[6 * f + 2 * k], cornerUVs[6 * f + 2 * k + 1]];
};
let turnSum = new Float64Array(nF), turnCount = new Float64Array(nF);
for (const list of edgeMap.values()) {
  if (list.length !== 2) {
    for (const e of list) seamFace[e.f] = 1; // boundary
    continue;
  }
  const [e0, e1] = list;
  adj[e0.f].push(e1.f);
  adj[e1.f].push(e0.f);
  const same = (p, q) => Math.abs(p[0] - q[0]) < 1e-7 && Math.abs(p[1] - q[1]) < 1e-7;
  if (!(same(uvOf(e0.f, e0.a), uvOf(e1.f, e0.a)) && same(uvOf(e0.f, e0.b), uvOf(e1.f, e0.b)))) seamFace[e0.f] = seamFace[e1.f] = 1;
  // Field turning across the edge (mod 180°), by parallel transport through the shared edge direction.
  const edir = sub(P(e0.b), P(e0.a));
  const el = norm(edir);
  const ang = (f) => {
    const v = faceVectors.slice(3 * f, 3 * f + 3);
    const u = edir.map((x) => x / el), w = cross(normal[f], u);
    return Math.atan2(dot(v, w), dot(v, u));
  };
  let d = Math.abs(ang(e0.f) - ang(e1.f)) % Math.PI;
  if (d > Math.PI / 2) d = Math.PI - d;
  const len = norm(sub(centroid[e0.f], centroid[e1.f]));
  for (const f of [e0.f, e1.f]) (turnSum[f] += d / len), turnCount[f]++;
}
// Dijkstra over faces (centroid distances) from a set of source faces.
function distances(sources) {
  const d = new Float64Array(nF).fill(Infinity);
  const heap = [];
  const push = (f, x) => {
    heap.push([x, f]);
    let i = heap.length - 1;
    while (i > 0) {
      const p = (i - 1) >> 1;
      if (heap[p][0] <= heap[i][0]) break;
      [heap[p], heap[i]] = [heap[i], heap[p]];
      i = p;
    }
  };
  const pop = () => {
    const top = heap[0], last = heap.pop();
    if (heap.length) {
      heap[0] = last;
      let i = 0;
      for (;;) {
        const l = 2 * i + 1, r = l + 1;
        let m = i;
        if (l < heap.length && heap[l][0] < heap[m][0]) m = l;
        if (r < heap.length && heap[r][0] < heap[m][0]) m = r;
        if (m === i) break;
        [heap[m], heap[i]] = [heap[i], heap[m]];
        i = m;
      }
    }
    return top;
  };
  for (const f of sources) (d[f] = 0), push(f, 0);
  while (heap.length) {
    const [x, f] = pop();
    if (x > d[f]) continue;
    for (const g of adj[f]) {
      const y = x + norm(sub(centroid[f], centroid[g]));
      if (y < d[g]) (d[g] = y), push(g, y);
    }
  }
  return d;
}
const seamDist = distances([...seamFace.keys()].filter((f) => seamFace[f]));
const singVerts = new Set(singularities.filter((s) => s.index !== 0).map((s) => s.vertex));
const singFaces = [];
for (let f = 0; f < nF; f++) if ([0, 1, 2].some((k) => singVerts.has(triangles[3 * f + k]))) singFaces.push(f);
const singDist = singFaces.length ? distances(singFaces) : new Float64Array(nF).fill(Infinity);

// Atlas map per face: singular values of the UV -> surface map (surface length per texel).
const R = diag.stats.resolution;
const aniso = new Float64Array(nF), density = new Float64Array(nF);
let totA3 = 0, totA2 = 0;
for (let f = 0; f < nF; f++) {
  const [a, b, c] = [0, 1, 2].map((k) => P(triangles[3 * f + k]));
  const u = cornerUVs.slice(6 * f, 6 * f + 6).map((x) => x * R);
  const du1 = u[2] - u[0], dv1 = u[3] - u[1], du2 = u[4] - u[0], dv2 = u[5] - u[1];
  const det = du1 * dv2 - du2 * dv1;
  totA3 += area[f];
  totA2 += Math.abs(det) / 2;
  if (!(Math.abs(det) > 1e-12)) continue;
  const e1 = sub(b, a), e2 = sub(c, a);
  const G1 = [0, 1, 2].map((k) => (e1[k] * dv2 - e2[k] * dv1) / det), G2 = [0, 1, 2].map((k) => (e2[k] * du1 - e1[k] * du2) / det);
  const E = dot(G1, G1), F = dot(G1, G2), G = dot(G2, G2);
  const tr = E + G, dd = Math.sqrt(Math.max(0, (E - G) ** 2 + 4 * F * F));
  const s1 = Math.sqrt((tr + dd) / 2), s2 = Math.sqrt(Math.max(1e-30, (tr - dd) / 2));
  aniso[f] = s1 / s2;
  density[f] = Math.sqrt(s1 * s2);
}
const meanTexel = Math.sqrt(totA3 / totA2);

// Floor 1: the measure's smoothing applied to the field itself (tensors of the field's normal direction).
function fieldSmoothingFloor() {
  const cell = 2 * period, grid = new Map();
  const key = (p) => p.map((x) => Math.floor(x / cell)).join(',');
  centroid.forEach((c, f) => {
    const k = key(c);
    if (!grid.has(k)) grid.set(k, []);
    grid.get(k).push(f);
  });
  const T = new Float64Array(6 * nF);
  for (let f = 0; f < nF; f++) {
    const v = faceVectors.slice(3 * f, 3 * f + 3);
    const g = cross(normal[f], v);
    const l = norm(g) || 1;
    const w = area[f] / (l * l);
    T.set([g[0] * g[0] * w, g[0] * g[1] * w, g[0] * g[2] * w, g[1] * g[1] * w, g[1] * g[2] * w, g[2] * g[2] * w], 6 * f);
  }
  const err = new Float64Array(nF);
  for (let f = 0; f < nF; f++) {
    const S = new Float64Array(6), c = centroid[f].map((x) => Math.floor(x / cell));
    for (let dx = -1; dx <= 1; dx++)
      for (let dy = -1; dy <= 1; dy++)
        for (let dz = -1; dz <= 1; dz++)
          for (const g of grid.get(`${c[0] + dx},${c[1] + dy},${c[2] + dz}`) ?? []) {
            const d = norm(sub(centroid[g], centroid[f]));
            if (d > cell) continue;
            const w = Math.exp(-(d * d) / (2 * period * period));
            for (let k = 0; k < 6; k++) S[k] += w * T[6 * g + k];
          }
    const n = normal[f], [a] = [0].map(() => P(triangles[3 * f])), b = P(triangles[3 * f + 1]);
    const e = sub(b, a), b1 = e.map((x) => x / norm(e)), b2 = cross(n, b1);
    const Tv = (u, w) => u[0] * (S[0] * w[0] + S[1] * w[1] + S[2] * w[2]) + u[1] * (S[1] * w[0] + S[3] * w[1] + S[4] * w[2]) + u[2] * (S[2] * w[0] + S[4] * w[1] + S[5] * w[2]);
    const m11 = Tv(b1, b1), m12 = Tv(b1, b2), m22 = Tv(b2, b2);
    const stripe = 0.5 * Math.atan2(2 * m12, m11 - m22) + Math.PI / 2;
    const v = faceVectors.slice(3 * f, 3 * f + 3);
    let d = Math.abs(stripe - Math.atan2(dot(v, b2), dot(v, b1))) % Math.PI;
    if (d > Math.PI / 2) d = Math.PI - d;
    err[f] = (d * 180) / Math.PI;
  }
  return err;
}
const smoothErr = fieldSmoothingFloor();

function summary(label, errs, select) {
  let w = 0, s = 0, within = 0;
  for (let f = 0; f < nF; f++) {
    if (!select(f) || !Number.isFinite(errs[f])) continue;
    w += area[f];
    s += area[f] * errs[f];
    if (errs[f] <= 10) within += area[f];
  }
  return { label, share: 0, area: w, mean: w ? s / w : NaN, within10: w ? within / w : NaN };
}
let totalArea = 0;
for (let f = 0; f < nF; f++) totalArea += area[f];
function table(title, value, edges) {
  console.log(`\n${title}`);
  console.log('bin              area%   mean°  ≤10°   | field-smoothing floor mean°  ≤10°');
  for (let i = 0; i + 1 < edges.length; i++) {
    const sel = (f) => value(f) >= edges[i] && value(f) < edges[i + 1];
    const a = summary('', align.errors, sel), b = summary('', smoothErr, sel);
    if (!a.area) continue;
    console.log(`[${edges[i]}, ${edges[i + 1]})`.padEnd(16), (100 * a.area / totalArea).toFixed(1).padStart(6), a.mean.toFixed(2).padStart(7), (100 * a.within10).toFixed(0).padStart(5), '  |', b.mean.toFixed(2).padStart(8), (100 * b.within10).toFixed(0).padStart(5));
  }
}
const all = summary('', smoothErr, () => true);
console.log(`field-smoothing floor overall: ${all.mean.toFixed(2)}° / ${(100 * all.within10).toFixed(1)}%`);
// Contribution of error mass: area * err share by bins.
table('distance to a chart seam (stripe periods)', (f) => seamDist[f] / period, [0, 0.25, 0.5, 1, 2, 4, Infinity]);
table('distance to a singularity (stripe periods)', (f) => singDist[f] / period, [0, 0.5, 1, 2, 4, 8, Infinity]);
table('atlas anisotropy (σ1/σ2)', (f) => aniso[f], [1, 1.1, 1.25, 1.5, 2, Infinity]);
table('atlas density (surface per texel / mean)', (f) => density[f] / meanTexel, [0, 0.8, 0.9, 1.1, 1.25, Infinity]);
table('face size sqrt(area) / period', (f) => Math.sqrt(area[f]) / period, [0, 0.1, 0.2, 0.4, 0.8, Infinity]);
table('field turning per period (degrees)', (f) => (turnCount[f] ? turnSum[f] / turnCount[f] : 0) * period * 180 / Math.PI, [0, 5, 10, 20, 40, 80, Infinity]);
console.log(`\nsingularities: ${singVerts.size}; seam faces: ${seamFace.reduce((a, b) => a + b, 0)} of ${nF}`);

// Floor 2: an analytic stripe texture (level sets of p·a, period as synthesized) painted into the GLB's own UVs at
// its own image size, measured against its own truth.
{
  const W = glb.image.width;
  const pixels = new Uint8Array(W * W * 4);
  const a = [0.6, 0.64, 0.48];
  const field = new Float64Array(3 * nF);
  for (let f = 0; f < nF; f++) {
    const Pf = [0, 1, 2].map((k) => P(triangles[3 * f + k]));
    const Q = [0, 1, 2].map((k) => [glb.uvs[2 * (3 * f + k)] * W, glb.uvs[2 * (3 * f + k) + 1] * W]);
    const n = normal[f], an = dot(a, n), ap = a.map((x, c) => x - an * n[c]);
    field.set(cross(n, ap), 3 * f);
    const t = [Q[1][0] - Q[0][0], Q[2][0] - Q[0][0], Q[1][1] - Q[0][1], Q[2][1] - Q[0][1]];
    const det = t[0] * t[3] - t[1] * t[2];
    if (!(Math.abs(det) > 1e-12)) continue;
    const e1 = sub(Pf[1], Pf[0]), e2 = sub(Pf[2], Pf[0]);
    const g = Math.ceil(2 * magnification);
    const x0 = Math.max(0, Math.floor(Math.min(Q[0][0], Q[1][0], Q[2][0])) - g), x1 = Math.min(W - 1, Math.ceil(Math.max(Q[0][0], Q[1][0], Q[2][0])) + g);
    const y0 = Math.max(0, Math.floor(Math.min(Q[0][1], Q[1][1], Q[2][1])) - g), y1 = Math.min(W - 1, Math.ceil(Math.max(Q[0][1], Q[1][1], Q[2][1])) + g);
    for (let y = y0; y <= y1; y++)
      for (let x = x0; x <= x1; x++) {
        const dx = x + 0.5 - Q[0][0], dy = y + 0.5 - Q[0][1];
        const l1 = (t[3] * dx - t[1] * dy) / det, l2 = (-t[2] * dx + t[0] * dy) / det;
        const inside = l1 >= 0 && l2 >= 0 && l1 + l2 <= 1;
        const o = 4 * (y * W + x);
        if (pixels[o + 3] === 255 && !inside) continue;
        const p = [0, 1, 2].map((c) => Pf[0][c] + l1 * e1[c] + l2 * e2[c]);
        const v = Math.round(127.5 + 127 * Math.sin((2 * Math.PI * dot(p, a)) / period));
        pixels.set([v, v, v, inside ? 255 : 254], o);
      }
  }
  for (let i = 3; i < pixels.length; i += 4) pixels[i] = pixels[i] ? 255 : 0;
  const analytic = { ...glb, image: { width: W, height: W, pixels } };
  const r = stripeAlignment(analytic, field, period);
  const s = seamJumpRatio(analytic, Int32Array.from(triangles));
  console.log(`analytic floor (same atlas, ${W}², same period): ${r.meanDegrees.toFixed(2)}° / ${(100 * r.shareWithin10).toFixed(1)}% / seam ${s.ratio.toFixed(3)}`);
}

// SPDX-License-Identifier: GPL-2.0-or-later
// The texture atlas synthesis runs in. The model's own TEXCOORD_0 is used when it is a usable atlas: every UV
// inside [0, 1], few degenerate triangles, and no two triangles covering the same texels (a tiling or mirrored-
// and-stacked UV layout would make two surface regions share — and fight over — the same synthesized texels).
// Otherwise an atlas is generated: charts grown over faces whose normals stay within a cone, each projected onto
// the plane of its mean normal (no flips: every face faces the projection axis), split again if its projection
// overlaps itself, rotated to its principal axes and shelf-packed with a gutter. Projection distorts area by up
// to ~1/cos(cone), which the synthesis Jacobian compensates exactly (it is built from the 3D-to-UV map per face).

const CONE_COS = 0.7; // ~45°: face normal vs. the chart's running mean normal

// Counts, per texel centre of an n x n grid, the triangles covering it (half-open edge rule: a centre on an
// edge shared by two triangles is counted once). cornerUVs: 6 per face. Returns Uint16Array (saturating).
export function rasterCoverage(cornerUVs, n, faces = null) {
  const count = new Uint16Array(n * n);
  const total = faces ? faces.length : cornerUVs.length / 6;
  for (let i = 0; i < total; i++) {
    const f = faces ? faces[i] : i;
    let ax = cornerUVs[6 * f] * n, ay = cornerUVs[6 * f + 1] * n;
    let bx = cornerUVs[6 * f + 2] * n, by = cornerUVs[6 * f + 3] * n;
    let cx = cornerUVs[6 * f + 4] * n, cy = cornerUVs[6 * f + 5] * n;
    let area = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
    if (!(Math.abs(area) > 1e-12)) continue;
    if (area < 0) [bx, by, cx, cy, area] = [cx, cy, bx, by, -area];
    const x0 = Math.max(0, Math.floor(Math.min(ax, bx, cx) - 0.5)), x1 = Math.min(n - 1, Math.ceil(Math.max(ax, bx, cx) - 0.5));
    const y0 = Math.max(0, Math.floor(Math.min(ay, by, cy) - 0.5)), y1 = Math.min(n - 1, Math.ceil(Math.max(ay, by, cy) - 0.5));
    // Edge function of p against edge (p0 -> p1); top-left rule for ties.
    const edge = (x0e, y0e, x1e, y1e, px, py) => {
      const e = (x1e - x0e) * (py - y0e) - (y1e - y0e) * (px - x0e);
      if (e !== 0) return e > 0;
      const dy = y1e - y0e, dx = x1e - x0e;
      return dy < 0 || (dy === 0 && dx > 0);
    };
    for (let y = y0; y <= y1; y++)
      for (let x = x0; x <= x1; x++) {
        const px = x + 0.5, py = y + 0.5;
        if (edge(ax, ay, bx, by, px, py) && edge(bx, by, cx, cy, px, py) && edge(cx, cy, ax, ay, px, py)) {
          const k = y * n + x;
          if (count[k] < 65535) count[k]++;
        }
      }
  }
  return count;
}

// Whether cornerUVs can serve as the synthesis atlas; {ok, reason, stats}.
export function checkAtlasUVs(positions, triangles, cornerUVs, { resolution = 512 } = {}) {
  const nF = triangles.length / 3;
  if (!cornerUVs || cornerUVs.length !== 6 * nF) return { ok: false, reason: 'the model has no TEXCOORD_0', stats: {} };
  let outside = 0, degenerate = 0, nonFinite = 0;
  const eps = 1e-4;
  for (let f = 0; f < nF; f++) {
    const u = cornerUVs.subarray(6 * f, 6 * f + 6);
    if (!u.every(Number.isFinite)) {
      nonFinite++;
      continue;
    }
    if (u.some((x) => x < -eps || x > 1 + eps)) outside++;
    const area = (u[2] - u[0]) * (u[5] - u[1]) - (u[4] - u[0]) * (u[3] - u[1]);
    if (!(Math.abs(area) * resolution * resolution > 1e-6)) degenerate++;
  }
  const stats = { faces: nF, outside, degenerate, nonFinite };
  if (nonFinite) return { ok: false, reason: `${nonFinite} faces have non-finite UVs`, stats };
  if (outside) return { ok: false, reason: `${outside} faces have UVs outside [0, 1] (a tiling layout, not an atlas)`, stats };
  if (degenerate > 0.01 * nF) return { ok: false, reason: `${degenerate} faces have (near-)zero UV area`, stats };
  const cov = rasterCoverage(cornerUVs, resolution);
  let covered = 0, overlapped = 0;
  for (const c of cov) {
    if (c > 0) covered++;
    if (c > 1) overlapped++;
  }
  Object.assign(stats, { coverage: covered / cov.length, overlap: covered ? overlapped / covered : 0 });
  if (!covered) return { ok: false, reason: 'the UV triangles cover no texel', stats };
  if (overlapped > 0.005 * covered)
    return { ok: false, reason: `UV triangles overlap on ${((100 * overlapped) / covered).toFixed(1)}% of the covered texels`, stats };
  return { ok: true, reason: 'TEXCOORD_0 is a valid non-overlapping atlas', stats };
}

function faceAdjacency(triangles) {
  const nF = triangles.length / 3;
  const map = new Map();
  const adj = new Int32Array(3 * nF).fill(-1);
  for (let f = 0; f < nF; f++)
    for (let k = 0; k < 3; k++) {
      const a = triangles[3 * f + k], b = triangles[3 * f + ((k + 1) % 3)];
      const key = a < b ? a * 4294967296 + b : b * 4294967296 + a;
      const other = map.get(key);
      if (other === undefined) map.set(key, 3 * f + k);
      else if (other >= 0) {
        adj[3 * f + k] = Math.floor(other / 3);
        adj[other] = f;
        map.set(key, -1); // non-manifold third face: left unconnected
      }
    }
  return adj;
}

function faceNormals(positions, triangles) {
  const nF = triangles.length / 3;
  const normals = new Float64Array(3 * nF), areas = new Float64Array(nF);
  for (let f = 0; f < nF; f++) {
    const [a, b, c] = [0, 1, 2].map((k) => 3 * triangles[3 * f + k]);
    const u = [0, 1, 2].map((k) => positions[b + k] - positions[a + k]);
    const w = [0, 1, 2].map((k) => positions[c + k] - positions[a + k]);
    const n = [u[1] * w[2] - u[2] * w[1], u[2] * w[0] - u[0] * w[2], u[0] * w[1] - u[1] * w[0]];
    const l = Math.hypot(n[0], n[1], n[2]);
    areas[f] = l / 2;
    if (l > 0) normals.set([n[0] / l, n[1] / l, n[2] / l], 3 * f);
  }
  return { normals, areas };
}

// Region growing: faces in decreasing area order seed charts; a chart takes a neighbouring face while its normal
// is within the cone around the chart's area-weighted mean normal.
function growCharts(triangles, normals, areas, adj, faces) {
  const nF = triangles.length / 3;
  const chartOf = new Int32Array(nF).fill(-1);
  const allowed = new Uint8Array(nF);
  for (const f of faces) allowed[f] = 1;
  const order = Array.from(faces).sort((a, b) => areas[b] - areas[a] || a - b);
  const charts = [];
  for (const seed of order) {
    if (chartOf[seed] >= 0) continue;
    const id = charts.length;
    const members = [seed];
    const sum = [normals[3 * seed] * areas[seed], normals[3 * seed + 1] * areas[seed], normals[3 * seed + 2] * areas[seed]];
    chartOf[seed] = id;
    for (let head = 0; head < members.length; head++) {
      const f = members[head];
      const l = Math.hypot(sum[0], sum[1], sum[2]) || 1;
      const axis = [sum[0] / l, sum[1] / l, sum[2] / l];
      for (let k = 0; k < 3; k++) {
        const g = adj[3 * f + k];
        if (g < 0 || chartOf[g] >= 0 || !allowed[g]) continue;
        const d = normals[3 * g] * axis[0] + normals[3 * g + 1] * axis[1] + normals[3 * g + 2] * axis[2];
        if (d < CONE_COS) continue;
        chartOf[g] = id;
        members.push(g);
        for (let c = 0; c < 3; c++) sum[c] += normals[3 * g + c] * areas[g];
      }
    }
    charts.push(members);
  }
  return charts;
}

// 2D coordinates of a chart's face corners: projected onto the plane of its mean normal, rotated to its principal
// axes, translated to the origin. Returns {uv: Float64Array(6 * faces), width, height}.
function flattenChart(positions, triangles, normals, areas, faces) {
  const axis = [0, 0, 0];
  for (const f of faces) for (let c = 0; c < 3; c++) axis[c] += normals[3 * f + c] * areas[f];
  let l = Math.hypot(...axis);
  if (!(l > 0)) axis.splice(0, 3, 0, 0, 1), (l = 1);
  const n = axis.map((x) => x / l);
  const ref = Math.abs(n[0]) < 0.9 ? [1, 0, 0] : [0, 1, 0];
  let t1 = [n[1] * ref[2] - n[2] * ref[1], n[2] * ref[0] - n[0] * ref[2], n[0] * ref[1] - n[1] * ref[0]];
  const l1 = Math.hypot(...t1);
  t1 = t1.map((x) => x / l1);
  const t2 = [n[1] * t1[2] - n[2] * t1[1], n[2] * t1[0] - n[0] * t1[2], n[0] * t1[1] - n[1] * t1[0]];
  const uv = new Float64Array(6 * faces.length);
  let mx = 0, my = 0;
  faces.forEach((f, i) => {
    for (let k = 0; k < 3; k++) {
      const v = 3 * triangles[3 * f + k];
      const x = positions[v] * t1[0] + positions[v + 1] * t1[1] + positions[v + 2] * t1[2];
      const y = positions[v] * t2[0] + positions[v + 1] * t2[1] + positions[v + 2] * t2[2];
      uv[6 * i + 2 * k] = x;
      uv[6 * i + 2 * k + 1] = y;
      mx += x;
      my += y;
    }
  });
  const cnt = 3 * faces.length;
  mx /= cnt;
  my /= cnt;
  let sxx = 0, syy = 0, sxy = 0;
  for (let i = 0; i < uv.length; i += 2) {
    const x = uv[i] - mx, y = uv[i + 1] - my;
    sxx += x * x;
    syy += y * y;
    sxy += x * y;
  }
  const angle = 0.5 * Math.atan2(2 * sxy, sxx - syy);
  const ca = Math.cos(angle), sa = Math.sin(angle);
  let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
  for (let i = 0; i < uv.length; i += 2) {
    const x = uv[i] - mx, y = uv[i + 1] - my;
    uv[i] = ca * x + sa * y;
    uv[i + 1] = -sa * x + ca * y;
    x0 = Math.min(x0, uv[i]);
    y0 = Math.min(y0, uv[i + 1]);
    x1 = Math.max(x1, uv[i]);
    y1 = Math.max(y1, uv[i + 1]);
  }
  for (let i = 0; i < uv.length; i += 2) {
    uv[i] -= x0;
    uv[i + 1] -= y0;
  }
  return { uv, width: x1 - x0, height: y1 - y0 };
}

function chartOverlaps(flat) {
  const size = Math.max(flat.width, flat.height);
  if (!(size > 0)) return false;
  const n = 96;
  const scaled = new Float32Array(flat.uv.length);
  for (let i = 0; i < scaled.length; i++) scaled[i] = (flat.uv[i] / size) * 0.98 + 0.01;
  const cov = rasterCoverage(scaled, n);
  let covered = 0, over = 0;
  for (const c of cov) {
    if (c) covered++;
    if (c > 1) over++;
  }
  return over > 0.002 * covered + 1;
}

// Splits a chart in two along its longer principal axis (face centroids, at the median).
function splitChart(flat, faces) {
  const key = (i) => {
    const o = 6 * i;
    return flat.width >= flat.height ? flat.uv[o] + flat.uv[o + 2] + flat.uv[o + 4] : flat.uv[o + 1] + flat.uv[o + 3] + flat.uv[o + 5];
  };
  const idx = faces.map((f, i) => i).sort((a, b) => key(a) - key(b));
  const half = idx.length >> 1;
  return [idx.slice(0, half).map((i) => faces[i]), idx.slice(half).map((i) => faces[i])];
}

// Shelf packing of rectangles (w, h in chart units) into the unit square at scale s with padding `pad` (UV units);
// returns offsets or null when they do not fit.
function shelfPack(rects, s, pad) {
  const order = rects.map((r, i) => i).sort((a, b) => rects[b].h - rects[a].h || a - b);
  const out = new Array(rects.length);
  let x = pad, y = pad, shelf = 0;
  for (const i of order) {
    const w = rects[i].w * s, h = rects[i].h * s;
    if (w + 2 * pad > 1 || h + 2 * pad > 1) return null;
    if (x + w + pad > 1) {
      x = pad;
      y += shelf + pad;
      shelf = 0;
    }
    if (y + h + pad > 1) return null;
    out[i] = [x, y];
    x += w + pad;
    shelf = Math.max(shelf, h);
  }
  return out;
}

// A generated atlas for a mesh (positions 3 per vertex, triangles 3 per face): cornerUVs (6 per face) and stats.
// `gutter` texels of padding at `resolution` around every chart.
export function generateAtlas(positions, triangles, { resolution = 512, gutter = 3 } = {}) {
  const nF = triangles.length / 3;
  const { normals, areas } = faceNormals(positions, triangles);
  const adj = faceAdjacency(triangles);
  const all = [];
  for (let f = 0; f < nF; f++) if (areas[f] > 0) all.push(f);
  let charts = growCharts(triangles, normals, areas, adj, all);
  // Flatten; split any chart whose projection overlaps itself.
  const flats = [];
  let splits = 0;
  while (charts.length) {
    const faces = charts.pop();
    const flat = flattenChart(positions, triangles, normals, areas, faces);
    if (faces.length > 1 && chartOverlaps(flat)) {
      charts.push(...splitChart(flat, faces));
      splits++;
      continue;
    }
    flats.push({ faces, ...flat });
  }
  flats.sort((a, b) => b.faces.length - a.faces.length || a.faces[0] - b.faces[0]);
  const rects = flats.map((c) => ({ w: c.width, h: c.height }));
  const pad = (2 * gutter + 1) / resolution;
  // Largest scale that fits: bisection on s (area bound first).
  const totalArea = rects.reduce((s, r) => s + r.w * r.h, 0);
  let lo = 0, hi = 1 / Math.sqrt(totalArea || 1);
  while (shelfPack(rects, hi, pad)) hi *= 1.5;
  for (let it = 0; it < 40; it++) {
    const mid = (lo + hi) / 2;
    if (shelfPack(rects, mid, pad)) lo = mid;
    else hi = mid;
  }
  const offsets = shelfPack(rects, lo, pad);
  if (!offsets) throw new Error('could not pack the atlas charts');
  const cornerUVs = new Float32Array(6 * nF);
  let used = 0;
  flats.forEach((c, i) => {
    const [ox, oy] = offsets[i];
    c.faces.forEach((f, j) => {
      for (let k = 0; k < 3; k++) {
        cornerUVs[6 * f + 2 * k] = ox + lo * c.uv[6 * j + 2 * k];
        cornerUVs[6 * f + 2 * k + 1] = oy + lo * c.uv[6 * j + 2 * k + 1];
      }
    });
    used += c.width * c.height * lo * lo;
  });
  // Degenerate faces (zero area) keep all-zero UVs: the synthesizer skips them.
  return { cornerUVs, stats: { charts: flats.length, splits, packing: used, scale: lo } };
}

// The atlas synthesis will use for a model: its TEXCOORD_0 when usable, else a generated one.
export function chooseAtlas({ positions, triangles, cornerUVs }, { resolution = 512, gutter = 3 } = {}) {
  const check = checkAtlasUVs(positions, triangles, cornerUVs, { resolution });
  if (check.ok) return { cornerUVs: Float32Array.from(cornerUVs), source: 'TEXCOORD_0', reason: check.reason, stats: check.stats };
  const t0 = performance.now();
  const gen = generateAtlas(positions, triangles, { resolution, gutter });
  return {
    cornerUVs: gen.cornerUVs,
    source: 'generated',
    reason: `generated (${check.reason})`,
    stats: { ...gen.stats, check: check.stats, ms: performance.now() - t0 },
  };
}

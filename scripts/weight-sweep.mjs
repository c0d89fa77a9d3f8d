#!/usr/bin/env node
// SPDX-License-Identifier: GPL-2.0-or-later
// weight-sweep.mjs: the stroke-weight sweep of Sec. 6 of the paper ("for the Bunny example we computed the maximum
// deviation along the curves when using given weights"), rerun on a CGAL benchmark mesh with the native CLI.
//
// Usage: node scripts/weight-sweep.mjs [--mesh NAME|PATH] [--weights 1,1e2,1e4,1e6] [--face F] [--crossings N]
//                                      [--tvf build/tvf] [--svg docs/images/weight-sweep.svg | --no-svg]
//   --mesh      a mesh of bench-data/meshes (default bunny00, from scripts/fetch-meshes.sh) or an OFF path
//   --face      the face the stroke starts in (default: the face nearest the mesh's vertex centroid)
//   --crossings how many edges the stroke crosses at most (default 60); --strength S: the stroke's strength (1)
// Output: a JSON summary on stdout, the markdown table on stderr, and the SVG chart (log-log: weight against the
// max and mean relative deviation).
//
// What is measured. A stroke enters the system as one weighted row per crossed edge, c_e = s·(t·p_e)
// (core/constraints/edge_rows.cpp; docs/method.md#constraints). This script builds a stroke programmatically (a
// straight walk across the surface from a start face, with a stroke point in every 4th face it visits), recomputes
// those rows independently (the same walk between consecutive stroke points, in JavaScript, from the OFF file),
// runs `tvf design` for each weight and reads the solved 1-form from the field file. For each row it takes
// |c_e − s·t·p_e| / |s·t·p_e| and reports the max and the mean over the stroke's rows
// (an edge crossed twice counts once, against the mean of its rows' values). It also reports the
// deviation scaled by the edge length instead, |c_e − s·t·p_e| / (s·|p_e|) (the error of the field's tangential
// component along the edge, relative to the strength), which stays meaningful where the stroke crosses an edge
// almost at a right angle (s·t·p_e near 0).
import { execFileSync } from 'node:child_process';
import { existsSync, mkdtempSync, readFileSync, rmSync, writeFileSync, mkdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { basename, dirname, join, resolve } from 'node:path';
import { fileURLToPath } from 'node:url';

const ROOT = resolve(dirname(fileURLToPath(import.meta.url)), '..');

function parseArgs(argv) {
  const o = {
    mesh: 'bunny00',
    weights: [1, 1e2, 1e4, 1e6],
    face: null,
    crossings: 60,
    strength: 1,
    tvf: join(ROOT, 'build/tvf'),
    svg: join(ROOT, 'docs/images/weight-sweep.svg'),
  };
  for (let k = 2; k < argv.length; ++k) {
    const a = argv[k];
    const next = () => {
      if (k + 1 >= argv.length) throw new Error(`${a} needs a value`);
      return argv[++k];
    };
    if (a === '--mesh') o.mesh = next();
    else if (a === '--weights') o.weights = next().split(',').map(Number);
    else if (a === '--face') o.face = Number(next());
    else if (a === '--crossings') o.crossings = Number(next());
    else if (a === '--strength') o.strength = Number(next());
    else if (a === '--tvf') o.tvf = resolve(next());
    else if (a === '--svg') o.svg = resolve(next());
    else if (a === '--no-svg') o.svg = null;
    else if (a === '-h' || a === '--help') {
      console.error(readFileSync(fileURLToPath(import.meta.url), 'utf8').split('\n').slice(2, 12).join('\n'));
      process.exit(0);
    } else throw new Error(`unknown argument ${a}`);
  }
  if (!o.weights.length || o.weights.some((w) => !(w > 0))) throw new Error('--weights: positive numbers');
  return o;
}

// ---- mesh -------------------------------------------------------------------------------------------------------

// OFF as core/io/off_loader.cpp reads it: '#' comments, polygons fan-triangulated in order (v0, vj, vj+1).
function readOff(path) {
  const text = readFileSync(path, 'latin1');
  const tokens = text.replace(/#[^\n]*/g, ' ').split(/\s+/).filter(Boolean);
  let k = 0;
  const header = tokens[k++];
  if (header !== 'OFF') throw new Error(`${path}: only plain OFF is supported here (header '${header}')`);
  const nv = Number(tokens[k++]);
  const nf = Number(tokens[k++]);
  k++;
  const pos = new Float64Array(3 * nv);
  for (let i = 0; i < 3 * nv; ++i) pos[i] = Number(tokens[k++]);
  const tris = [];
  for (let f = 0; f < nf; ++f) {
    const n = Number(tokens[k++]);
    const idx = tokens.slice(k, k + n).map(Number);
    k += n;
    for (let j = 1; j + 1 < n; ++j) tris.push(idx[0], idx[j], idx[j + 1]);
  }
  return { pos, tris: Int32Array.from(tris), nv, nf: tris.length / 3 };
}

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const scale = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = (a) => Math.hypot(a[0], a[1], a[2]);

class Mesh {
  constructor({ pos, tris, nv, nf }) {
    Object.assign(this, { pos, tris, nv, nf });
    this.edgeFaces = new Map(); // canonical key -> faces
    for (let f = 0; f < nf; ++f)
      for (let c = 0; c < 3; ++c) {
        const key = this.key(tris[3 * f + c], tris[3 * f + ((c + 1) % 3)]);
        const list = this.edgeFaces.get(key);
        if (list) list.push(f);
        else this.edgeFaces.set(key, [f]);
      }
  }
  key(i, j) {
    return i < j ? i * this.nv + j : j * this.nv + i;
  }
  vertex(v) {
    return [this.pos[3 * v], this.pos[3 * v + 1], this.pos[3 * v + 2]];
  }
  corners(f) {
    return [0, 1, 2].map((c) => this.vertex(this.tris[3 * f + c]));
  }
  // p_e in canonical orientation (lower vertex index to higher).
  edgeVector(i, j) {
    return i < j ? sub(this.vertex(j), this.vertex(i)) : sub(this.vertex(i), this.vertex(j));
  }
  otherFace(i, j, f) {
    const list = this.edgeFaces.get(this.key(i, j)) ?? [];
    if (list.length !== 2) return -1; // boundary or non-manifold: the walk stops, as the core's does
    return list[0] === f ? list[1] : list[0];
  }
  // Unit normal and barycentric gradients, as core/mesh/mesh_geometry.h forms them.
  frame(p) {
    const n2 = cross(sub(p[1], p[0]), sub(p[2], p[0]));
    const twiceArea = norm(n2);
    const n = twiceArea > 0 ? scale(n2, 1 / twiceArea) : [0, 0, 0];
    const grad = [0, 1, 2].map((k) => scale(cross(n, sub(p[(k + 2) % 3], p[(k + 1) % 3])), 1 / twiceArea));
    return { n, grad };
  }
}

const at = (p, b) => add(add(scale(p[0], b[0]), scale(p[1], b[1])), scale(p[2], b[2]));

// One step of a straight walk: from bary in face along the in-plane direction d, to the edge where the first
// barycentric coordinate reaches zero. Returns the exit corner, the crossing's barycentrics in the next face, etc.
function crossFace(mesh, face, bary, d, p, grad) {
  let exitCorner = -1;
  let sMin = Infinity;
  for (let k = 0; k < 3; ++k) {
    const rate = dot(grad[k], d);
    if (rate < 0) {
      const s = -bary[k] / rate;
      if (s < sMin) {
        sMin = s;
        exitCorner = k;
      }
    }
  }
  if (exitCorner < 0) return null;
  const ci = (exitCorner + 1) % 3;
  const cj = (exitCorner + 2) % 3;
  const vi = mesh.tris[3 * face + ci];
  const vj = mesh.tris[3 * face + cj];
  const bi = Math.max(0, bary[ci] + sMin * dot(grad[ci], d));
  const bj = Math.max(0, bary[cj] + sMin * dot(grad[cj], d));
  const tau = bj / Math.max(bi + bj, 1e-300);
  const exitBary = [0, 0, 0];
  exitBary[ci] = 1 - tau;
  exitBary[cj] = tau;
  const next = mesh.otherFace(vi, vj, face);
  let nextBary = null;
  if (next >= 0) {
    nextBary = [0, 1, 2].map((k) => {
      const v = mesh.tris[3 * next + k];
      return v === vi ? 1 - tau : v === vj ? tau : 0;
    });
  }
  return { vi, vj, next, nextBary, exitBary };
}

// The stroke rows, recomputed the way core/constraints/edge_rows.cpp (walkSegment) forms them: between consecutive
// points, walk towards the next point re-projected into each face; every crossed edge gets t·p_e, t the unit
// in-plane direction where it is crossed.
function strokeRows(mesh, points) {
  const rows = [];
  for (let k = 0; k + 1 < points.length; ++k) {
    const a = points[k];
    const b = points[k + 1];
    const target = at(mesh.corners(b.face), b.bary);
    let face = a.face;
    let bary = [...a.bary];
    const maxSteps = 64 + 4 * Math.trunc(Math.sqrt(mesh.nf)) * 8;
    for (let step = 0; step < maxSteps && face !== b.face; ++step) {
      const p = mesh.corners(face);
      const { n, grad } = mesh.frame(p);
      const u = sub(target, at(p, bary));
      const d = sub(u, scale(n, dot(n, u)));
      if (!(norm(d) > 1e-14 * norm(sub(p[1], p[0])))) break;
      const c = crossFace(mesh, face, bary, d, p, grad);
      if (!c) break;
      const t = scale(d, 1 / norm(d));
      const pe = mesh.edgeVector(c.vi, c.vj);
      rows.push({ i: Math.min(c.vi, c.vj), j: Math.max(c.vi, c.vj), value: dot(t, pe), length: norm(pe) });
      if (c.next < 0) break;
      face = c.next;
      bary = c.nextBary;
    }
  }
  return rows;
}

// A stroke made programmatically: start at the centroid of a face and walk straight (the direction carried into
// each next face by projection onto its plane) across up to `crossings` edges; a stroke point sits in the middle
// of the walk's segment in every 4th face, plus the start and the last face.
function makeStroke(mesh, startFace, crossings) {
  let face = startFace;
  let bary = [1 / 3, 1 / 3, 1 / 3];
  let p = mesh.corners(face);
  let d = sub(p[1], p[0]);
  const points = [{ face, bary: [...bary] }];
  let length = 0;
  for (let step = 1; step <= crossings; ++step) {
    p = mesh.corners(face);
    const { n, grad } = mesh.frame(p);
    d = sub(d, scale(n, dot(n, d)));
    d = scale(d, 1 / norm(d));
    const c = crossFace(mesh, face, bary, d, p, grad);
    if (!c) break;
    length += norm(sub(at(p, c.exitBary), at(p, bary)));
    if (step % 4 === 0 || step === crossings || c.next < 0) {
      points.push({ face, bary: [0, 1, 2].map((k) => (bary[k] + c.exitBary[k]) / 2) });
    }
    if (c.next < 0) break;
    face = c.next;
    bary = c.nextBary;
  }
  return { points, length };
}

// Default start: the face whose centroid is nearest the mesh's vertex centroid, i.e. on the body of the model
// rather than at an extremity.
function defaultStartFace(mesh) {
  const c = [0, 0, 0];
  for (let v = 0; v < mesh.nv; ++v) for (let a = 0; a < 3; ++a) c[a] += mesh.pos[3 * v + a] / mesh.nv;
  let best = -1;
  let bestDist = Infinity;
  for (let f = 0; f < mesh.nf; ++f) {
    const q = at(mesh.corners(f), [1 / 3, 1 / 3, 1 / 3]);
    const dist = norm(sub(q, c));
    if (dist < bestDist) {
      bestDist = dist;
      best = f;
    }
  }
  return best;
}

// ---- sweep ------------------------------------------------------------------------------------------------------

function runDesign(tvf, meshPath, design, dir, tag) {
  const designPath = join(dir, `design-${tag}.json`);
  const fieldPath = join(dir, `field-${tag}.json`);
  writeFileSync(designPath, JSON.stringify(design));
  execFileSync(tvf, ['design', meshPath, designPath, '-o', fieldPath], { stdio: ['ignore', 'ignore', 'inherit'] });
  const field = JSON.parse(readFileSync(fieldPath, 'utf8'));
  rmSync(fieldPath);
  return field;
}

// Rows on one edge (a stroke that crosses an edge twice) act together: with equal weights their least-squares
// target is the mean of their values, so the deviation is measured per edge against that mean.
function edgeTargets(mesh, rows) {
  const byEdge = new Map();
  for (const r of rows) {
    const k = mesh.key(r.i, r.j);
    const t = byEdge.get(k) ?? { i: r.i, j: r.j, sum: 0, count: 0, length: r.length };
    t.sum += r.value;
    t.count += 1;
    byEdge.set(k, t);
  }
  return [...byEdge.values()].map((t) => ({ i: t.i, j: t.j, value: t.sum / t.count, length: t.length }));
}

function measure(mesh, field, rows, strength) {
  const index = new Map();
  field.edges.forEach(([i, j], e) => index.set(mesh.key(i, j), e));
  const targets = edgeTargets(mesh, rows);
  let maxRel = 0;
  let sumRel = 0;
  let maxScaled = 0;
  let sumScaled = 0;
  for (const r of targets) {
    const e = index.get(mesh.key(r.i, r.j));
    if (e === undefined) throw new Error(`edge ${r.i}-${r.j} is not in the field file`);
    const prescribed = strength * r.value;
    const diff = Math.abs(field.oneForm[e] - prescribed);
    const rel = diff / Math.abs(prescribed);
    const scaled = diff / (Math.abs(strength) * r.length);
    maxRel = Math.max(maxRel, rel);
    sumRel += rel;
    maxScaled = Math.max(maxScaled, scaled);
    sumScaled += scaled;
  }
  return {
    maxRelDeviation: maxRel,
    meanRelDeviation: sumRel / targets.length,
    maxEdgeScaledDeviation: maxScaled,
    meanEdgeScaledDeviation: sumScaled / targets.length,
    solveMs: field.stats?.solveMs,
  };
}

const fmtPct = (x) => {
  const pct = 100 * x;
  if (pct >= 10) return `${pct.toFixed(1)} %`;
  return `${pct.toPrecision(pct >= 0.01 ? 3 : 2)} %`;
};
const fmtWeight = (w) => {
  const e = Math.log10(w);
  return Number.isInteger(e) && e >= 2 ? `1e${e}` : String(w);
};

// The README's table: one column per weight (docs: README.md, "What the designer guarantees").
function markdownTable(summary) {
  const r = summary.results;
  return [
    `| weight | ${r.map((x) => fmtWeight(x.weight)).join(' | ')} |`,
    `|---|${r.map(() => '---|').join('')}`,
    `| max | ${r.map((x) => fmtPct(x.maxRelDeviation)).join(' | ')} |`,
    `| mean | ${r.map((x) => fmtPct(x.meanRelDeviation)).join(' | ')} |`,
  ].join('\n');
}

// ---- SVG: log-log line chart ------------------------------------------------------------------------------------

function svgChart(summary) {
  const W = 560;
  const H = 340;
  const m = { left: 70, right: 20, top: 40, bottom: 50 };
  const xs = summary.results.map((r) => Math.log10(r.weight));
  const series = [
    { name: 'max', color: '#c0392b', values: summary.results.map((r) => r.maxRelDeviation) },
    { name: 'mean', color: '#2874a6', values: summary.results.map((r) => r.meanRelDeviation) },
  ];
  const all = series.flatMap((s) => s.values).filter((v) => v > 0);
  const yMin = Math.floor(Math.log10(Math.min(...all)));
  const yMax = Math.ceil(Math.log10(Math.max(...all)));
  const xMin = Math.min(...xs);
  const xMax = Math.max(...xs);
  const px = (x) => m.left + ((x - xMin) / Math.max(xMax - xMin, 1)) * (W - m.left - m.right);
  const py = (ly) => m.top + ((yMax - ly) / Math.max(yMax - yMin, 1)) * (H - m.top - m.bottom);
  const out = [];
  out.push(`<svg xmlns="http://www.w3.org/2000/svg" width="${W}" height="${H}" viewBox="0 0 ${W} ${H}" ` +
    `font-family="sans-serif" font-size="12">`);
  out.push(`<rect width="${W}" height="${H}" fill="#fff"/>`);
  out.push(`<text x="${W / 2}" y="20" text-anchor="middle" font-size="14">Stroke weight sweep on ${summary.mesh} ` +
    `(${summary.edges.toLocaleString('en-US')} edges, ${summary.strokeRows} constrained edges)</text>`);
  const yStep = yMax - yMin > 8 ? 2 : 1;
  for (let e = yMin; e <= yMax; e += yStep) {
    const y = py(e).toFixed(1);
    out.push(`<line x1="${m.left}" y1="${y}" x2="${W - m.right}" y2="${y}" stroke="#ddd"/>`);
    out.push(`<text x="${m.left - 6}" y="${y}" text-anchor="end" dominant-baseline="middle">1e${e}</text>`);
  }
  for (let i = 0; i < xs.length; ++i) {
    const x = px(xs[i]).toFixed(1);
    out.push(`<line x1="${x}" y1="${m.top}" x2="${x}" y2="${H - m.bottom}" stroke="#eee"/>`);
    out.push(`<text x="${x}" y="${H - m.bottom + 16}" text-anchor="middle">${fmtWeight(summary.results[i].weight)}</text>`);
  }
  out.push(`<rect x="${m.left}" y="${m.top}" width="${W - m.left - m.right}" height="${H - m.top - m.bottom}" ` +
    `fill="none" stroke="#444"/>`);
  out.push(`<text x="${(m.left + W - m.right) / 2}" y="${H - 12}" text-anchor="middle">stroke weight ` +
    `(relative to the mean diagonal; log scale)</text>`);
  out.push(`<text transform="translate(16 ${(m.top + H - m.bottom) / 2}) rotate(-90)" text-anchor="middle">` +
    `max, mean of |c_e − s·t·p_e| / |s·t·p_e| (log)</text>`);
  series.forEach((s, k) => {
    const pts = s.values.map((v, i) => `${px(xs[i]).toFixed(1)},${py(Math.log10(v)).toFixed(1)}`);
    out.push(`<polyline points="${pts.join(' ')}" fill="none" stroke="${s.color}" stroke-width="2"/>`);
    for (const q of pts) {
      const [x, y] = q.split(',');
      out.push(`<circle cx="${x}" cy="${y}" r="3.5" fill="${s.color}"/>`);
    }
    const lx = W - m.right - 150;
    const ly = m.top + 16 + 18 * k;
    out.push(`<line x1="${lx}" y1="${ly}" x2="${lx + 24}" y2="${ly}" stroke="${s.color}" stroke-width="2"/>`);
    out.push(`<text x="${lx + 30}" y="${ly}" dominant-baseline="middle">${s.name} over the stroke</text>`);
  });
  out.push('</svg>');
  return out.join('\n') + '\n';
}

// ---- main -------------------------------------------------------------------------------------------------------

function main() {
  const o = parseArgs(process.argv);
  const meshPath = existsSync(o.mesh) ? resolve(o.mesh) : join(ROOT, 'bench-data/meshes', `${o.mesh}.off`);
  if (!existsSync(meshPath)) throw new Error(`${meshPath} not found: run bash scripts/fetch-meshes.sh first`);
  if (!existsSync(o.tvf)) throw new Error(`${o.tvf} not found: build the native CLI first (scripts/build-native.sh)`);
  const mesh = new Mesh(readOff(meshPath));
  const startFace = o.face ?? defaultStartFace(mesh);
  const { points, length } = makeStroke(mesh, startFace, o.crossings);
  const rows = strokeRows(mesh, points);
  if (rows.length < 2) throw new Error(`the stroke from face ${startFace} crosses ${rows.length} edges; try --face`);
  const design = (weight) => ({
    schema: 'tvf-design/1',
    boundary: 'free',
    gamma: 0,
    constraints: [{ type: 'stroke', points, strength: o.strength, weight }],
  });
  const dir = mkdtempSync(join(tmpdir(), 'weight-sweep-'));
  const results = [];
  let edges = 0;
  try {
    for (const weight of o.weights) {
      const field = runDesign(o.tvf, meshPath, design(weight), dir, String(weight));
      edges = field.edges.length;
      results.push({ weight, ...measure(mesh, field, rows, o.strength) });
    }
  } finally {
    rmSync(dir, { recursive: true, force: true });
  }
  const summary = {
    mesh: basename(meshPath, '.off'),
    meshPath: meshPath.startsWith(ROOT) ? meshPath.slice(ROOT.length + 1) : meshPath,
    vertices: mesh.nv,
    faces: mesh.nf,
    edges,
    stroke: {
      startFace,
      points: points.length,
      length,
      strength: o.strength,
    },
    strokeRows: rows.length,
    strokeEdges: new Set(rows.map((r) => mesh.key(r.i, r.j))).size,
    measure: 'per constrained edge (rows on one edge: their mean): |c_e − s·t·p_e| / |s·t·p_e| (relative); |c_e − s·t·p_e| / (s·|p_e|) (edge-scaled)',
    results,
  };
  if (o.svg) {
    mkdirSync(dirname(o.svg), { recursive: true });
    writeFileSync(o.svg, svgChart(summary));
  }
  console.log(JSON.stringify(summary, null, 2));
  console.error(`\n${summary.mesh}: ${summary.edges} edges, stroke of ${summary.stroke.points} points crossing ` +
    `${summary.strokeRows} edges\n\n${markdownTable(summary)}\n`);
}

try {
  main();
} catch (e) {
  console.error(`weight-sweep: ${e.message}`);
  process.exit(1);
}

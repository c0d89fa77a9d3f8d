// The baked stripe pattern measured on exported GLBs as docs/texture-synthesis.md measures the synthesized texture
// (tests/e2e/surface-texture-metrics.mjs: the stripes' direction from every texel's luminance gradient against the
// field, per face; the colour jump across chart seams against the jump across interior edges), model by model.
// Runs the native `tvf export --stripes` (the page's exportGlb() bakes with the same core code) on each model with
// a design of the asked symmetry (the smoothest field, or aligned with the principal curvatures), and prints JSON.
//   node scripts/stripe-quality.mjs [--symmetry 2] [--curvature 0] [--size 2048] [--per-diagonal 40 | --frequency F]
//     [--truth] MESH...
// Each model's figures come twice: by stripeAlignment (the window's tensor against the middle face's field) and by
// stripeAlignmentAlongField (each texel against its own face's field); a grid (--symmetry 4) also each family
// apart (gridFamiliesAlongField: the lines along each face's field direction X, and along n x X), labelled by
// the pattern's own families (familiesByPhase: the phase the GLB carries) and per face the worse and the better.
// both measures of a texture of known direction: the same atlas repainted with straight 3D stripes and their
// exact field.
// Writes into .cache/stripe-quality/ (ignored).
import { execFileSync } from 'node:child_process';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { basename, join } from 'node:path';
import {
  gridFamiliesAlongField, paintHeightStripes, readGlb, seamJumpRatio, stripeAlignment, stripeAlignmentAlongField,
} from '../tests/e2e/surface-texture-metrics.mjs';
import { familiesByPhase } from '../tests/e2e/stripe-phase-families.mjs';

const args = process.argv.slice(2);
const option = (name, fallback) => {
  const i = args.indexOf(`--${name}`);
  if (i < 0) return fallback;
  const [value] = args.splice(i, 2).slice(1);
  return Number(value);
};
const symmetry = option('symmetry', 2), curvature = option('curvature', 0), size = option('size', 2048);
const truth = args.includes('--truth');
if (truth) args.splice(args.indexOf('--truth'), 1);
const perDiagonal = option('per-diagonal', 40), fixedFrequency = option('frequency', 0), profile = symmetry === 4 ? 'grid' : 'stripes';
const out = '.cache/stripe-quality';
mkdirSync(out, { recursive: true });

function readOff(path) {
  const words = readFileSync(path, 'utf8').replace(/#.*$/gm, '').split(/\s+/).filter(Boolean);
  const nV = Number(words[1]), nF = Number(words[2]);
  const positions = words.slice(4, 4 + 3 * nV).map(Number);
  const triangles = [];
  let i = 4 + 3 * nV;
  for (let f = 0; f < nF; f++) {
    const n = Number(words[i]);
    triangles.push(...words.slice(i + 1, i + 4).map(Number));
    i += n + 1;
  }
  return { positions, triangles };
}

// The page's default frequency (web/stripes/controller.js defaultFrequency).
function frequencyOf({ positions, triangles }) {
  const lo = [Infinity, Infinity, Infinity], hi = [-Infinity, -Infinity, -Infinity];
  for (let i = 0; i < positions.length; i += 3)
    for (let c = 0; c < 3; c++) (lo[c] = Math.min(lo[c], positions[i + c])), (hi[c] = Math.max(hi[c], positions[i + c]));
  let edge = 0;
  for (let f = 0; f < triangles.length; f += 3)
    for (let k = 0; k < 3; k++) {
      const a = triangles[f + k], b = triangles[f + ((k + 1) % 3)];
      edge += Math.hypot(...[0, 1, 2].map((c) => positions[3 * a + c] - positions[3 * b + c]));
    }
  edge /= triangles.length;
  const diagonal = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
  return Number(Math.min(perDiagonal / diagonal, 1 / (4 * edge)).toPrecision(2));
}

const results = [];
for (const meshPath of args) {
  const name = basename(meshPath).replace(/\.[^.]+$/, '');
  const mesh = readOff(meshPath);
  const frequency = fixedFrequency || frequencyOf(mesh);
  const design = join(out, `${name}.design.json`);
  writeFileSync(design, JSON.stringify({ symmetry, curvatureAlignment: curvature, constraints: [] }));
  const fieldPath = join(out, `${name}.field.json`), glbPath = join(out, `${name}.stripes.glb`);
  execFileSync('build/tvf', ['design', meshPath, design, '-o', fieldPath]);
  const t0 = performance.now();
  execFileSync('build/tvf', ['export', meshPath, design, '--glb', glbPath, '--size', String(size), '--stripes',
    String(frequency), '--stripe-profile', profile]);
  const exportMs = performance.now() - t0;
  const field = JSON.parse(readFileSync(fieldPath, 'utf8'));
  const faceVectors = Float64Array.from((field.faceDirections ?? field.faceVectors).flat());
  const glb = readGlb(readFileSync(glbPath));
  const period = 1 / frequency;
  // Area-weighted means and shares within 1 and 5 degrees, and the same away (> 2 periods) from the field's
  // singularities.
  const singular = (field.singularities ?? []).map((s) => mesh.positions.slice(3 * s.vertex, 3 * s.vertex + 3));
  const summary = (errors) => {
    let area = 0, w1 = 0, w5 = 0, sum = 0, areaFar = 0, sumFar = 0, w1Far = 0, w5Far = 0;
    for (let f = 0; f < mesh.triangles.length / 3; f++) {
      const e = errors[f];
      if (!Number.isFinite(e)) continue;
      const P = [0, 1, 2].map((k) => mesh.positions.slice(3 * mesh.triangles[3 * f + k], 3 * mesh.triangles[3 * f + k] + 3));
      const u = [0, 1, 2].map((c) => P[1][c] - P[0][c]), v = [0, 1, 2].map((c) => P[2][c] - P[0][c]);
      const a = 0.5 * Math.hypot(u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]);
      const c = [0, 1, 2].map((k) => (P[0][k] + P[1][k] + P[2][k]) / 3);
      const near = singular.some((s) => Math.hypot(s[0] - c[0], s[1] - c[1], s[2] - c[2]) < 2 * period);
      area += a, sum += a * e, w1 += e <= 1 ? a : 0, w5 += e <= 5 ? a : 0;
      if (!near) (areaFar += a), (sumFar += a * e), (w1Far += e <= 1 ? a : 0), (w5Far += e <= 5 ? a : 0);
    }
    return {
      meanDegrees: sum / area, within1: w1 / area, within5: w5 / area, meanDegreesAwayFromSingularities: sumFar / areaFar,
      within1AwayFromSingularities: w1Far / areaFar, within5AwayFromSingularities: w5Far / areaFar,
    };
  };
  const seams = seamJumpRatio(glb, mesh.triangles);
  const r = {
    model: name, faces: mesh.triangles.length / 3, frequency, size, profile, symmetry, exportMs: Math.round(exportMs),
    singularities: singular.length, ...summary(stripeAlignment(glb, faceVectors, period).errors),
    alongField: summary(stripeAlignmentAlongField(glb, faceVectors, period, symmetry).errors),
    seamRatio: seams.ratio, seamEdges: seams.seamEdges,
  };
  // A grid's families apart, each against its own direction of the cross field: the pattern's first and second
  // (told by the phase the GLB carries), and per face the worse of its two and the better.
  if (symmetry === 4) {
    const [a, b] = gridFamiliesAlongField(glb, faceVectors, period);
    const worse = a.map((e, f) => Math.max(e, b[f])), better = a.map((e, f) => Math.min(e, b[f]));
    const [first, second] = familiesByPhase(glb, faceVectors, [a, b]);
    r.families = { first: summary(first), second: summary(second), worse: summary(worse), better: summary(better) };
  }
  // The measures' own error: the texture repainted with straight 3D stripes and their exact field.
  if (truth) {
    const painted = paintHeightStripes(glb, [1, 2, 3].map((x) => x / Math.sqrt(14)), frequency);
    r.truth = {
      stripeAlignment: summary(stripeAlignment(painted.glb, painted.field, period).errors),
      alongField: summary(stripeAlignmentAlongField(painted.glb, painted.field, period, 2).errors),
    };
  }
  results.push(r);
  console.error(JSON.stringify(r));
}
console.log(JSON.stringify(results, null, 1));

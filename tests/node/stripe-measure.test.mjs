// SPDX-License-Identifier: GPL-2.0-or-later
// The instrument that reads a baked texture's stripe direction (tests/e2e/surface-texture-metrics.mjs), checked
// against a texture of known direction: a cylinder as thin as two of its stripes' periods, unrolled into one
// chart, painted with the level sets of a height along a slanted direction (paintHeightStripes), whose exact
// field is known per face. Read in each face's own frame of the field (stripeAlignmentAlongField), the stripes
// lie along it; the same field turned by 10° reads 10°; a window's tensor against its middle face
// (stripeAlignment) reads the bending of the surface as error. A grid of lines along and round the cylinder reads
// along its cross field the same way. Run: node --test tests/node/stripe-measure.test.mjs
import assert from 'node:assert/strict';
import test from 'node:test';
import {
  gridFamiliesAlongField, paintHeightStripes, stripeAlignment, stripeAlignmentAlongField,
} from '../e2e/surface-texture-metrics.mjs';
import { familiesByPhase } from '../e2e/stripe-phase-families.mjs';

// A GLB-like model (unwelded faces, one chart: u along the circumference, v along the axis) on a blank image.
function unrolledCylinder(radius, length, around, along, size) {
  const positions = [], uvs = [];
  const point = (i, j) => {
    const a = (2 * Math.PI * i) / around;
    return [radius * Math.cos(a), radius * Math.sin(a), (length * j) / along];
  };
  const uv = (i, j) => [0.05 + (0.9 * i) / around, 0.05 + (0.9 * j) / along];
  for (let i = 0; i < around; i++)
    for (let j = 0; j < along; j++)
      for (const [di, dj] of [[0, 0], [1, 0], [1, 1], [0, 0], [1, 1], [0, 1]]) {
        positions.push(...point(i + di, j + dj));
        uvs.push(...uv(i + di, j + dj));
      }
  const indices = Uint32Array.from({ length: positions.length / 3 }, (_, k) => k);
  const image = { width: size, height: size, pixels: new Uint8Array(4 * size * size) };
  return { positions: Float32Array.from(positions), uvs: Float32Array.from(uvs), indices, image };
}

// Each face's vector turned by `degrees` about the face's normal.
function turned(field, glb, degrees) {
  const out = new Float64Array(field.length);
  const c = Math.cos((degrees * Math.PI) / 180), s = Math.sin((degrees * Math.PI) / 180);
  for (let f = 0; f < field.length / 3; f++) {
    const P = [0, 1, 2].map((k) => Array.from(glb.positions.subarray(9 * f + 3 * k, 9 * f + 3 * k + 3)));
    const e1 = P[1].map((x, k) => x - P[0][k]), e2 = P[2].map((x, k) => x - P[0][k]);
    const n = [e1[1] * e2[2] - e1[2] * e2[1], e1[2] * e2[0] - e1[0] * e2[2], e1[0] * e2[1] - e1[1] * e2[0]];
    const l = Math.hypot(...n);
    const u = n.map((x) => x / l), v = Array.from(field.subarray(3 * f, 3 * f + 3));
    const w = [u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0]];
    for (let k = 0; k < 3; k++) out[3 * f + k] = c * v[k] + s * w[k];
  }
  return out;
}

const mean = (errors) => {
  let sum = 0, n = 0;
  for (const e of errors) if (Number.isFinite(e)) (sum += e), n++;
  return { mean: sum / n, faces: n };
};

test('straight stripes on a thin cylinder read along their own field, and a turned field reads its turn', () => {
  const frequency = 8, period = 1 / frequency;
  const model = unrolledCylinder(0.15, 1, 64, 32, 512);
  const { glb, field } = paintHeightStripes(model, [1, 2, 3].map((x) => x / Math.sqrt(14)), frequency);
  const exact = mean(stripeAlignmentAlongField(glb, field, period, 2).errors);
  assert.ok(exact.faces > 2000, `${exact.faces} faces measured`);
  assert.ok(exact.mean < 0.3, `stripes along their exact field read ${exact.mean.toFixed(3)}°`);
  const off = mean(stripeAlignmentAlongField(glb, turned(field, glb, 10), period, 2).errors);
  assert.ok(Math.abs(off.mean - 10) < 0.5, `the field turned by 10° reads ${off.mean.toFixed(3)}°`);
  const windowed = mean(stripeAlignment(glb, field, period).errors);
  assert.ok(windowed.mean > 2 * exact.mean + 1, `the window's tensor reads ${windowed.mean.toFixed(3)}°`);
});

// A grid on the same cylinder: lines along its axis and round it (eight round it, eight a unit along it), the
// field round it; every texel's grey and its face's field painted here. With `helix` the lines round it climb
// one period per turn (a helix, atan(1 / (8 2π r)) = 7.55° off the field at r = 0.15), those along it stay.
function paintCylinderGrid(model, helix = false) {
  const { width: W, height: H } = model.image;
  const pixels = new Uint8Array(4 * W * H);
  const field = new Float64Array(model.positions.length / 3);
  for (let f = 0; f < model.indices.length / 3; f++) {
    const corner = (k) => Array.from(model.positions.subarray(9 * f + 3 * k, 9 * f + 3 * k + 3));
    const uv = (k) => [model.uvs[6 * f + 2 * k] * W, model.uvs[6 * f + 2 * k + 1] * H];
    const P = [0, 1, 2].map(corner), Q = [0, 1, 2].map(uv);
    const c = [0, 1, 2].map((k) => (P[0][k] + P[1][k] + P[2][k]) / 3), r = Math.hypot(c[0], c[1]);
    field.set([-c[1] / r, c[0] / r, 0], 3 * f);
    const det = (Q[1][0] - Q[0][0]) * (Q[2][1] - Q[0][1]) - (Q[2][0] - Q[0][0]) * (Q[1][1] - Q[0][1]);
    for (let y = Math.floor(Math.min(Q[0][1], Q[1][1], Q[2][1])); y <= Math.max(Q[0][1], Q[1][1], Q[2][1]); y++)
      for (let x = Math.floor(Math.min(Q[0][0], Q[1][0], Q[2][0])); x <= Math.max(Q[0][0], Q[1][0], Q[2][0]); x++) {
        const px = x + 0.5 - Q[0][0], py = y + 0.5 - Q[0][1];
        const b1 = (px * (Q[2][1] - Q[0][1]) - py * (Q[2][0] - Q[0][0])) / det;
        const b2 = (py * (Q[1][0] - Q[0][0]) - px * (Q[1][1] - Q[0][1])) / det;
        if (b1 < 0 || b2 < 0 || b1 + b2 > 1) continue;
        const p = [0, 1, 2].map((k) => P[0][k] + b1 * (P[1][k] - P[0][k]) + b2 * (P[2][k] - P[0][k]));
        const line = (phase) => Math.exp(-8 * (1 - Math.cos(2 * Math.PI * phase)));
        const around = (8 * Math.atan2(p[1], p[0])) / (2 * Math.PI);
        const round = 8 * p[2] + (helix ? Math.atan2(p[1], p[0]) / (2 * Math.PI) : 0);
        const grey = 1 + Math.round(254 * (1 - Math.max(line(round), line(around))));
        const i = 4 * (y * W + x);
        pixels[i] = pixels[i + 1] = pixels[i + 2] = grey;
        pixels[i + 3] = 255;
      }
  }
  return { glb: { ...model, image: { ...model.image, pixels } }, field };
}

test("a grid's lines read along its cross field's directions, and a turned field reads its turn", () => {
  const period = 1 / 8;
  const { glb, field } = paintCylinderGrid(unrolledCylinder(0.15, 1, 64, 32, 512));
  const exact = mean(stripeAlignmentAlongField(glb, field, period, 4).errors);
  assert.ok(exact.faces > 2000, `${exact.faces} faces measured`);
  assert.ok(exact.mean < 0.5, `grid lines along their exact field read ${exact.mean.toFixed(3)}°`);
  const off = mean(stripeAlignmentAlongField(glb, turned(field, glb, 10), period, 4).errors);
  assert.ok(Math.abs(off.mean - 10) < 0.7, `the field turned by 10° reads ${off.mean.toFixed(3)}°`);
});

test("a grid's two families read apart: lines round the cylinder turned into a helix, those along it not", () => {
  const period = 1 / 8, helixDegrees = (Math.atan(1 / (8 * 2 * Math.PI * 0.15)) * 180) / Math.PI;
  const straight = paintCylinderGrid(unrolledCylinder(0.15, 1, 64, 32, 512));
  const [round, along] = gridFamiliesAlongField(straight.glb, straight.field, period).map(mean);
  assert.ok(round.faces > 2000 && along.faces > 2000, `${round.faces} and ${along.faces} faces measured`);
  assert.ok(round.mean < 0.5 && along.mean < 0.5,
    `families read ${round.mean.toFixed(3)}° and ${along.mean.toFixed(3)}°`);
  const helix = paintCylinderGrid(unrolledCylinder(0.15, 1, 64, 32, 512), true);
  const [helical, kept] = gridFamiliesAlongField(helix.glb, helix.field, period).map(mean);
  assert.ok(Math.abs(helical.mean - helixDegrees) < 0.7,
    `the helix reads ${helical.mean.toFixed(3)}° (${helixDegrees.toFixed(2)}°)`);
  assert.ok(kept.mean < 0.5, `the lines along the axis read ${kept.mean.toFixed(3)}°`);
  // Both at once (the fourth-order reading) splits the difference; the families' own readings do not.
  const both = mean(stripeAlignmentAlongField(helix.glb, helix.field, period, 4).errors);
  assert.ok(both.mean > 2 && both.mean < helixDegrees - 2, `both families at once read ${both.mean.toFixed(3)}°`);
  // A cross field's face direction is any one of its four: the field turned a quarter on every other face, whose
  // families then swap, reads the same.
  const quarter = turned(helix.field, helix.glb, 90).map((x, i) => (Math.floor(i / 3) % 2 ? x : helix.field[i]));
  const mixed = gridFamiliesAlongField(helix.glb, quarter, period);
  const byFamily = (k) => mixed[0].map((_, f) => mixed[f % 2 ? 1 - k : k][f]);
  const [again0, again1] = [0, 1].map((k) => mean(byFamily(k)));
  assert.ok(Math.abs(again0.mean - helical.mean) < 0.2 && Math.abs(again1.mean - kept.mean) < 0.2,
    `with mixed representatives ${again0.mean.toFixed(3)}° and ${again1.mean.toFixed(3)}°`);
});

// The painted grid's phases as an exported GLB carries them (TEXCOORD_1, in periods): the lines round the cylinder
// as the first family and those along it as the second, or the other way with `swap`; each face's corners
// unwrapped about its centroid's angle, as the export splits vertices where the phase differs.
function withPhases(glb, helix, swap) {
  const phases = new Float32Array((2 * glb.positions.length) / 3);
  for (let f = 0; f < glb.indices.length / 3; f++) {
    const P = [0, 1, 2].map((k) => Array.from(glb.positions.subarray(9 * f + 3 * k, 9 * f + 3 * k + 3)));
    const middle = Math.atan2(P[0][1] + P[1][1] + P[2][1], P[0][0] + P[1][0] + P[2][0]);
    P.forEach((p, k) => {
      let a = Math.atan2(p[1], p[0]) - middle;
      a -= 2 * Math.PI * Math.round(a / (2 * Math.PI));
      const angle = (middle + a) / (2 * Math.PI);
      const round = 8 * p[2] + (helix ? angle : 0), around = 8 * angle;
      phases.set(swap ? [around, round] : [round, around], 2 * (3 * f + k));
    });
  }
  return { ...glb, phases };
}

test("a grid's families are told apart by the pattern's own phases, whatever the field's face directions", () => {
  const period = 1 / 8, helixDegrees = (Math.atan(1 / (8 * 2 * Math.PI * 0.15)) * 180) / Math.PI;
  const helix = paintCylinderGrid(unrolledCylinder(0.15, 1, 64, 32, 512), true);
  // The field turned a quarter on every other face: gridFamiliesAlongField's labels then alternate.
  const quarter = turned(helix.field, helix.glb, 90).map((x, i) => (Math.floor(i / 3) % 2 ? x : helix.field[i]));
  for (const swap of [false, true]) {
    const glb = withPhases(helix.glb, true, swap);
    const [first, second] = familiesByPhase(glb, quarter, gridFamiliesAlongField(glb, quarter, period)).map(mean);
    const [helical, kept] = swap ? [second, first] : [first, second];
    assert.ok(helical.faces > 2000 && kept.faces > 2000, `${helical.faces} and ${kept.faces} faces labelled`);
    const which = swap ? 'second' : 'first';
    assert.ok(Math.abs(helical.mean - helixDegrees) < 0.7,
      `the helical family (${which}) reads ${helical.mean.toFixed(3)}° (${helixDegrees.toFixed(2)}°)`);
    assert.ok(kept.mean < 0.5, `the family along the axis reads ${kept.mean.toFixed(3)}°`);
  }
  assert.throws(() => familiesByPhase(helix.glb, helix.field, [[], []]), /no phase/);
});

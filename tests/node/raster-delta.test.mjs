// Which faces a new field is drawn again for (web/synthesis/raster-delta.js), against the field itself: a face
// left as drawn must have its field, at every point of it, within the angle asked of the one drawn, and scaled
// within its sine (sampled densely here, in double precision); the rectangles drawn must hold every moved face's
// texels; and when a field's frame waits for its texture (quick-edits.js followsWithin).
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { blockRects, blocksOf, coarserRects, faceBoxes, faceMoved } from '../../web/synthesis/raster-delta.js';
import { noteJacobianDrawn } from '../../web/synthesis/raster-delta.js';
import { FOLLOW_MS, followsWithin } from '../../web/synthesis/quick-edits.js';
import { FIELD_UPLOAD_PHASE } from '../../web/synthesis/phase-clock.js';

// A small deterministic generator (mulberry32).
function random(seed) {
  let a = seed >>> 0;
  return () => {
    a = (a + 0x6d2b79f5) >>> 0;
    let t = Math.imul(a ^ (a >>> 15), 1 | a);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

const project = (v, n) => {
  const s = v[0] * n[0] + v[1] * n[1] + v[2] * n[2];
  return v.map((x, d) => x - s * n[d]);
};
const len = (v) => Math.hypot(...v);

// The largest angle (radians) and relative length change between the two fields interpolated over the face
// (barycentric samples), as the raster's shader projects them into the face's plane.
function worstChange(next, drawn, n) {
  let angle = 0, scale = 0;
  for (let i = 0; i <= 40; i++)
    for (let j = 0; i + j <= 40; j++) {
      const b = [i / 40, j / 40, 1 - (i + j) / 40];
      const at = (f) => project([0, 1, 2].map((d) => b.reduce((s, w, k) => s + w * f[4 * k + d], 0)), n);
      const p = at(next), q = at(drawn);
      if (len(p) === 0 || len(q) === 0) return { angle: Math.PI, scale: Infinity };
      const c = (p[0] * q[0] + p[1] * q[1] + p[2] * q[2]) / (len(p) * len(q));
      angle = Math.max(angle, Math.acos(Math.min(1, Math.max(-1, c))));
      scale = Math.max(scale, Math.abs(len(p) - len(q)) / len(p));
    }
  return { angle, scale };
}

test('a face left as drawn has its field within the angle everywhere in it; fields that vanish are drawn again', () => {
  const rnd = random(7), eps = (0.25 * Math.PI) / 180, sinTol = Math.sin(eps);
  const normal = new Float32Array([0, 0, 1]);
  let kept = 0, moved = 0;
  for (let trial = 0; trial < 3000; trial++) {
    // A field of about unit length with a random spread over the face, and the one drawn a random step away
    // (some well within the bound, some beyond it); a third of the trials' corners leave the plane a little.
    const base = [rnd() - 0.5, rnd() - 0.5, 0].map((x) => 2 * x);
    const spread = rnd() * 1.5, step = eps * 10 ** (rnd() * 2 - 1.5), lift = trial % 3 === 0 ? 0.3 : 0;
    const next = new Float32Array(12), drawn = new Float32Array(12);
    for (let k = 0; k < 3; k++)
      for (let d = 0; d < 3; d++) {
        next[4 * k + d] = (d === 2 ? lift * (rnd() - 0.5) : base[d] + spread * (rnd() - 0.5));
        drawn[4 * k + d] = next[4 * k + d] + step * (rnd() - 0.5) * (d === 2 ? 0 : 1);
      }
    if (faceMoved(next, drawn, normal, 0, sinTol)) {
      moved++;
      continue;
    }
    kept++;
    const { angle, scale } = worstChange(next, drawn, normal);
    assert.ok(angle <= eps * (1 + 1e-5), `trial ${trial}: kept with the field turned by ${(angle * 180) / Math.PI}°`);
    assert.ok(scale <= sinTol * (1 + 1e-5), `trial ${trial}: kept with the field scaled by ${scale}`);
  }
  assert.ok(kept > 300 && moved > 300, `both outcomes sampled (kept ${kept}, moved ${moved})`);
  // A field through zero inside the face (its corners opposite) is drawn again however small the change; the
  // same field exactly is not.
  const through = new Float32Array([1, 0, 0, 0, -1, 0, 0, 0, -1, 1, 0, 0]);
  const nudged = through.map((x, i) => (i === 0 ? x + 1e-7 : x));
  assert.equal(faceMoved(nudged, through, normal, 0, sinTol), true);
  assert.equal(faceMoved(through, through, normal, 0, sinTol), false);
});

test('the rectangles drawn hold every texel of the moved faces\' boxes, and the coarser levels their parents', () => {
  const rnd = random(3), R = 256, nF = 400;
  const uvs = new Float32Array(6 * nF);
  for (let f = 0; f < nF; f++) {
    const u = rnd() * 0.95, v = rnd() * 0.95;
    for (let k = 0; k < 3; k++) (uvs[6 * f + 2 * k] = u + 0.04 * rnd()), (uvs[6 * f + 2 * k + 1] = v + 0.04 * rnd());
  }
  const boxes = faceBoxes(uvs, R, 3);
  const faces = Int32Array.from({ length: 25 }, (_, i) => 16 * i);
  const rects = blockRects(boxes, faces, faces.length, R);
  const inside = (rs, x, y) => rs.some((r) => x >= r.x && x < r.x + r.w && y >= r.y && y < r.y + r.h);
  let area = 0;
  for (const r of rects) area += r.w * r.h;
  assert.ok(area < 0.9 * R * R, `the moved faces' part of the atlas only (${area} of ${R * R} texels)`);
  for (const f of faces) {
    const [x0, y0, x1, y1] = boxes.subarray(4 * f, 4 * f + 4);
    // The box holds the face's UVs and the gutter's reach past them.
    const us = [0, 2, 4].map((k) => uvs[6 * f + k] * R), vs = [1, 3, 5].map((k) => uvs[6 * f + k] * R);
    assert.ok(x0 <= Math.min(...us) - 2 && x1 >= Math.max(...us) + 2 && y0 <= Math.min(...vs) - 2);
    for (let y = y0; y < y1; y++)
      for (let x = x0; x < x1; x++) assert.ok(inside(rects, x, y), `face ${f} at ${x},${y}`);
    for (let k = 1; k <= 4; k++) {
      const coarse = coarserRects(rects, k);
      for (let y = y0; y < y1; y++)
        for (let x = x0; x < x1; x++) assert.ok(inside(coarse, x >> k, y >> k), `level ${k}: face ${f} at ${x},${y}`);
    }
  }
  assert.deepEqual(blockRects(boxes, faces, 0, R), []);
});

// Each level keeps where its Jacobian was drawn since the local update last compared it (local-update.js find
// compares only there): every draw's rectangles at the level's scale, anywhere (null) after a whole draw or before
// the first comparison, and the blocks that hold them.
test('each level knows where its Jacobian was drawn since it was compared, and the blocks that hold it', () => {
  const levels = [{}, {}, {}];
  const inside = (rs, x, y) => rs.some((r) => x >= r.x && x < r.x + r.w && y >= r.y && y < r.y + r.h);
  noteJacobianDrawn(levels, [{ x: 32, y: 48, w: 16, h: 32 }]);
  assert.deepEqual(levels.map((L) => L.jacDrawn), [null, null, null], 'never compared: anywhere');
  for (const L of levels) L.jacDrawn = []; // compared and made (local-update.js after)
  const a = { x: 32, y: 48, w: 16, h: 32 }, b = { x: 200, y: 0, w: 48, h: 16 };
  noteJacobianDrawn(levels, [a]);
  noteJacobianDrawn(levels, [b]);
  for (let k = 0; k < 3; k++) {
    for (const r of [a, b])
      for (let y = r.y; y < r.y + r.h; y++)
        for (let x = r.x; x < r.x + r.w; x++) {
          assert.ok(inside(levels[k].jacDrawn, x >> k, y >> k), `level ${k} at ${x},${y}`);
          assert.ok(inside(blocksOf(levels[k].jacDrawn), (x >> k) >> 4, (y >> k) >> 4), `its block`);
        }
    assert.ok(!inside(levels[k].jacDrawn, 100 >> k, 100 >> k), 'a texel drawn in neither');
  }
  noteJacobianDrawn(levels, null);
  assert.deepEqual(levels.map((L) => L.jacDrawn), [null, null, null], 'drawn whole: anywhere');
  for (const L of levels) L.jacDrawn = [];
  noteJacobianDrawn(levels, Array.from({ length: 600 }, (_, i) => ({ x: i, y: 0, w: 1, h: 1 })));
  assert.equal(levels[0].jacDrawn, null, 'too many rectangles: anywhere');
});

test('a field\'s frame waits for its texture only after a quick local update, the texture caught up', () => {
  const c = {
    active: true,
    options: { autoUpdate: true },
    stats: { local: true, preview: false, wallMs: 120 },
    runsQueued: 0,
    pendingField: false,
    settleTimer: null,
    lastFieldVersion: 4,
    getFieldVersion: () => 5,
  };
  assert.equal(followsWithin(c), 240);
  assert.equal(followsWithin({ ...c, stats: { ...c.stats, wallMs: 200 } }), FOLLOW_MS);
  assert.equal(followsWithin({ ...c, stats: { ...c.stats, wallMs: FOLLOW_MS + 1 } }), 0); // a slow update
  assert.equal(followsWithin({ ...c, followMs: 2000, stats: { ...c.stats, wallMs: 400 } }), 800); // a test's budget
  assert.equal(followsWithin({ ...c, stats: { ...c.stats, local: false } }), 0); // a whole run, none local after
  // A whole run whose next is local (its first of the atlas): half the budget, its own time unknown, unless its
  // field upload (which a local run makes again) took over a quarter of the budget.
  const whole = { ...c.stats, local: false, localNext: true, wallMs: 4000, phases: { [FIELD_UPLOAD_PHASE]: 27 } };
  assert.equal(followsWithin({ ...c, stats: whole }), FOLLOW_MS / 2);
  assert.equal(followsWithin({ ...c, followMs: 2000, stats: whole }), 1000);
  assert.equal(followsWithin({ ...c, stats: { ...whole, phases: { [FIELD_UPLOAD_PHASE]: 204 } } }), 0);
  assert.equal(followsWithin({ ...c, stats: { ...whole, phases: {} } }), 0);
  assert.equal(followsWithin({ ...c, isPreviewField: () => true }), 0); // a big model's preview: its exact one follows
  assert.equal(followsWithin({ ...c, stats: { ...c.stats, preview: true } }), 0); // a quick edit's preview
  assert.equal(followsWithin({ ...c, runsQueued: 1 }), 0); // behind: this change is a quick edit
  assert.equal(followsWithin({ ...c, settleTimer: 1 }), 0);
  assert.equal(followsWithin({ ...c, getFieldVersion: () => 4 }), 0); // no new field: no run
  assert.equal(followsWithin({ ...c, options: { autoUpdate: false } }), 0);
  assert.equal(followsWithin({ ...c, active: false }), 0);
});

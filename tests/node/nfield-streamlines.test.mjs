// Streamlines and glyphs of N-fields against fields whose integral lines are known in closed form: a constant
// line or cross field (straight lines along its directions) and a circular line field (circles about the
// centre), each with its representatives scrambled per vertex and per face by random rotations of 2πk/N, which
// naive interpolation would turn into noise.
import assert from 'node:assert/strict';
import test from 'node:test';
import { PerspectiveCamera, Scene, Vector3 } from 'three';
import { grid, scrambledField, surfaceOf } from './fakes.mjs';
import { randomSequence } from '../../web/geometry/arrow-sampling.js';
import { traceStreamlines } from '../../web/geometry/streamlines.js';
import { ArrowsView } from '../../web/views/arrows-view.js';

const TWO_PI = 2 * Math.PI;


const pointsOf = (l) => Array.from({ length: l.length / 3 }, (_, k) => [l[3 * k], l[3 * k + 1], l[3 * k + 2]]);
const lengthOf = (pts) => pts.slice(1).reduce((sum, p, k) => sum + Math.hypot(p[0] - pts[k][0], p[1] - pts[k][1]), 0);

// The line's direction (unoriented, in [0, π)) if all its points lie within tol of the chord, else null.
function straightDirection(pts, tol) {
  const a = pts[0], b = pts[pts.length - 1], d = [b[0] - a[0], b[1] - a[1]], l = Math.hypot(...d);
  if (!(l > 0)) return null;
  const off = Math.max(...pts.map((p) => Math.abs((p[0] - a[0]) * d[1] - (p[1] - a[1]) * d[0]) / l));
  return off < tol ? ((Math.atan2(d[1], d[0]) % Math.PI) + Math.PI) % Math.PI : null;
}

const angleGap = (a, b, period) => Math.abs(((((a - b) % period) + 1.5 * period) % period) - period / 2);

test('streamlines of a constant line field with scrambled signs: straight, along it, spaced, wall to wall', () => {
  const m = grid(20, 1), s = surfaceOf(m), spacing = 0.08, theta = 0.3;
  for (const faces of [true, false]) {
    const { V, F } = scrambledField(s, 2, () => theta, randomSequence(faces ? 11 : 12));
    const lines = traceStreamlines(s, V, { spacing, symmetry: 2, faceVectors: faces ? F : null });
    assert.ok(lines.length >= 8, `${lines.length} lines`);
    let total = 0;
    for (const l of lines) {
      const pts = pointsOf(l), dir = straightDirection(pts, 1e-6);
      assert.ok(dir !== null, 'straight');
      assert.ok(angleGap(dir, theta, Math.PI) < 1e-6, `along the field: ${dir}`);
      total += lengthOf(pts);
    }
    // Lines spaced d_sep apart over the unit square: about 1/d_sep of them, each about as long as the square.
    assert.ok(total > 0.6 / spacing && total < 1.6 / spacing, `total length ${total} for spacing ${spacing}`);
  }
});

test('streamlines of a constant cross field: two families, each straight along one of its directions', () => {
  const m = grid(20, 1), s = surfaceOf(m), spacing = 0.1, theta = -0.5;
  const { V, F } = scrambledField(s, 4, () => theta, randomSequence(4));
  const lines = traceStreamlines(s, V, { spacing, symmetry: 4, faceVectors: F });
  const family = [0, 0];
  for (const l of lines) {
    const dir = straightDirection(pointsOf(l), 1e-6);
    assert.ok(dir !== null, 'straight');
    const k = [0, 1].find((j) => angleGap(dir, theta + (j * Math.PI) / 2, Math.PI) < 1e-6);
    assert.ok(k !== undefined, `along one of the two directions: ${dir}`);
    family[k]++;
  }
  // Lines of the two families cross each other freely: each family fills the square on its own.
  assert.ok(family[0] >= 6 && family[1] >= 6, `families ${family}`);
});

test('streamlines of a constant 3-field: rays along its three directions', () => {
  const s = surfaceOf(grid(16, 1)), theta = 0.2;
  const { V, F } = scrambledField(s, 3, () => theta, randomSequence(9));
  const lines = traceStreamlines(s, V, { spacing: 0.1, symmetry: 3, faceVectors: F });
  const seen = new Set();
  for (const l of lines) {
    const dir = straightDirection(pointsOf(l), 1e-6);
    assert.ok(dir !== null, 'straight');
    const k = [0, 1, 2].find((j) => angleGap(dir, theta + (j * TWO_PI) / 3, Math.PI) < 1e-6);
    assert.ok(k !== undefined, `along a direction of the field: ${dir}`);
    seen.add(k);
  }
  assert.equal(seen.size, 3);
});

test('streamlines of a circular line field with scrambled signs are circles about its centre, spaced', () => {
  const m = grid(40, 2, -1), s = surfaceOf(m), spacing = 0.15;
  const { V, F } = scrambledField(s, 2, (x, y) => Math.atan2(y, x) + Math.PI / 2, randomSequence(21));
  const lines = traceStreamlines(s, V, { spacing, symmetry: 2, faceVectors: F });
  const closed = [];
  for (const l of lines) {
    const pts = pointsOf(l), r = pts.map(([x, y]) => Math.hypot(x, y));
    const mean = r.reduce((a, b) => a + b) / r.length;
    if (mean < spacing) continue; // the last, tiny loop round the centre: a few steps per turn
    for (const x of r) assert.ok(Math.abs(x - mean) < 0.01 * mean, `radius ${x} on a circle of ${mean}`);
    // Inside the square the circle closes on itself.
    if (mean < 1 - spacing) {
      assert.ok(Math.hypot(pts[0][0] - pts.at(-1)[0], pts[0][1] - pts.at(-1)[1]) <= spacing, 'a full circle');
      closed.push(mean);
    }
  }
  closed.sort((a, b) => a - b);
  assert.ok(closed.length >= 5, `${closed.length} circles`);
  for (let k = 1; k < closed.length; k++) {
    const gap = closed[k] - closed[k - 1];
    assert.ok(gap >= 0.9 * spacing && gap <= 1.1 * spacing, `circles ${gap} apart`);
  }
});

test('streamlines of a circular cross field: circles and rays, away from its centre', () => {
  const s = surfaceOf(grid(20, 2, -1)), spacing = 0.1;
  const { V, F } = scrambledField(s, 4, (x, y) => Math.atan2(y, x), randomSequence(8));
  const lines = traceStreamlines(s, V, { spacing, symmetry: 4, faceVectors: F });
  const kinds = { circle: 0, ray: 0 };
  for (const l of lines) {
    const pts = pointsOf(l), r = pts.map(([x, y]) => Math.hypot(x, y));
    if (Math.min(...r) < spacing) continue; // at the singularity itself the directions are undefined
    // Linear interpolation of the corners bends the radial family a little between vertices.
    const dir = straightDirection(pts, 0.01);
    const a = Math.atan2(pts[0][1], pts[0][0]);
    if (dir !== null && angleGap(dir, a, Math.PI) < 0.05) kinds.ray++;
    else {
      assert.ok(Math.max(...r) - Math.min(...r) < 0.03, `neither a ray nor a circle: r ${Math.min(...r)}…${Math.max(...r)}`);
      kinds.circle++;
    }
  }
  assert.ok(kinds.circle >= 4 && kinds.ray >= 4, JSON.stringify(kinds));
});

test('streamlines: symmetry 1, absent or invalid traces the vector field as before', () => {
  const s = surfaceOf(grid(10, 1));
  const V = new Float64Array(3 * s.nV);
  for (let v = 0; v < s.nV; v++) V.set([1, 0.3 * s.vertex(v)[1], 0], 3 * v);
  const plain = traceStreamlines(s, V, { spacing: 0.1 });
  assert.deepEqual(traceStreamlines(s, V, { spacing: 0.1, symmetry: 1 }), plain);
  assert.deepEqual(traceStreamlines(s, V, { spacing: 0.1, symmetry: 9 }), plain);
});

// The arrows view in node (three.js needs no GL until it renders): the glyphs' first spokes.
function drawnGlyphs(s, F, V, N) {
  const view = new ArrowsView(new Scene());
  view.setSurface(s);
  view.setField(F, V, null, N);
  const camera = new PerspectiveCamera(40, 1, 0.01, 100);
  camera.position.set(0.5, 0.5, 2);
  camera.lookAt(0.5, 0.5, 0);
  camera.updateMatrixWorld();
  view.updateView(camera, new Vector3(0.5, 0.5, 0), 720);
  return { view, ...view.drawn() };
}

test('glyphs of a scrambled constant line or cross field: every glyph along the field, none shortened', () => {
  const s = surfaceOf(grid(12, 1)), theta = 0.7;
  for (const N of [2, 4]) {
    const { V, F } = scrambledField(s, N, () => theta, randomSequence(30 + N));
    const { view, vectors } = drawnGlyphs(s, F, V, N);
    const n = vectors.length / 3;
    assert.ok(n > 50, `${n} glyphs`);
    assert.equal(view.mesh.geometry.getAttribute('position').count, 6 * N, `${N} spokes`);
    const lengths = [];
    for (let i = 0; i < n; i++) {
      const [x, y, z] = vectors.subarray(3 * i, 3 * i + 3);
      lengths.push(Math.hypot(x, y, z));
      assert.ok(Math.abs(z) < 1e-6);
      assert.ok(angleGap(Math.atan2(y, x), theta, TWO_PI / N) < 1e-5, `glyph ${i}: ${Math.atan2(y, x)}`);
    }
    // The matched corners agree, so their mean keeps full length: all glyphs equally long.
    assert.ok(Math.max(...lengths) - Math.min(...lengths) < 1e-6 * Math.max(...lengths));
    // Back to a vector field: the arrow again.
    view.setField(F, V, null, 1);
    assert.equal(view.mesh.geometry.getAttribute('position').count, 9, 'the arrow: shaft and head');
  }
});

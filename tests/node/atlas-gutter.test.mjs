// The atlas's gutter quads (web/synthesis/atlas-gutter.js) against a hand-made atlas: which edges get one, that they
// lie outside their face and cover the ring the gutter asks for, and what each vertex carries.
import { test } from 'node:test';
import assert from 'node:assert/strict';
import { cornerData, FRAME_FLOATS } from '../../web/synthesis/atlas-corners.js';
import { gutterQuads, gutterReach } from '../../web/synthesis/atlas-gutter.js';
import { halfEdgeNeighbours } from '../../web/geometry/mesh-geometry.js';

// A unit square in the plane z = 0 as two triangles sharing the diagonal 0-2, laid out at `R` texels: `seam`
// false puts both faces in one chart (the square at [0.25, 0.75]^2); true moves the second face to the atlas's
// other half, so the diagonal becomes a seam.
function square(seam, R = 64) {
  const positions = new Float64Array([0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0]);
  const triangles = new Int32Array([0, 1, 2, 0, 2, 3]);
  const at = (x, y, dx = 0) => [0.25 + 0.5 * x * 0.5 + dx, 0.25 + 0.5 * y];
  const dx = seam ? 0.4 : 0;
  const uvs = [at(0, 0), at(1, 0), at(1, 1), at(0, 0, dx), at(1, 1, dx), at(0, 1, dx)];
  const cornerUVs = new Float32Array(uvs.flat());
  const corners = cornerData(positions, triangles, cornerUVs);
  return { positions, triangles, cornerUVs, corners, resolution: R, neighbour: halfEdgeNeighbours(triangles, 4) };
}

const edges = (q) => q.indices.length / 6;

const inTriangle = (p, a, b, c) => {
  const s = (u, v, w) => (v[0] - u[0]) * (w[1] - u[1]) - (w[0] - u[0]) * (v[1] - u[1]);
  const d1 = s(a, b, p), d2 = s(b, c, p), d3 = s(c, a, p);
  return (d1 >= 0 && d2 >= 0 && d3 >= 0) || (d1 <= 0 && d2 <= 0 && d3 <= 0);
};

// The quads as triangles of UV points.
function quadTriangles(q) {
  const uv = (i) => [q.uv[2 * i], q.uv[2 * i + 1]];
  const out = [];
  for (let t = 0; t < q.indices.length; t += 3) out.push([0, 1, 2].map((k) => uv(q.indices[t + k])));
  return out;
}

// Distance from p to segment ab.
function segmentDistance(p, a, b) {
  const dx = b[0] - a[0], dy = b[1] - a[1];
  const t = Math.max(0, Math.min(1, ((p[0] - a[0]) * dx + (p[1] - a[1]) * dy) / (dx * dx + dy * dy)));
  return Math.hypot(p[0] - a[0] - t * dx, p[1] - a[1] - t * dy);
}

test('one chart: a quad on each of its four outer edges, none on the shared diagonal', () => {
  const mesh = square(false);
  const q = gutterQuads({ ...mesh, gutter: 2 });
  assert.equal(edges(q), 4);
  assert.equal(q.source.length, 16);
});

test('a seam along the diagonal adds a quad on each side of it', () => {
  const q = gutterQuads({ ...square(true), gutter: 2 });
  assert.equal(edges(q), 6);
});

test('no gutter, no quads; the reach stays inside the border a chart owns', () => {
  assert.equal(edges(gutterQuads({ ...square(true), gutter: 0 })), 0);
  assert.equal(gutterReach(0), 0);
  assert.equal(gutterReach(1), 1);
  assert.equal(gutterReach(2), 1.5);
  assert.equal(gutterReach(8), 1.5);
});

test('the quads lie outside the chart and cover every texel centre within the reach of its edge', () => {
  const mesh = square(false), R = mesh.resolution;
  const q = gutterQuads({ ...mesh, gutter: 2 });
  const tris = quadTriangles(q);
  const reach = gutterReach(2) / R;
  const [a, b, c, d] = [[0.25, 0.25], [0.5, 0.25], [0.5, 0.75], [0.25, 0.75]]; // the chart (a rectangle)
  const sides = [[a, b], [b, c], [c, d], [d, a]];
  let ring = 0;
  for (let y = 0; y < R; y++)
    for (let x = 0; x < R; x++) {
      const p = [(x + 0.5) / R, (y + 0.5) / R];
      const inside = p[0] > a[0] && p[0] < b[0] && p[1] > a[1] && p[1] < d[1];
      const dist = Math.min(...sides.map(([u, v]) => segmentDistance(p, u, v)));
      const covered = tris.some(([u, v, w]) => inTriangle(p, u, v, w));
      if (inside) continue;
      if (dist < reach - 1e-9) {
        ring++;
        assert.ok(covered, `texel (${x}, ${y}) ${dist * R} texels from the chart is in no quad`);
      }
      // The square ends reach diagonally √2 times as far, and no further.
      if (covered) assert.ok(dist <= Math.SQRT2 * reach + 1e-9, `texel (${x}, ${y}) is ${dist * R} texels out`);
    }
  assert.ok(ring > 4 * 16, `the ring has ${ring} texel centres`);
});

test('each vertex names the corner whose field it takes, one of its edge\'s, beside it', () => {
  const mesh = square(true);
  const q = gutterQuads({ ...mesh, gutter: 2 });
  for (let e = 0; e < q.source.length / 4; e++) {
    // A quad's four vertices take their field from its edge's two corners, of one face.
    const cs = new Set(Array.from(q.source.subarray(4 * e, 4 * e + 4)));
    assert.equal(cs.size, 2);
    assert.equal(new Set([...cs].map((c) => Math.floor(c / 3))).size, 1);
  }
  for (let i = 0; i < q.source.length; i++) {
    const c = q.source[i];
    assert.ok(c >= 0 && c < 6);
    // The vertex is within the reach (diagonally) of its corner's UV.
    const du = q.uv[2 * i] - mesh.cornerUVs[2 * c], dv = q.uv[2 * i + 1] - mesh.cornerUVs[2 * c + 1];
    assert.ok(Math.hypot(du, dv) * mesh.resolution <= Math.SQRT2 * 1.5 + 1e-4); // UVs in float32
  }
});

test('faces degenerate in UV make no quads, and their neighbours\' edges towards them get one', () => {
  const mesh = square(false);
  const uv = mesh.cornerUVs.slice();
  uv.set([0.25, 0.25, 0.25, 0.25, 0.25, 0.25], 6); // the second face collapsed to a point
  const corners = cornerData(mesh.positions, mesh.triangles, uv);
  assert.equal(corners.used, 1);
  const q = gutterQuads({ ...mesh, cornerUVs: uv, corners, gutter: 2 });
  assert.equal(edges(q), 3);
});

test('a face\'s frame maps its UV edges onto its 3D edges; a degenerate face keeps zeros', () => {
  const mesh = square(true);
  const { uv, frames } = mesh.corners;
  const P = (v) => Array.from(mesh.positions.subarray(3 * v, 3 * v + 3));
  for (let f = 0; f < 2; f++) {
    const G = (j, k) => frames[FRAME_FLOATS * f + 4 * j + k];
    const [a, b, c] = Array.from(mesh.triangles.subarray(3 * f, 3 * f + 3)).map(P);
    for (const [to, k1] of [[b, 1], [c, 2]]) {
      const du = uv[6 * f + 2 * k1] - uv[6 * f], dv = uv[6 * f + 2 * k1 + 1] - uv[6 * f + 1];
      for (let k = 0; k < 3; k++) assert.ok(Math.abs(G(0, k) * du + G(1, k) * dv - (to[k] - a[k])) < 1e-5);
    }
    assert.deepEqual([G(2, 0), G(2, 1), G(2, 2)], [0, 0, 1]);
  }
  const flat = mesh.cornerUVs.slice();
  flat.set([0.3, 0.3, 0.3, 0.3, 0.3, 0.3], 0);
  const c = cornerData(mesh.positions, mesh.triangles, flat);
  assert.ok(c.uv.subarray(0, 6).every((x) => x === 0) && c.frames.subarray(0, FRAME_FLOATS).every((x) => x === 0));
  assert.ok(c.frames.subarray(FRAME_FLOATS).some((x) => x !== 0));
});

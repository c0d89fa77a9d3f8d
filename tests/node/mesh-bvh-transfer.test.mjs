// The BVH the worker builds and the page adopts (web/geometry/mesh-bvh-transfer.js): after a structured clone
// with transfer (what postMessage does), the adopted tree must answer raycasts and closest-point queries as a
// tree built on the page would, and as brute force over the core's faces does: same faceIndex (the core's
// face, i.e. indirect mode really kept the order) and the same point.
import assert from 'node:assert/strict';
import test from 'node:test';
import { Worker } from 'node:worker_threads';
import { BufferAttribute, BufferGeometry, DoubleSide, Mesh, MeshBasicMaterial, Raycaster, Triangle, Vector3 } from 'three';
import { MeshBVH, acceleratedRaycast } from 'three-mesh-bvh';
import { icosphere } from './fakes.mjs';
import {
  SERIALIZED_MESH_BVH_VERSION,
  adoptBVH,
  buildSerializedBVH,
  float32Arrays,
  pageSurface,
  pickingParts,
  transferList,
} from '../../web/geometry/mesh-bvh-transfer.js';
import { Surface } from '../../web/geometry/surface.js';

// Deterministic (mulberry32), so a failure reproduces.
function random(seed) {
  return () => {
    seed = (seed + 0x6d2b79f5) | 0;
    let t = Math.imul(seed ^ (seed >>> 15), 1 | seed);
    t = (t + Math.imul(t ^ (t >>> 7), 61 | t)) ^ t;
    return ((t ^ (t >>> 14)) >>> 0) / 4294967296;
  };
}

// An icosphere (5,120 faces) with its vertices pushed in and out: a bumpy closed surface whose rays can hit
// it up to four times and whose faces are not all alike, so a reordered face list would show.
function bumpySphere() {
  const m = icosphere(4);
  const rnd = random(7);
  for (let v = 0; v < m.positions.length / 3; v++) {
    const s = 1 + 0.15 * (rnd() - 0.5);
    for (let k = 0; k < 3; k++) m.positions[3 * v + k] *= s;
  }
  return m;
}

// Rays from a sphere of radius 3 towards random points of the ball of radius 1.3: most hit, some miss.
function rays(count, seed) {
  const rnd = random(seed);
  const onSphere = (r) => {
    const z = 2 * rnd() - 1, a = 2 * Math.PI * rnd(), s = Math.sqrt(1 - z * z);
    return new Vector3(r * s * Math.cos(a), r * s * Math.sin(a), r * z);
  };
  return Array.from({ length: count }, () => {
    const origin = onSphere(3);
    const target = onSphere(1.3 * Math.cbrt(rnd()));
    return { origin, direction: target.sub(origin).normalize() };
  });
}

// What postMessage(obj, transferList(obj)) delivers: a structured clone, with the sender's buffers detached.
function sendToPage(...objects) {
  const list = transferList(...objects);
  const copy = structuredClone(objects, { transfer: list });
  return { copy, list };
}

function meshOf(geometry, accelerated) {
  const mesh = new Mesh(geometry, new MeshBasicMaterial({ side: DoubleSide })); // the viewer's side
  if (accelerated) mesh.raycast = acceleratedRaycast;
  return mesh;
}

function castAll(mesh, rayList, firstHitOnly) {
  const raycaster = new Raycaster();
  raycaster.firstHitOnly = firstHitOnly;
  return rayList.map(({ origin, direction }) => {
    raycaster.set(origin, direction);
    return raycaster.intersectObject(mesh, false).map((h) => ({ face: h.faceIndex, point: h.point }));
  });
}

function assertSameHits(actual, expected, what) {
  assert.equal(actual.length, expected.length);
  for (let i = 0; i < expected.length; i++) {
    assert.equal(actual[i].length, expected[i].length, `${what}, ray ${i}: number of hits`);
    for (let j = 0; j < expected[i].length; j++) {
      assert.equal(actual[i][j].face, expected[i][j].face, `${what}, ray ${i}, hit ${j}: face`);
      assert.ok(actual[i][j].point.distanceTo(expected[i][j].point) < 1e-6, `${what}, ray ${i}, hit ${j}: point`);
    }
  }
}

test('an adopted BVH hits what a fresh indirect BVH and brute force hit, on the core\'s faces', () => {
  const m = bumpySphere();
  const nF = m.triangles.length / 3;
  const built = buildSerializedBVH(m.positions, m.triangles);
  assert.equal(built.format, SERIALIZED_MESH_BVH_VERSION);
  assert.equal(built.faces, nF);
  assert.ok(built.indirectBuffer && built.indirectBuffer.length === nF, 'indirect mode');
  // Indirect mode leaves the index in the core's order.
  assert.deepEqual(Array.from(built.index), Array.from(m.triangles));

  const { copy: [bvh], list } = sendToPage(built);
  assert.equal(built.positions.byteLength, 0, 'positions were transferred, not copied');
  assert.equal(built.index.byteLength, 0, 'index was transferred, not copied');
  assert.equal(new Set(list).size, list.length);

  // The page: a fresh geometry with the transferred arrays, as viewer.setMesh makes it.
  const page = new BufferGeometry();
  page.setAttribute('position', new BufferAttribute(bvh.positions, 3));
  page.setIndex(new BufferAttribute(bvh.index, 1));
  const tree = adoptBVH(page, bvh);
  assert.equal(page.boundsTree, tree);
  assert.ok(tree.indirect);
  assert.equal(page.index.array, bvh.index, 'the index the tree expects, not a copy');
  assert.equal(page.getAttribute('position').array, bvh.positions);

  // Reference 1: a tree built here, the way the viewer builds it without a worker.
  const fresh = new BufferGeometry();
  fresh.setAttribute('position', new BufferAttribute(new Float32Array(m.positions), 3));
  fresh.setIndex(new BufferAttribute(new Uint32Array(m.triangles), 1));
  fresh.computeBoundingSphere();
  fresh.boundsTree = new MeshBVH(fresh, { indirect: true });
  // Reference 2: three's own per-triangle raycast, with no tree at all.
  const brute = new BufferGeometry();
  brute.setAttribute('position', new BufferAttribute(new Float32Array(m.positions), 3));
  brute.setIndex(new BufferAttribute(new Uint32Array(m.triangles), 1));
  brute.computeBoundingSphere();

  const rayList = rays(200, 11);
  const adopted = castAll(meshOf(page, true), rayList, true);
  const hits = adopted.filter((h) => h.length).length;
  assert.ok(hits > 120 && hits < 200, `${hits} of 200 rays hit: both hits and misses are tested`);
  assertSameHits(adopted, castAll(meshOf(fresh, true), rayList, true), 'first hit vs fresh BVH');
  const bruteAll = castAll(meshOf(brute, false), rayList, false);
  assertSameHits(adopted, bruteAll.map((h) => h.slice(0, 1)), 'first hit vs brute force');
  // Every hit along the ray, not only the first: the whole tree is right, not only the near side.
  assertSameHits(castAll(meshOf(page, true), rayList, false), bruteAll, 'all hits vs brute force');

  // The bounding volumes a fresh build leaves (the camera frames the model on the sphere).
  assert.ok(page.boundingBox.equals(fresh.boundingBox));
  assert.ok(page.boundingSphere.center.distanceTo(fresh.boundingSphere.center) < 1e-7);
  assert.ok(Math.abs(page.boundingSphere.radius - fresh.boundingSphere.radius) < 1e-7);

  // closestPointToPoint (the viewer's normal lookups) agrees too.
  const rnd = random(5);
  for (let i = 0; i < 50; i++) {
    const p = new Vector3(rnd() - 0.5, rnd() - 0.5, rnd() - 0.5).multiplyScalar(3);
    const a = page.boundsTree.closestPointToPoint(p), b = fresh.boundsTree.closestPointToPoint(p);
    assert.ok(Math.abs(a.distance - b.distance) < 1e-6);
    assert.ok(a.point.distanceTo(b.point) < 1e-6);
  }
});

test('adoptBVH on a geometry with no attributes yet gives it the BVH\'s positions and index', () => {
  const m = bumpySphere();
  const { copy: [bvh] } = sendToPage(buildSerializedBVH(m.positions, m.triangles));
  const geometry = new BufferGeometry();
  adoptBVH(geometry, bvh);
  assert.equal(geometry.getAttribute('position').array, bvh.positions);
  assert.equal(geometry.index.array, bvh.index);
  const hits = castAll(meshOf(geometry, true), rays(20, 3), true).filter((h) => h.length);
  assert.ok(hits.length > 0);
});

test('adoptBVH replaces, not overwrites, a different index, and refuses a geometry of another size', () => {
  const m = bumpySphere();
  const { copy: [bvh] } = sendToPage(buildSerializedBVH(m.positions, m.triangles));
  const own = new Uint32Array(m.triangles.length); // zeros: overwriting it in place would hide a mismatch
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(bvh.positions, 3));
  geometry.setIndex(new BufferAttribute(own, 1));
  adoptBVH(geometry, bvh);
  assert.equal(geometry.index.array, bvh.index);
  assert.ok(own.every((x) => x === 0));

  const small = new BufferGeometry();
  small.setAttribute('position', new BufferAttribute(new Float32Array(9), 3));
  assert.throws(() => adoptBVH(small, bvh), /vertices/);
  assert.throws(() => adoptBVH(new BufferGeometry(), { ...bvh, format: 0 }), /version/);
});

test('float32Arrays shares the BVH\'s buffers, and transferList lists each buffer once', () => {
  const m = bumpySphere();
  // Stand-in vertex normals (any Float64Array, 3 per vertex): +z everywhere.
  const normals = new Float64Array(m.positions.length).map((_, i) => (i % 3 === 2 ? 1 : 0));
  const bvh = buildSerializedBVH(m.positions, m.triangles);
  const float32 = float32Arrays(normals, bvh);
  assert.equal(float32.positions, bvh.positions);
  assert.equal(float32.index, bvh.index);
  assert.ok(float32.normals instanceof Float32Array && float32.normals[2] === 1);
  assert.ok(float32.colors.length === m.positions.length && float32.colors instanceof Uint8Array && float32.colors.every((c) => c === 255));
  // A buffer listed twice makes postMessage (and structuredClone) throw; sharing must not.
  const { copy: [b, f] } = sendToPage(bvh, float32);
  assert.equal(f.positions, b.positions, 'one array on the page too, not two copies');
  assert.equal(f.index, b.index);

  const alone = float32Arrays(normals, null, m.positions, m.triangles);
  assert.deepEqual(Array.from(alone.index), Array.from(m.triangles));
  assert.equal(alone.positions[4], Math.fround(m.positions[4]));
});

test('built in a worker thread and posted with its transfer list, the BVH works on this thread', async () => {
  const m = bumpySphere();
  const normals = new Float64Array(m.positions.length).fill(0.5);
  const worker = new Worker(new URL('./mesh-bvh-worker.mjs', import.meta.url), {
    workerData: { positions: m.positions, triangles: m.triangles, normals },
  });
  const { bvh, float32 } = await new Promise((resolve, reject) => {
    worker.once('message', resolve);
    worker.once('error', reject);
  });
  await worker.terminate();
  assert.equal(float32.positions, bvh.positions);
  const geometry = new BufferGeometry();
  geometry.setAttribute('position', new BufferAttribute(float32.positions, 3));
  geometry.setIndex(new BufferAttribute(float32.index, 1));
  adoptBVH(geometry, bvh);
  const brute = new BufferGeometry();
  brute.setAttribute('position', new BufferAttribute(new Float32Array(m.positions), 3));
  brute.setIndex(new BufferAttribute(new Uint32Array(m.triangles), 1));
  brute.computeBoundingSphere();
  const rayList = rays(100, 23);
  const expected = castAll(meshOf(brute, false), rayList, false).map((h) => h.slice(0, 1));
  assertSameHits(castAll(meshOf(geometry, true), rayList, true), expected, 'worker-built vs brute force');
});

// A big model's surface goes in two messages (core-worker.js loadMesh): drawable first, then the adjacency and
// the BVH (pickingParts), which the page adopts onto the geometry it already draws, without sending positions
// or index again. The adopted tree must hit what brute force hits, and the adjacency be what a Surface builds.
test('a surface sent without picking, then its picking parts: the same adjacency, and a tree that hits right', () => {
  const m = bumpySphere();
  const { arrays, list } = pageSurface(new Surface(m.positions.slice(), m.triangles.slice(), m.edges.slice()), true, { picking: false });
  assert.equal(arrays.bvh, undefined);
  assert.equal(arrays.neighbour, undefined, 'no adjacency in the first message');
  assert.equal(arrays.normals, undefined, 'nor face normals');
  assert.ok(arrays.pickingFollows);
  const { copy: [sent] } = sendToPage(arrays);
  assert.equal(new Set(list).size, list.length);
  const surface = Surface.fromArrays(sent);

  const reference = new Surface(m.positions, m.triangles, m.edges);
  for (let f = 0; f < surface.nF; f++) {
    // The reference: three's own face normal of the face's corners.
    const [p, q, r] = [0, 1, 2].map((k) => new Vector3().fromArray(m.positions, 3 * m.triangles[3 * f + k]));
    const b = new Triangle(p, q, r).getNormal(new Vector3()).toArray();
    const a = surface.normal(f);
    assert.ok(Math.hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]) < 1e-12, `face ${f}'s normal, made when asked`);
  }

  const parts = pickingParts(m.positions, m.triangles);
  assert.equal(parts.value.bvh.positions, null, 'positions are not sent twice');
  assert.equal(parts.value.bvh.index, null, 'nor the index');
  const { copy: [picking] } = sendToPage(parts.value);
  surface.adoptPicking(picking);
  assert.equal(surface.pickingFollows, false);
  for (const key of Surface.PICKING) assert.deepEqual(Array.from(surface[key]), Array.from(reference[key]), key);

  // The page's geometry, drawn from the first message's arrays; the tree adopted onto it later.
  const page = new BufferGeometry();
  page.setAttribute('position', new BufferAttribute(sent.float32.positions, 3));
  page.setIndex(new BufferAttribute(sent.float32.index, 1));
  const index = page.index;
  adoptBVH(page, surface.bvh);
  assert.equal(page.index, index, 'the index drawn from is kept (no second upload)');
  const brute = new BufferGeometry();
  brute.setAttribute('position', new BufferAttribute(new Float32Array(m.positions), 3));
  brute.setIndex(new BufferAttribute(new Uint32Array(m.triangles), 1));
  brute.computeBoundingSphere();
  const [x, y, z, r] = sent.float32.boundingSphere;
  assert.ok(brute.boundingSphere.center.distanceTo(new Vector3(x, y, z)) < 1e-7 && Math.abs(brute.boundingSphere.radius - r) < 1e-7);
  const rayList = rays(200, 13);
  assertSameHits(castAll(meshOf(page, true), rayList, false), castAll(meshOf(brute, false), rayList, false), 'all hits vs brute force');
  assert.throws(() => adoptBVH(new BufferGeometry(), surface.bvh), /counts/, 'without positions and index the geometry must have its own');
});

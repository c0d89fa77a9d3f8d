// The quad layer's pure parts (web/quad/quad-mesh.js, quad-files.js) on quad meshes made here (quad-fixtures.mjs):
// edges, valences, normals, the triangulation (the shorter diagonal, the orientation and the area kept), the
// remesh target's checks, the OBJ read back literally (every coordinate the same double, every polygon the same
// corners) and the GLB taken apart chunk by chunk (header, chunk lengths and padding, accessor counts and bounds
// against the mesh), passed by the Khronos glTF-Validator with 0 errors, and loaded by three.js's GLTFLoader.
import assert from 'node:assert/strict';
import test from 'node:test';
import validator from 'gltf-validator';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { quadGlb, quadObj } from '../../web/quad/quad-files.js';
import {
  meanEdgeLength, remeshTarget, triangulate, uniqueEdges, valences, vertexNormals,
} from '../../web/quad/quad-mesh.js';
import { statsLines } from '../../web/quad/panel.js';
import { cubeQuads, mixedPolygons, parseObj } from './quad-fixtures.mjs';

const point = (p, v) => [p[3 * v], p[3 * v + 1], p[3 * v + 2]];
const sub = (a, b) => a.map((x, k) => x - b[k]);
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const triangleNormal = (p, a, b, c) => cross(sub(point(p, b), point(p, a)), sub(point(p, c), point(p, a)));

test('edges and valences: the cube of 6 × 3² quads, closed, genus 0, with eight valence-3 corners', () => {
  const mesh = cubeQuads(3);
  const nV = mesh.positions.length / 3, nF = mesh.faceStart.length - 1, edges = uniqueEdges(mesh);
  assert.equal(nV, 6 * 9 + 2);
  assert.equal(nF, 54);
  assert.equal(edges.length / 2, 2 * nF, 'each quad has four edges, each shared by two quads');
  assert.equal(nV - edges.length / 2 + nF, 2, 'Euler characteristic');
  for (let k = 0; k < edges.length; k += 2) assert.ok(edges[k] < edges[k + 1]);
  assert.equal(new Set(Array.from({ length: edges.length / 2 }, (_, k) => `${edges[2 * k]},${edges[2 * k + 1]}`)).size,
    edges.length / 2, 'no edge twice');
  const valence = valences(mesh);
  const irregular = [...valence.keys()].filter((v) => valence[v] !== 4);
  assert.deepEqual(irregular, Array.from(mesh.irregular));
  assert.ok(irregular.every((v) => valence[v] === 3));
  assert.ok(Math.abs(meanEdgeLength(mesh) - 2 / 3) < 1e-12);
});

test('vertex normals point out of the cube and the sphere, unit length', () => {
  for (const mesh of [cubeQuads(4), cubeQuads(5, { sphere: true })]) {
    const n = vertexNormals(mesh), p = mesh.positions;
    for (let v = 0; v < p.length / 3; v++) {
      assert.ok(Math.abs(Math.hypot(...point(n, v)) - 1) < 1e-12);
      assert.ok(dot(point(n, v), point(p, v)) > 0.5 * Math.hypot(...point(p, v)), `vertex ${v} points out`);
    }
  }
});

test('the triangulation splits each quad along its shorter diagonal, keeping orientation and area', () => {
  const mesh = cubeQuads(6, { sphere: true });
  const tris = triangulate(mesh), p = mesh.positions;
  const nF = mesh.faceStart.length - 1;
  assert.equal(tris.length, 6 * nF);
  for (let f = 0; f < nF; f++) {
    const [a, b, c, d] = mesh.faceVertices.subarray(4 * f, 4 * f + 4);
    const t = tris.subarray(6 * f, 6 * f + 6);
    const corners = new Set(t);
    assert.deepEqual([...corners].sort((x, y) => x - y), [a, b, c, d].sort((x, y) => x - y));
    // The diagonal both triangles share is the quad's shorter one.
    const shared = [...corners].filter((v) => t.subarray(0, 3).includes(v) && t.subarray(3).includes(v));
    const length = (u, w) => Math.hypot(...sub(point(p, u), point(p, w)));
    assert.equal(length(...shared), Math.min(length(a, c), length(b, d)));
    const quadNormal = cross(sub(point(p, c), point(p, a)), sub(point(p, d), point(p, b)));
    for (let k = 0; k < 6; k += 3) assert.ok(dot(triangleNormal(p, t[k], t[k + 1], t[k + 2]), quadNormal) > 0);
  }
  // Polygons that are not quads are fanned: the planar mesh's area is the sum of its triangles'.
  const mixed = mixedPolygons(), fan = triangulate(mixed);
  assert.equal(fan.length / 3, 3 + 2 + 1 + 1);
  let area = 0;
  for (let k = 0; k < fan.length; k += 3) {
    const z = triangleNormal(mixed.positions, fan[k], fan[k + 1], fan[k + 2])[2];
    assert.ok(z > 0, 'counter-clockwise from +z, as the polygons');
    area += z / 2;
  }
  assert.ok(Math.abs(area - (2 + 1 + 0.5 * 0.6 * 1 + 0.5 * 1 * 1)) < 1e-12, `area ${area}`);
});

test('the remesh target: exactly one of edgeLength and quads, each checked by name', () => {
  assert.deepEqual(remeshTarget({ quads: 5000 }), { quads: 5000 });
  assert.deepEqual(remeshTarget({ edgeLength: 0.02 }), { edgeLength: 0.02 });
  assert.throws(() => remeshTarget({}), /remesh: give either edgeLength or quads/);
  assert.throws(() => remeshTarget({ quads: 10, edgeLength: 1 }), /give either/);
  assert.throws(() => remeshTarget({ quads: 2.5 }), /quads must be a whole number/);
  assert.throws(() => remeshTarget({ quads: 0 }), /quads must be a whole number/);
  assert.throws(() => remeshTarget({ edgeLength: -1 }), /edgeLength must be a positive length/);
  assert.throws(() => remeshTarget({ edgeLength: Infinity }), /edgeLength must be a positive length/);
  assert.throws(() => remeshTarget({ size: 3 }), /unknown option size/);
  assert.throws(() => remeshTarget(null, 'setTarget'), /^Error: setTarget: options must be an object/);
});

test('OBJ: read back literally, every coordinate and every polygon as the mesh has them', () => {
  for (const mesh of [cubeQuads(5, { sphere: true }), mixedPolygons()]) {
    const text = quadObj(mesh, { name: 'my model' });
    const obj = parseObj(text);
    const nV = mesh.positions.length / 3, nF = mesh.faceStart.length - 1;
    assert.equal(obj.vertices.length, nV);
    assert.equal(obj.faces.length, nF);
    assert.deepEqual(obj.objects, ['my_model']);
    assert.ok(obj.comments.some((c) => c === `${nV} vertices, ${nF} faces`));
    assert.deepEqual(obj.vertices.flat(), Array.from(mesh.positions), 'the same doubles');
    for (let f = 0; f < nF; f++)
      assert.deepEqual(obj.faces[f], Array.from(mesh.faceVertices.subarray(mesh.faceStart[f], mesh.faceStart[f + 1])));
    assert.ok(text.endsWith('\n'));
  }
  const cube = parseObj(quadObj(cubeQuads(2)));
  assert.ok(cube.faces.every((f) => f.length === 4));
  assert.ok(/^f \d+ \d+ \d+ \d+$/m.test(quadObj(cubeQuads(2))), 'f a b c d, 1-based');
  assert.ok(!/^f .*\b0\b/m.test(quadObj(cubeQuads(2))), 'no index 0');
});

// A GLB's chunks, checked as the glTF 2.0 spec lays them out: {doc, bin}.
function readGlb(buffer) {
  const view = new DataView(buffer);
  assert.equal(view.getUint32(0, true), 0x46546c67, 'magic glTF');
  assert.equal(view.getUint32(4, true), 2, 'version 2');
  assert.equal(view.getUint32(8, true), buffer.byteLength, 'total length');
  const jsonLength = view.getUint32(12, true);
  assert.equal(view.getUint32(16, true), 0x4e4f534a, 'JSON chunk first');
  assert.equal(jsonLength % 4, 0);
  const doc = JSON.parse(new TextDecoder().decode(new Uint8Array(buffer, 20, jsonLength)));
  const at = 20 + jsonLength;
  const binLength = view.getUint32(at, true);
  assert.equal(view.getUint32(at + 4, true), 0x004e4942, 'BIN chunk second');
  assert.equal(binLength % 4, 0);
  assert.equal(at + 8 + binLength, buffer.byteLength, 'nothing after the BIN chunk');
  return { doc, bin: buffer.slice(at + 8, at + 8 + binLength) };
}

const accessorData = ({ doc, bin }, index, Type) => {
  const a = doc.accessors[index], v = doc.bufferViews[a.bufferView];
  const components = { VEC3: 3, SCALAR: 1 }[a.type];
  return new Type(bin, v.byteOffset + (a.byteOffset ?? 0), a.count * components);
};

test('GLB: chunks, accessor counts and bounds equal the mesh and its triangulation', () => {
  const mesh = cubeQuads(7, { sphere: true });
  const glb = readGlb(quadGlb(mesh, { name: 'ball quad mesh' }));
  const { doc } = glb;
  const nV = mesh.positions.length / 3, nF = mesh.faceStart.length - 1;
  assert.equal(doc.asset.version, '2.0');
  assert.equal(doc.buffers[0].byteLength, glb.bin.byteLength);
  const primitive = doc.meshes[0].primitives[0];
  assert.equal(primitive.mode, 4);
  assert.equal(doc.meshes[0].extras.quadFaces, nF);
  const position = doc.accessors[primitive.attributes.POSITION];
  const normal = doc.accessors[primitive.attributes.NORMAL];
  const indices = doc.accessors[primitive.indices];
  assert.equal(position.count, nV);
  assert.equal(normal.count, nV);
  assert.equal(indices.count, 6 * nF, 'two triangles per quad');
  assert.equal(indices.componentType, 5125);
  for (const v of doc.bufferViews)
    assert.ok(v.byteOffset % 4 === 0 && v.byteOffset + v.byteLength <= glb.bin.byteLength, 'aligned, inside BIN');
  const p = accessorData(glb, primitive.attributes.POSITION, Float32Array);
  assert.deepEqual(Array.from(p), Array.from(Float32Array.from(mesh.positions)));
  for (let c = 0; c < 3; c++) {
    const values = Array.from(p).filter((_, k) => k % 3 === c);
    assert.equal(position.min[c], Math.min(...values));
    assert.equal(position.max[c], Math.max(...values));
  }
  assert.deepEqual(Array.from(accessorData(glb, primitive.indices, Uint32Array)), Array.from(triangulate(mesh)));
  const n = accessorData(glb, primitive.attributes.NORMAL, Float32Array);
  for (let v = 0; v < nV; v++) assert.ok(Math.abs(Math.hypot(n[3 * v], n[3 * v + 1], n[3 * v + 2]) - 1) < 1e-6);
});

test('GLB: the Khronos glTF-Validator reports no error, and three.js loads the triangles', async () => {
  for (const mesh of [cubeQuads(6, { sphere: true }), mixedPolygons()]) {
    const buffer = quadGlb(mesh);
    const report = await validator.validateBytes(new Uint8Array(buffer), {
      uri: 'quad.glb',
      externalResourceFunction: (uri) => Promise.reject(new Error(`external resource ${uri}`)),
    });
    assert.equal(report.issues.numErrors, 0, JSON.stringify(report.issues.messages.slice(0, 5)));
    const gltf = await new Promise((resolve, reject) => new GLTFLoader().parse(buffer, '', resolve, reject));
    const meshes = [];
    gltf.scene.traverse((o) => o.isMesh && meshes.push(o));
    assert.equal(meshes.length, 1);
    const geometry = meshes[0].geometry;
    assert.equal(geometry.getAttribute('position').count, mesh.positions.length / 3);
    assert.equal(geometry.index.count, triangulate(mesh).length);
  }
});

// The panel's lines from the core's statistics: counts grouped, and a line on singularities closer than a quad only
// where there are some, with what helps only where the grid folded (a polygon left or a flipped face).
test("the panel says where the field's singularities crowd closer than a quad, and what helps where it folded", () => {
  const stats = {
    quads: 18589, faces: 18597, quadShare: 18589 / 18597, irregularVertices: 166, irregularNearSingularity: 1,
    fieldSingularities: 175, edgeAngleMedianDeg: 3.85, edgeAngleP90Deg: 11.4, hausdorffRelative: 0.0052,
    aspectMedian: 1.106, flippedFaces: 0, degenerateFaces: 0, manifold: true, ms: 56083, crowdedSingularities: 0,
  };
  const clean = statsLines(stats);
  assert.equal(clean[0], 'Quads: 18,589 of 18,597 faces (99.96 %)');
  assert.ok(!clean.some((l) => l.startsWith('Singularities closer')));
  const crowdedLine = (s) => statsLines(s).find((l) => l.startsWith('Singularities closer than a quad'));
  assert.equal(crowdedLine({ ...stats, crowdedSingularities: 156 }),
    'Singularities closer than a quad: 156: smaller quads, or fewer features, give cleaner quads');
  assert.equal(crowdedLine({ ...stats, quads: 18597, crowdedSingularities: 2 }), 'Singularities closer than a quad: 2');
  assert.match(crowdedLine({ ...stats, quads: 18597, flippedFaces: 1, crowdedSingularities: 2 }), /smaller quads/);
});

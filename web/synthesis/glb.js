// SPDX-License-Identifier: GPL-2.0-or-later
// A minimal glTF 2.0 binary (GLB) writer for textured triangle meshes: positions, optional normals, TEXCOORD_0,
// 32-bit indices, and optionally one PNG as the base-colour texture of a single material. Runs in browsers and
// in node (typed arrays, DataView and TextEncoder only). Used for exportGLB() and for the generated test meshes.

const FLOAT = 5126;
const UINT32 = 5125;

function minMax(values, width) {
  const min = new Array(width).fill(Infinity), max = new Array(width).fill(-Infinity);
  for (let i = 0; i < values.length; i += width)
    for (let k = 0; k < width; k++) {
      min[k] = Math.min(min[k], values[i + k]);
      max[k] = Math.max(max[k], values[i + k]);
    }
  return { min, max };
}

const pad4 = (n) => (n + 3) & ~3;

// positions: Float32Array (3 per vertex); uvs: Float32Array (2 per vertex) or null; normals: Float32Array or
// null; indices: Uint32Array; png: Uint8Array (PNG bytes) or null; name: mesh name.
// UVs are written as given (glTF's v axis points down the image: pass v flipped if the image is stored bottom-up).
export function encodeGlb({ positions, uvs = null, normals = null, indices, png = null, name = 'mesh', generator = 'tangent-field-designer' }) {
  const chunks = [];
  let offset = 0;
  const bufferViews = [];
  const accessors = [];
  const addView = (bytes, target) => {
    const view = { buffer: 0, byteOffset: offset, byteLength: bytes.byteLength };
    if (target) view.target = target;
    bufferViews.push(view);
    chunks.push({ offset, bytes: new Uint8Array(bytes.buffer, bytes.byteOffset, bytes.byteLength) });
    offset = pad4(offset + bytes.byteLength);
    return bufferViews.length - 1;
  };
  const addAccessor = (array, type, width, componentType, withBounds, target) => {
    const view = addView(array, target);
    const acc = { bufferView: view, componentType, count: array.length / width, type };
    if (withBounds) Object.assign(acc, minMax(array, width));
    accessors.push(acc);
    return accessors.length - 1;
  };
  const attributes = { POSITION: addAccessor(Float32Array.from(positions), 'VEC3', 3, FLOAT, true, 34962) };
  if (normals) attributes.NORMAL = addAccessor(Float32Array.from(normals), 'VEC3', 3, FLOAT, false, 34962);
  if (uvs) attributes.TEXCOORD_0 = addAccessor(Float32Array.from(uvs), 'VEC2', 2, FLOAT, false, 34962);
  const indexAccessor = addAccessor(Uint32Array.from(indices), 'SCALAR', 1, UINT32, false, 34963);

  const primitive = { attributes, indices: indexAccessor, mode: 4 };
  const gltf = {
    asset: { version: '2.0', generator },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0, name }],
    meshes: [{ name, primitives: [primitive] }],
    accessors,
    bufferViews,
    buffers: [],
  };
  if (png) {
    const imageView = addView(png, 0);
    gltf.images = [{ bufferView: imageView, mimeType: 'image/png' }];
    gltf.samplers = [{ magFilter: 9729, minFilter: 9987, wrapS: 33071, wrapT: 33071 }];
    gltf.textures = [{ source: 0, sampler: 0 }];
    gltf.materials = [{ name: 'synthesized', pbrMetallicRoughness: { baseColorTexture: { index: 0 }, metallicFactor: 0, roughnessFactor: 0.8 }, doubleSided: true }];
    primitive.material = 0;
  }
  const binLength = pad4(offset);
  gltf.buffers.push({ byteLength: binLength });

  const json = new TextEncoder().encode(JSON.stringify(gltf));
  const jsonLength = pad4(json.length);
  const total = 12 + 8 + jsonLength + 8 + binLength;
  const out = new Uint8Array(total);
  const dv = new DataView(out.buffer);
  dv.setUint32(0, 0x46546c67, true); // 'glTF'
  dv.setUint32(4, 2, true);
  dv.setUint32(8, total, true);
  dv.setUint32(12, jsonLength, true);
  dv.setUint32(16, 0x4e4f534a, true); // 'JSON'
  out.set(json, 20);
  out.fill(0x20, 20 + json.length, 20 + jsonLength);
  let o = 20 + jsonLength;
  dv.setUint32(o, binLength, true);
  dv.setUint32(o + 4, 0x004e4942, true); // 'BIN\0'
  o += 8;
  for (const c of chunks) out.set(c.bytes, o + c.offset);
  return out;
}

// Reads the JSON chunk of a GLB (for tests and sanity checks).
export function glbJson(bytes) {
  const dv = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  if (dv.getUint32(0, true) !== 0x46546c67) throw new Error('not a GLB');
  const len = dv.getUint32(12, true);
  return JSON.parse(new TextDecoder().decode(bytes.subarray(20, 20 + len)));
}

// An n x n grid over the unit square in the z = 0 plane, UV = (x, y): the flat test surface of the synthesis
// tests and of the benchmark. Counter-clockwise seen from +z.
export function flatSquareGlb(n = 16) {
  const positions = new Float32Array(3 * (n + 1) * (n + 1));
  const uvs = new Float32Array(2 * (n + 1) * (n + 1));
  for (let j = 0; j <= n; j++)
    for (let i = 0; i <= n; i++) {
      const v = j * (n + 1) + i;
      positions.set([i / n, j / n, 0], 3 * v);
      uvs.set([i / n, j / n], 2 * v);
    }
  const indices = [];
  for (let j = 0; j < n; j++)
    for (let i = 0; i < n; i++) {
      const a = j * (n + 1) + i, b = a + 1, c = a + n + 1, d = c + 1;
      // Alternate the diagonal so that the mesh has no preferred direction.
      if ((i + j) % 2 === 0) indices.push(a, b, d, a, d, c);
      else indices.push(a, b, c, b, d, c);
    }
  return encodeGlb({ positions, uvs, indices: Uint32Array.from(indices), name: 'flat-square', generator: 'tangent-field-designer synthesis' });
}

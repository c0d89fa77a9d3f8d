// Small models for the export and synthesis tests, made in code: a curved height-field patch with its own
// (warped, non-conformal) UVs as GLB, with a node transform, the same patch as OFF without UVs, and a flat
// square with UV = (x, y).
export const GRID = 16;

const height = (x, y) => 0.25 * Math.sin(2.5 * x) * Math.cos(2.0 * y);
const warpedUV = (x, y) => [0.05 + 0.8 * x + 0.1 * y * y, 0.05 + 0.7 * y + 0.1 * x];

function patch() {
  const positions = [], uvs = [], indices = [];
  for (let j = 0; j <= GRID; j++)
    for (let i = 0; i <= GRID; i++) {
      const x = i / GRID, y = j / GRID;
      positions.push(x, y, height(x, y));
      uvs.push(...warpedUV(x, y));
    }
  for (let j = 0; j < GRID; j++)
    for (let i = 0; i < GRID; i++) {
      const a = j * (GRID + 1) + i, b = a + 1, c = a + GRID + 2, d = a + GRID + 1;
      indices.push(a, b, c, a, c, d);
    }
  return { positions: new Float32Array(positions), uvs: new Float32Array(uvs), indices: new Uint32Array(indices) };
}

export function patchGlb({ normalMap = false } = {}) {
  const { positions, uvs, indices } = patch();
  // A 1x1 PNG as the normal map: the smallest valid image that makes the material normal-mapped.
  const png = normalMap
    ? Uint8Array.from(atob('iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR4nGNoaPj/HwAFhgKZXtj7LQAAAABJRU5ErkJggg=='), (c) => c.charCodeAt(0))
    : null;
  const material = { name: 'own', pbrMetallicRoughness: { baseColorFactor: [0.9, 0.5, 0.2, 1] } };
  const doc = {
    asset: { version: '2.0' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0, translation: [1, 2, 3], scale: [2, 2, 2] }],
    meshes: [{ primitives: [{ attributes: { POSITION: 0, TEXCOORD_0: 1 }, indices: 2, material: 0 }] }],
    materials: [png ? { ...material, normalTexture: { index: 0 } } : material],
    accessors: meshAccessors(positions, uvs, indices),
    bufferViews: [], // filled in by encodeGlb
    buffers: [],
  };
  if (png) {
    doc.images = [{ bufferView: 3, mimeType: 'image/png' }];
    doc.textures = [{ source: 0 }];
  }
  return encodeGlb(doc, png ? [positions, uvs, indices, png] : [positions, uvs, indices]);
}

// An n x n grid over the unit square in the z = 0 plane, UV = (x, y): the flat test surface of the synthesis
// tests. Counter-clockwise seen from +z.
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
  const doc = {
    asset: { version: '2.0' },
    scene: 0,
    scenes: [{ nodes: [0] }],
    nodes: [{ mesh: 0, name: 'flat-square' }],
    meshes: [{ name: 'flat-square', primitives: [{ attributes: { POSITION: 0, TEXCOORD_0: 1 }, indices: 2, mode: 4 }] }],
    accessors: meshAccessors(positions, uvs, Uint32Array.from(indices)),
  };
  return encodeGlb(doc, [positions, uvs, Uint32Array.from(indices)]);
}

// Accessors 0-2 over bufferViews 0-2: POSITION (with its bounds), TEXCOORD_0 and 32-bit indices.
function meshAccessors(positions, uvs, indices) {
  const min = [0, 1, 2].map((k) => Math.min(...positions.filter((_, i) => i % 3 === k)));
  const max = [0, 1, 2].map((k) => Math.max(...positions.filter((_, i) => i % 3 === k)));
  return [
    { bufferView: 0, componentType: 5126, count: positions.length / 3, type: 'VEC3', min, max },
    { bufferView: 1, componentType: 5126, count: uvs.length / 2, type: 'VEC2' },
    { bufferView: 2, componentType: 5125, count: indices.length, type: 'SCALAR' },
  ];
}

// A GLB of `doc` with one bufferView per part (typed arrays, each 4-byte aligned in the one buffer).
function encodeGlb(doc, parts) {
  const views = [];
  let offset = 0;
  for (const part of parts) {
    views.push({ buffer: 0, byteOffset: offset, byteLength: part.byteLength });
    offset += (part.byteLength + 3) & ~3;
  }
  doc.bufferViews = views;
  doc.buffers = [{ byteLength: offset }];
  const bin = new Uint8Array(offset);
  for (const [i, part] of parts.entries()) bin.set(new Uint8Array(part.buffer, part.byteOffset, part.byteLength), views[i].byteOffset);
  let json = new TextEncoder().encode(JSON.stringify(doc));
  const padded = new Uint8Array((json.length + 3) & ~3).fill(0x20);
  padded.set(json);
  json = padded;
  const out = new Uint8Array(12 + 8 + json.length + 8 + bin.length);
  const dv = new DataView(out.buffer);
  dv.setUint32(0, 0x46546c67, true);
  dv.setUint32(4, 2, true);
  dv.setUint32(8, out.length, true);
  dv.setUint32(12, json.length, true);
  dv.setUint32(16, 0x4e4f534a, true);
  out.set(json, 20);
  dv.setUint32(20 + json.length, bin.length, true);
  dv.setUint32(24 + json.length, 0x004e4942, true);
  out.set(bin, 28 + json.length);
  return out;
}

export function patchOff() {
  const { positions, indices } = patch();
  const lines = ['OFF', `${positions.length / 3} ${indices.length / 3} 0`];
  for (let i = 0; i < positions.length; i += 3) lines.push(`${positions[i]} ${positions[i + 1]} ${positions[i + 2]}`);
  for (let i = 0; i < indices.length; i += 3) lines.push(`3 ${indices[i]} ${indices[i + 1]} ${indices[i + 2]}`);
  return lines.join('\n') + '\n';
}

// A stroke across the patch's middle as welded-mesh surface points: the patch's faces come in (i, j) order,
// two per grid square, so the face above (x, y) is found in closed form (before the node transform).
export function diagonalStrokeDesign() {
  const points = [];
  for (let s = 0; s <= 24; s++) {
    const x = 0.15 + (0.7 * s) / 24, y = 0.3 + 0.4 * x;
    const i = Math.min(GRID - 1, Math.floor(x * GRID)), j = Math.min(GRID - 1, Math.floor(y * GRID));
    const fx = x * GRID - i, fy = y * GRID - j;
    const square = j * GRID + i;
    // Triangles (a, b, c) and (a, c, d) with a = (0,0), b = (1,0), c = (1,1), d = (0,1) in the square.
    if (fx >= fy) points.push({ face: 2 * square, bary: [1 - fx, fx - fy, fy] });
    else points.push({ face: 2 * square + 1, bary: [1 - fy, fx, fy - fx] });
  }
  return { boundary: 'free', constraints: [{ type: 'stroke', points, strength: 1, weight: 100 }] };
}

// SPDX-License-Identifier: GPL-2.0-or-later
// The model as a non-indexed geometry, every face's corners their own vertices: for what differs from one face
// to the next at a shared vertex (the synthesized texture's atlas UVs, the stripe pattern's phases). Shaded with
// the welded mesh's smooth vertex normals, which the Surface already holds. Imports three.js.
import { BufferAttribute, BufferGeometry } from 'three';

// Faces per task while the geometry is built (~20 ms).
const BUILD_SLICE = 1 << 15;

const nextTask = () => new Promise((resolve) => setTimeout(resolve, 0));

// The model's corners, each with its position, smooth normal and (given cornerUVs, 6 per face) atlas UV.
// bounds: the surface's bounding sphere (the same points), when it has one. Built a slice of faces per task,
// the first too.
export async function cornerGeometry({ positions, triangles, vertexNormals }, cornerUVs, bounds) {
  const nF = triangles.length / 3;
  const pos = new Float32Array(9 * nF), nor = new Float32Array(9 * nF);
  const uv = cornerUVs ? new Float32Array(6 * nF) : null;
  for (let f0 = 0; f0 < nF; f0 += BUILD_SLICE) {
    await nextTask();
    for (let f = f0; f < Math.min(nF, f0 + BUILD_SLICE); f++)
      for (let k = 0; k < 3; k++) {
        const v = 3 * triangles[3 * f + k];
        for (let c = 0; c < 3; c++) {
          pos[9 * f + 3 * k + c] = positions[v + c];
          nor[9 * f + 3 * k + c] = vertexNormals[v + c];
        }
        if (!uv) continue;
        uv[6 * f + 2 * k] = cornerUVs[6 * f + 2 * k];
        uv[6 * f + 2 * k + 1] = cornerUVs[6 * f + 2 * k + 1];
      }
  }
  const geom = new BufferGeometry();
  geom.setAttribute('position', new BufferAttribute(pos, 3));
  geom.setAttribute('normal', new BufferAttribute(nor, 3));
  if (uv) geom.setAttribute('uv', new BufferAttribute(uv, 2));
  if (bounds) geom.boundingSphere = bounds.clone();
  else geom.computeBoundingSphere();
  return geom;
}

// cornerGeometry (extend(geom) adding attributes of its own), sent to the GPU ahead of its first frame by
// `staging` (views/mesh-staging.js): at 832k faces, 80 MB that took the page's thread 0.6 s in one task. Resolves
// with the geometry, or with null (the geometry freed) once current() says a newer call replaced this one.
export async function stagedCornerGeometry(staging, surface, cornerUVs, bounds, current, extend = () => {}) {
  const geom = await cornerGeometry(surface, cornerUVs, bounds);
  extend(geom);
  if (current()) {
    await staging.stage(geom, () => geom);
    staging.take(geom);
  }
  if (current()) return geom;
  geom.dispose();
  return null;
}

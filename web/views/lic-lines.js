// The flow texture of an N-field (N ≥ 2, lic.js): what differs from a vector field's.
//
// The vertex representatives cannot be interpolated as they come (a line field's two ends of a face may point
// opposite ways), so the direction pass draws its own, unindexed copy of the surface whose corners carry each face's
// matched representatives (geometry/chart-comb.js atlasCombedCorners): matched within a face before they reach the
// GPU, combed across faces so that "the representative turned by 2πk/N" is one family of lines over whole regions.
// Each family (lineFamilies: a line field one, a cross field two at 90°) is one direction pass and one convolution,
// and the convolutions are averaged on screen.
import { BufferAttribute, BufferGeometry } from 'three';
import { atlasCombedCorners } from '../geometry/chart-comb.js';
import { familyCosine, lineFamilies } from '../geometry/nfield.js';

// Pass 1 for one family: the corner field turned by `angle` about its face's normal.
export const LINE_DIRECTION_VERTEX = /* glsl */ `
attribute vec3 licField;
attribute vec3 licNormal;
uniform float angle;
varying vec3 vWorld;
varying vec3 vField;
varying vec3 vNormal;
void main() {
  vec4 world = modelMatrix * vec4(position, 1.0);
  vWorld = world.xyz;
  vField = mat3(modelMatrix) * (cos(angle) * licField + sin(angle) * cross(licNormal, licField));
  vNormal = normalize(mat3(modelMatrix) * normal);
  gl_Position = projectionMatrix * viewMatrix * world;
}`;

// The surface unindexed, three corners per face: positions, the vertex normals (the shading matches the
// indexed surface's) and the face normal each corner's vector turns about.
export function lineGeometry(surface) {
  const { triangles: T, positions: P, vertexNormals: VN, normals: FN, nF } = surface;
  const pos = new Float32Array(9 * nF), nrm = new Float32Array(9 * nF), face = new Float32Array(9 * nF);
  for (let f = 0; f < nF; f++) {
    for (let k = 0; k < 3; k++) {
      const v = T[3 * f + k], o = 9 * f + 3 * k;
      for (let c = 0; c < 3; c++) {
        pos[o + c] = P[3 * v + c];
        nrm[o + c] = VN[3 * v + c];
        face[o + c] = FN[3 * f + c];
      }
    }
  }
  const g = new BufferGeometry();
  g.setAttribute('position', new BufferAttribute(pos, 3));
  g.setAttribute('normal', new BufferAttribute(nrm, 3));
  g.setAttribute('licNormal', new BufferAttribute(face, 3));
  g.computeBoundingSphere();
  return g;
}

// The corner field of one N-field on the line geometry.
export function setLineField(geometry, surface, vertexVectors, faceVectors, N) {
  // One comb over each connected surface (no atlas here): the one the texture uses, without seams.
  const corners = Float32Array.from(atlasCombedCorners(surface, vertexVectors, faceVectors, N).corners);
  const attr = geometry.getAttribute('licField');
  if (attr && attr.count === corners.length / 3) {
    attr.array.set(corners);
    attr.needsUpdate = true;
  } else geometry.setAttribute('licField', new BufferAttribute(corners, 3));
}

// Per convolution pass: the family's angle, the weight that keeps the picture the running mean of the
// passes drawn so far (alpha 1/(k+1) over the last mean), the streak's stop where it meets another family
// (across a comb's cut the direction jumps by a family's spacing), and contrast made up for averaging.
export function linePasses(N, contrast) {
  const { count, angles } = lineFamilies(N);
  const minCos = Math.max(0, familyCosine(N));
  return angles.map((angle, k) => ({ angle, passAlpha: 1 / (k + 1), minCos, contrast: contrast * Math.sqrt(count) }));
}

// A grid's families told apart by the pattern's own labels: the phase the GLB carries as TEXCOORD_1 (the first
// family's phase in x, the second's in y; docs/export.md). gridFamiliesAlongField reads each face's lines along
// its field direction X and along n x X, but a cross field's face direction is any one of its four, so which of
// those is the pattern's first family changes from face to face; taking the worse of the two per face reads two
// families each within a degree as worse than that. Owns no state; imports the texture metrics alone.
import { faces, fieldFrame } from './surface-texture-metrics.mjs';

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];

// The 3D gradient of a function linear on the face with values s at its corners P.
function faceGradient(P, s) {
  const e1 = sub(P[1], P[0]), e2 = sub(P[2], P[0]), n = cross(e1, e2), nn = dot(n, n);
  if (!(nn > 0)) return null;
  // grad = ((s1 - s0) (e2 x n) + (s2 - s0) (n x e1)) / |n|^2
  const a = cross(e2, n), b = cross(n, e1);
  return [0, 1, 2].map((k) => ((s[1] - s[0]) * a[k] + (s[2] - s[0]) * b[k]) / nn);
}

// families: gridFamiliesAlongField's [along X, along n x X] per face. Returns [first, second]: per face, the error
// of the pattern's first family (the one whose phase is TEXCOORD_1's x) and of its second; NaN where the GLB has
// no phase, the face no field, or the first family's phase does not change over the face.
export function familiesByPhase(glb, fieldPerFace, families) {
  if (!glb.phases) throw new Error('familiesByPhase: the GLB carries no phase (TEXCOORD_1)');
  const F = faces(glb);
  const first = new Float64Array(F.length).fill(NaN), second = new Float64Array(F.length).fill(NaN);
  F.forEach((face, f) => {
    const frame = fieldFrame(face, fieldPerFace.slice(3 * f, 3 * f + 3));
    const corners = [0, 1, 2].map((k) => glb.indices[3 * f + k]);
    const g = faceGradient(face.P, corners.map((i) => glb.phases[2 * i]));
    if (!frame || !g || !(Math.hypot(...g) > 0)) return;
    // The first family's lines run across its phase's gradient: along X where the gradient lies nearer n x X.
    const k = Math.abs(dot(g, frame.Y)) >= Math.abs(dot(g, frame.X)) ? 0 : 1;
    first[f] = families[k][f];
    second[f] = families[1 - k][f];
  });
  return [first, second];
}

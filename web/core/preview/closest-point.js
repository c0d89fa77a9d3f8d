// The closest point of a triangle to a point: the one test of every search of the preview's map
// (coarse-search.js, design-on-coarse.js). Owns nothing; imports nothing.

// Squared distance from p to triangle f of (P, T), and the closest point's barycentric coordinates into b
// (Ericson, Real-Time Collision Detection, 5.1.5). Scalars only: it runs a few million times per model.
export function closestOnTriangle(p, P, T, f, b) {
  const a = 3 * T[3 * f], bb = 3 * T[3 * f + 1], c = 3 * T[3 * f + 2];
  const ax = P[a], ay = P[a + 1], az = P[a + 2];
  const abx = P[bb] - ax, aby = P[bb + 1] - ay, abz = P[bb + 2] - az;
  const acx = P[c] - ax, acy = P[c + 1] - ay, acz = P[c + 2] - az;
  const apx = p[0] - ax, apy = p[1] - ay, apz = p[2] - az;
  const d1 = abx * apx + aby * apy + abz * apz, d2 = acx * apx + acy * apy + acz * apz;
  let u = 1, v = 0, w = 0;
  if (d1 > 0 || d2 > 0) {
    const bpx = apx - abx, bpy = apy - aby, bpz = apz - abz;
    const d3 = abx * bpx + aby * bpy + abz * bpz, d4 = acx * bpx + acy * bpy + acz * bpz;
    const cpx = apx - acx, cpy = apy - acy, cpz = apz - acz;
    const d5 = abx * cpx + aby * cpy + abz * cpz, d6 = acx * cpx + acy * cpy + acz * cpz;
    const vc = d1 * d4 - d3 * d2, vb = d5 * d2 - d1 * d6, va = d3 * d6 - d5 * d4;
    if (d3 >= 0 && d4 <= d3) {
      u = 0;
      v = 1;
    } else if (d6 >= 0 && d5 <= d6) {
      u = 0;
      w = 1;
    } else if (vc <= 0 && d1 >= 0 && d3 <= 0) {
      v = d1 / (d1 - d3);
      u = 1 - v;
    } else if (vb <= 0 && d2 >= 0 && d6 <= 0) {
      w = d2 / (d2 - d6);
      u = 1 - w;
    } else if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
      w = (d4 - d3) / (d4 - d3 + (d5 - d6));
      u = 0;
      v = 1 - w;
    } else {
      const den = 1 / (va + vb + vc);
      v = vb * den;
      w = vc * den;
      u = 1 - v - w;
    }
  }
  b[0] = u;
  b[1] = v;
  b[2] = w;
  const qx = v * abx + w * acx - apx, qy = v * aby + w * acy - apy, qz = v * abz + w * acz - apz;
  return qx * qx + qy * qy + qz * qz;
}

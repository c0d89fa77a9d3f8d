// N-symmetric fields (N = 1 vector, 2 line, 4 cross; 1..6): the core hands one unit representative per face
// and per vertex, chosen arbitrarily among the N rotations by 2πk/N about the normal. Anything that combines
// two representatives (interpolating across a face, comparing neighbours, following a line) must first
// rotate one to the rotation closest to the other; these are those matchings, in 2D face frames and in 3D.

const TWO_PI = 2 * Math.PI;
export const MAX_SYMMETRY = 6;

// The symmetry a field declares, as an integer 1..MAX_SYMMETRY; anything else (absent, bad) is a vector field.
export function symmetryOf(n) {
  return Number.isInteger(n) && n >= 1 && n <= MAX_SYMMETRY ? n : 1;
}

// The rotation of v by 2πk/N closest to ref: k = round(N · angle(v → ref) / 2π). Whatever k, the result
// differs from ref by at most π/N, so a heading or a reference is never turned through by more than that.
export function closestRotation2d(v, ref, N) {
  if (N === 1) return [v[0], v[1]];
  const k = Math.round((N * Math.atan2(v[0] * ref[1] - v[1] * ref[0], v[0] * ref[0] + v[1] * ref[1])) / TWO_PI);
  if (k === 0) return [v[0], v[1]];
  const a = (TWO_PI * k) / N, c = Math.cos(a), s = Math.sin(a);
  return [c * v[0] - s * v[1], s * v[0] + c * v[1]];
}

// v (3D) turned about the unit normal n by `angle` (Rodrigues: its tangent part turns, its normal part stays).
export function rotateAbout(v, n, angle) {
  const c = Math.cos(angle), s = Math.sin(angle);
  const d = (v[0] * n[0] + v[1] * n[1] + v[2] * n[2]) * (1 - c);
  const x = n[1] * v[2] - n[2] * v[1], y = n[2] * v[0] - n[0] * v[2], z = n[0] * v[1] - n[1] * v[0];
  return [c * v[0] + s * x + d * n[0], c * v[1] + s * y + d * n[1], c * v[2] + s * z + d * n[2]];
}

// The 3D counterpart of closestRotation2d, about the unit normal n (v and ref in, or near, its tangent plane).
export function closestRotation(v, ref, n, N) {
  if (N === 1) return [v[0], v[1], v[2]];
  const cx = v[1] * ref[2] - v[2] * ref[1], cy = v[2] * ref[0] - v[0] * ref[2], cz = v[0] * ref[1] - v[1] * ref[0];
  const sin = cx * n[0] + cy * n[1] + cz * n[2], cos = v[0] * ref[0] + v[1] * ref[1] + v[2] * ref[2];
  const k = Math.round((N * Math.atan2(sin, cos)) / TWO_PI);
  return k === 0 ? [v[0], v[1], v[2]] : rotateAbout(v, n, (TWO_PI * k) / N);
}

// The directions of an N-field at a point, as angles from the representative: the glyph's spokes.
export function spokeAngles(N) {
  return Array.from({ length: N }, (_, k) => (TWO_PI * k) / N);
}

// The families of lines an N-field has through a point. An even N holds −d with every d, so N/2 lines each
// run both ways; an odd N does not (a 3-field's directions are 120° apart), so each of its N directions is
// a ray of its own, traced forward only. angles: from the representative; bothWays: whether to trace −d too.
export function lineFamilies(N) {
  const count = N % 2 ? N : N / 2;
  return { count, bothWays: N % 2 === 0, angles: Array.from({ length: count }, (_, k) => (TWO_PI * k) / N) };
}

// |cos| above which two unoriented lines belong to one family: half the angle between neighbouring families
// (π/N for even N, π/2N for odd N, whose rays as lines interleave). −1 (any two lines) where there is one.
export function familyCosine(N) {
  if (N <= 2) return -1;
  return Math.cos(N % 2 ? Math.PI / (2 * N) : Math.PI / N);
}

// Per face, the three vertex representatives laid into the face's plane and each turned to the rotation
// closest to the face's reference (reference: 3 per face, e.g. the face representatives; a zero reference
// matches corners 1 and 2 to corner 0): after this, interpolating the three is meaningful. Returns
// Float64Array(9 · nF), corner k of face f at 9f + 3k. Scalar code: it runs over every corner of the mesh
// whenever the flow texture shows a new N-field.
export function matchedCorners(surface, vertexVectors, reference, N) {
  const { triangles: T, normals: Nm, nF } = surface, V = vertexVectors;
  const out = new Float64Array(9 * nF);
  for (let f = 0; f < nF; f++) {
    const nx = Nm[3 * f], ny = Nm[3 * f + 1], nz = Nm[3 * f + 2];
    let rx = reference ? reference[3 * f] : 0;
    let ry = reference ? reference[3 * f + 1] : 0;
    let rz = reference ? reference[3 * f + 2] : 0;
    for (let k = 0; k < 3; k++) {
      const v = 3 * T[3 * f + k], o = 9 * f + 3 * k;
      const d = V[v] * nx + V[v + 1] * ny + V[v + 2] * nz;
      const tx = V[v] - d * nx, ty = V[v + 1] - d * ny, tz = V[v + 2] - d * nz;
      if (rx === 0 && ry === 0 && rz === 0) {
        rx = tx;
        ry = ty;
        rz = tz;
      }
      // Angle from t to the reference about n, in steps of 2π/N: k = round(N · angle / 2π).
      const sin = (ty * rz - tz * ry) * nx + (tz * rx - tx * rz) * ny + (tx * ry - ty * rx) * nz;
      const steps = N === 1 ? 0 : Math.round((N * Math.atan2(sin, tx * rx + ty * ry + tz * rz)) / TWO_PI);
      if (steps === 0) {
        out[o] = tx;
        out[o + 1] = ty;
        out[o + 2] = tz;
        continue;
      }
      // t lies in the plane: turning it by a about n is t cos a + (n × t) sin a.
      const a = (TWO_PI * steps) / N, c = Math.cos(a), sn = Math.sin(a);
      out[o] = c * tx + sn * (ny * tz - nz * ty);
      out[o + 1] = c * ty + sn * (nz * tx - nx * tz);
      out[o + 2] = c * tz + sn * (nx * ty - ny * tx);
    }
  }
  return out;
}

// The interpolated field at barycentric (b0, b1, b2) of face f, its corners matched to ref (3D, in the
// face's plane) first; out (3) receives it. One face's worth of matchedCorners, for the few faces sampled.
export function matchedAt(surface, vertexVectors, f, bary, ref, N, out) {
  const { triangles: T, normals: Nm } = surface, V = vertexVectors;
  const n = [Nm[3 * f], Nm[3 * f + 1], Nm[3 * f + 2]];
  out[0] = out[1] = out[2] = 0;
  for (let k = 0; k < 3; k++) {
    const v = T[3 * f + k], b = bary[k];
    const x = [V[3 * v], V[3 * v + 1], V[3 * v + 2]];
    const d = x[0] * n[0] + x[1] * n[1] + x[2] * n[2];
    const m = closestRotation([x[0] - d * n[0], x[1] - d * n[1], x[2] - d * n[2]], ref, n, N);
    out[0] += b * m[0];
    out[1] += b * m[1];
    out[2] += b * m[2];
  }
  return out;
}

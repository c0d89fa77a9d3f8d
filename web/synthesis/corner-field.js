// SPDX-License-Identifier: GPL-2.0-or-later
// The field the atlas's raster draws, per corner of each face (atlas-raster.js: 4 floats a corner, 12 a face),
// from what a run hands it: a vector field's 1-form (its Whitney field at the corners), a combed line or cross
// field's per-corner vectors, or per-vertex vectors; with each slice of faces' part of the reference magnitude.
// Owns nothing.
import { whitneyCorners } from '../geometry/whitney-corners.js';

// Faces f0 .. f1 - 1 of `field` ({whitney}, {cornerVectors} or per-vertex vectors) into out, adding their
// area-weighted magnitude and area to sums. T: the triangles (3 a face); A: the faces' areas.
export function fillCornerField(field, T, A, f0, f1, sums, out) {
  if (field?.cornerVectors) fromCorners(field.cornerVectors, T, A, f0, f1, sums, out);
  else if (field?.whitney) fromOneForm(field.whitney, T, A, f0, f1, sums, out);
  else fromVertices(field, T, A, f0, f1, sums, out);
}

// The field per corner of faces f0 .. f1 - 1 from the vertices', and their part of the reference magnitude
// (area-weighted mean over faces of the corner mean). Math.sqrt, not Math.hypot: 5 x faster in V8, and this
// is on the path from a stroke to its texture (bunny00: 7 -> 1.3 ms).
function fromVertices(vertexVectors, T, A, f0, f1, sums, out) {
  let magSum = 0, areaSum = 0;
  for (let f = f0; f < f1; f++) {
    let mag = 0;
    for (let k = 0; k < 3; k++) {
      const v = 3 * T[3 * f + k], o = 12 * f + 4 * k;
      const x = vertexVectors[v], y = vertexVectors[v + 1], z = vertexVectors[v + 2];
      out[o] = x;
      out[o + 1] = y;
      out[o + 2] = z;
      mag += Math.sqrt(x * x + y * y + z * z);
    }
    magSum += (mag / 3) * A[f];
    areaSum += A[f];
  }
  sums.mag += magSum;
  sums.area += areaSum;
}

// The same from a vector field's 1-form: its Whitney field at the corners.
function fromOneForm({ positions, rows, oneForm }, T, A, f0, f1, sums, out) {
  sums.mag += whitneyCorners(positions, T, rows, oneForm, f0, f1, out, 12);
  for (let f = f0; f < f1; f++) sums.area += A[f];
}

// The same from a per-corner field (9 per face).
function fromCorners(C, T, A, f0, f1, sums, out) {
  for (let f = f0; f < f1; f++) {
    let mag = 0;
    for (let k = 0; k < 3; k++) {
      const c = 9 * f + 3 * k, o = 12 * f + 4 * k;
      const x = C[c], y = C[c + 1], z = C[c + 2];
      out[o] = x;
      out[o + 1] = y;
      out[o + 2] = z;
      mag += Math.sqrt(x * x + y * y + z * z) / 3;
    }
    sums.mag += mag * A[f];
    sums.area += A[f];
  }
}

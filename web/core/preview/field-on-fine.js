// The coarse field carried back to the fine mesh of a big model's preview, through the map of the fine surface
// onto the coarse one (surface-map.js), so that the page draws the preview on the mesh it shows.
// Owns nothing; imports nothing.

// The coarse field on the fine mesh: {vertexVectors, faceVectors} (Float64Array, fine sizes). A vector field
// is interpolated from the coarse vertex vectors and laid into each fine tangent plane; a line or cross field
// (symmetry > 1: representatives, whose signs do not interpolate) takes the coarse face's. The face vectors
// only when out.faceVectors is given (an N-field's representatives, which the page cannot derive); the
// page derives a vector field's face vectors and one-form from its vertex vectors (geometry/vertex-field.js).
// out: {vertexVectors, faceVectors}: arrays to refill (the page hands old ones back). map: the SurfaceMap.
export function fieldOnFine(map, coarseFaceVectors, coarseVertexVectors, symmetry, out) {
  const lines = symmetry > 1;
  const { faceVectors, vertexVectors } = out;
  if (faceVectors) {
    map.everyFaceOnCoarse();
    sampleInto(
      faceVectors,
      map.faceFace,
      map.faceBary,
      map.faceNormals(),
      map.coarse.triangles,
      coarseFaceVectors,
      coarseVertexVectors,
      lines,
    );
  }
  sampleInto(
    vertexVectors,
    map.vertexFace,
    map.vertexBary,
    map.vertexNormals,
    map.coarse.triangles,
    coarseFaceVectors,
    coarseVertexVectors,
    lines,
  );
  return { faceVectors, vertexVectors };
}

// For each sample k (a fine face or vertex): the coarse field at its closest point (coarse face face[k], bary
// 3k..), laid into the plane of normals 3k..; a line or cross field takes the coarse face's representative,
// as a unit vector.
function sampleInto(out, face, bary, normals, tri, faceVectors, vertexVectors, lines) {
  for (let k = 0, n = face.length; k < n; k++) {
    const f = face[k];
    let x = 0;
    let y = 0;
    let z = 0;
    if (lines) {
      x = faceVectors[3 * f];
      y = faceVectors[3 * f + 1];
      z = faceVectors[3 * f + 2];
    } else {
      for (let j = 0; j < 3; j++) {
        const c = 3 * tri[3 * f + j], w = bary[3 * k + j];
        x += w * vertexVectors[c];
        y += w * vertexVectors[c + 1];
        z += w * vertexVectors[c + 2];
      }
    }
    const n0 = normals[3 * k], n1 = normals[3 * k + 1], n2 = normals[3 * k + 2];
    const d = x * n0 + y * n1 + z * n2;
    x -= d * n0;
    y -= d * n1;
    z -= d * n2;
    if (lines) {
      const len = Math.hypot(x, y, z) || 1;
      x /= len;
      y /= len;
      z /= len;
    }
    out[3 * k] = x;
    out[3 * k + 1] = y;
    out[3 * k + 2] = z;
  }
}

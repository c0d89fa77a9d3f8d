// Quad meshes made here for the quad layer's tests (web/quad/): a cube's surface cut into n × n quads per side,
// welded, counter-clockwise seen from outside, optionally pushed onto the unit sphere, in the core's CSR form
// ({positions, faceStart, faceVertices, irregular}); and an OBJ reader that takes the file's text literally.

// The cube [-1, 1]³ with n × n quads per side (6n² quads, 6n² + 2 vertices); sphere: projected onto the unit
// sphere. Its eight corners are the valence-3 vertices (`irregular`).
export function cubeQuads(n, { sphere = false } = {}) {
  const index = new Map(), positions = [], faceVertices = [];
  const vertex = (p) => {
    const key = p.map((x) => Math.round(x * n)).join(',');
    if (!index.has(key)) {
      index.set(key, positions.length / 3);
      const l = sphere ? Math.hypot(...p) : 1;
      positions.push(...p.map((x) => x / l));
    }
    return index.get(key);
  };
  // Each side: a normal axis and sign, and two tangent axes (u, v) with u × v = the outward normal.
  const sides = [[0, 1, 1, 2], [0, -1, 2, 1], [1, 1, 2, 0], [1, -1, 0, 2], [2, 1, 0, 1], [2, -1, 1, 0]];
  for (const [axis, sign, u, v] of sides)
    for (let j = 0; j < n; j++)
      for (let i = 0; i < n; i++) {
        const at = (a, b) => {
          const p = [0, 0, 0];
          p[axis] = sign;
          p[u] = -1 + (2 * a) / n;
          p[v] = -1 + (2 * b) / n;
          return vertex(p);
        };
        faceVertices.push(at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
      }
  const nF = faceVertices.length / 4;
  const corners = [];
  for (let v = 0; v < positions.length / 3; v++)
    if ([0, 1, 2].every((c) => Math.abs(Math.abs(positions[3 * v + c]) - (sphere ? 1 / Math.sqrt(3) : 1)) < 1e-12))
      corners.push(v);
  return {
    positions: Float64Array.from(positions),
    faceStart: Int32Array.from({ length: nF + 1 }, (_, f) => 4 * f),
    faceVertices: Int32Array.from(faceVertices),
    irregular: Int32Array.from(corners),
  };
}

// A mesh with polygons other than quads, in the plane z = 0, counter-clockwise seen from +z: a pentagon (one
// corner on a straight side), a quad and two triangles.
export function mixedPolygons() {
  const positions = Float64Array.from([0, 0, 0, 2, 0, 0, 2, 1, 0, 1, 1, 0, 0, 1, 0, 3, 0, 0, 3, 1, 0, 2.5, 1.6, 0,
    4, 0.5, 0]);
  const polygons = [[0, 1, 2, 3, 4], [1, 5, 6, 2], [6, 7, 2], [5, 8, 6]];
  const faceStart = [0];
  for (const p of polygons) faceStart.push(faceStart.at(-1) + p.length);
  return { positions, faceStart: Int32Array.from(faceStart), faceVertices: Int32Array.from(polygons.flat()),
    irregular: new Int32Array(0) };
}

// OBJ text → {vertices: [[x, y, z]], faces: [[a, b, ...] 0-based], objects, comments}; throws on a line it
// does not know or an index out of range.
export function parseObj(text) {
  const vertices = [], faces = [], objects = [], comments = [];
  for (const line of text.split('\n')) {
    const [key, ...rest] = line.trim().split(/\s+/);
    if (key === '' || key === undefined) continue;
    if (key === '#') comments.push(rest.join(' '));
    else if (key === 'o') objects.push(rest.join(' '));
    else if (key === 'v') {
      if (rest.length !== 3) throw new Error(`a vertex with ${rest.length} coordinates: ${line}`);
      vertices.push(rest.map(Number));
    } else if (key === 'f') faces.push(rest.map((s) => Number(s.split('/')[0]) - 1));
    else throw new Error(`unknown OBJ line: ${line}`);
  }
  for (const f of faces)
    for (const v of f) if (!(Number.isInteger(v) && v >= 0 && v < vertices.length)) throw new Error(`index ${v + 1}`);
  return { vertices, faces, objects, comments };
}

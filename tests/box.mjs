// A box [-1, 1]^3 with n edges along each crease, faces outward, as OFF text: its 12 n crease edges are convex
// folds of 90 degrees, every other edge flat. A closed genus-0 test mesh with sharp features, shared by the
// browser tests.
export function boxOff(n) {
  const index = new Map(), positions = [], triangles = [];
  const at = (p) => {
    const key = p.join(',');
    if (!index.has(key)) index.set(key, positions.push(p) - 1);
    return index.get(key);
  };
  for (let axis = 0; axis < 3; axis++)
    for (const sign of [-1, 1]) {
      const [u, w] = [(axis + 1) % 3, (axis + 2) % 3];
      const grid = (i, j) => {
        const p = [0, 0, 0];
        p[axis] = sign;
        p[u] = -1 + (2 * i) / n;
        p[w] = -1 + (2 * j) / n;
        return at(p);
      };
      for (let i = 0; i < n; i++)
        for (let j = 0; j < n; j++) {
          const [a, b, c, d] = [grid(i, j), grid(i + 1, j), grid(i + 1, j + 1), grid(i, j + 1)];
          triangles.push(...(sign > 0 ? [a, b, c, a, c, d] : [a, c, b, a, d, c]));
        }
    }
  const faces = Array.from({ length: triangles.length / 3 }, (_, f) => `3 ${triangles.slice(3 * f, 3 * f + 3).join(' ')}`);
  return `OFF\n${positions.length} ${faces.length} 0\n${positions.map((p) => p.join(' ')).join('\n')}\n${faces.join('\n')}\n`;
}

// An icosphere: the icosahedron with `levels` midpoint subdivisions, projected onto the unit sphere, as OFF
// text (levels 2: 320 faces; 5: 30,720 edges). A closed genus-0 test mesh shared by the node and browser tests.
export function icosphereOff(levels) {
  const t = (1 + Math.sqrt(5)) / 2;
  let p = [[-1, t, 0], [1, t, 0], [-1, -t, 0], [1, -t, 0], [0, -1, t], [0, 1, t],
    [0, -1, -t], [0, 1, -t], [t, 0, -1], [t, 0, 1], [-t, 0, -1], [-t, 0, 1]];
  let f = [[0, 11, 5], [0, 5, 1], [0, 1, 7], [0, 7, 10], [0, 10, 11], [1, 5, 9], [5, 11, 4], [11, 10, 2],
    [10, 7, 6], [7, 1, 8], [3, 9, 4], [3, 4, 2], [3, 2, 6], [3, 6, 8], [3, 8, 9], [4, 9, 5], [2, 4, 11],
    [6, 2, 10], [8, 6, 7], [9, 8, 1]];
  for (let l = 0; l < levels; ++l) {
    const mid = new Map();
    const m = (a, b) => {
      const key = a < b ? `${a},${b}` : `${b},${a}`;
      if (!mid.has(key)) {
        mid.set(key, p.length);
        p.push(p[a].map((x, c) => 0.5 * (x + p[b][c])));
      }
      return mid.get(key);
    };
    f = f.flatMap(([a, b, c]) => {
      const ab = m(a, b), bc = m(b, c), ca = m(c, a);
      return [[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]];
    });
  }
  p = p.map((v) => v.map((x) => x / Math.hypot(...v)));
  return `OFF\n# icosphere, ${levels} subdivisions\n${p.length} ${f.length} 0\n` +
    p.map((v) => v.join(' ')).join('\n') + '\n' + f.map((t3) => `3 ${t3.join(' ')}`).join('\n') + '\n';
}

// SPDX-License-Identifier: GPL-2.0-or-later
// The texture atlas synthesis runs in, from the core (core/texture/texture_atlas, wasm TextureAtlasBuilder):
// the model's own TEXCOORD_0 when it is a usable one-to-one atlas inside [0, 1]^2, otherwise a generated one
// (LSCM charts at one texel density, packed with a gutter; docs/texture-synthesis.md). rasterCoverage stays
// here for the seam indirection, which runs on the page.

// Counts, per texel centre of an n x n grid, the triangles covering it (half-open edge rule: a centre on an
// edge shared by two triangles is counted once). cornerUVs: 6 per face. Returns Uint16Array (saturating).
export function rasterCoverage(cornerUVs, n, faces = null) {
  const count = new Uint16Array(n * n);
  const total = faces ? faces.length : cornerUVs.length / 6;
  for (let i = 0; i < total; i++) {
    const f = faces ? faces[i] : i;
    let ax = cornerUVs[6 * f] * n, ay = cornerUVs[6 * f + 1] * n;
    let bx = cornerUVs[6 * f + 2] * n, by = cornerUVs[6 * f + 3] * n;
    let cx = cornerUVs[6 * f + 4] * n, cy = cornerUVs[6 * f + 5] * n;
    let area = (bx - ax) * (cy - ay) - (cx - ax) * (by - ay);
    if (!(Math.abs(area) > 1e-12)) continue;
    if (area < 0) [bx, by, cx, cy, area] = [cx, cy, bx, by, -area];
    const x0 = Math.max(0, Math.floor(Math.min(ax, bx, cx) - 0.5));
    const x1 = Math.min(n - 1, Math.ceil(Math.max(ax, bx, cx) - 0.5));
    const y0 = Math.max(0, Math.floor(Math.min(ay, by, cy) - 0.5));
    const y1 = Math.min(n - 1, Math.ceil(Math.max(ay, by, cy) - 0.5));
    // Edge function of p against edge (p0 -> p1); top-left rule for ties.
    const edge = (x0e, y0e, x1e, y1e, px, py) => {
      const e = (x1e - x0e) * (py - y0e) - (y1e - y0e) * (px - x0e);
      if (e !== 0) return e > 0;
      const dy = y1e - y0e, dx = x1e - x0e;
      return dy < 0 || (dy === 0 && dx > 0);
    };
    for (let y = y0; y <= y1; y++)
      for (let x = x0; x <= x1; x++) {
        const px = x + 0.5, py = y + 0.5;
        if (edge(ax, ay, bx, by, px, py) && edge(bx, by, cx, cy, px, py) && edge(cx, cy, ax, ay, px, py)) {
          const k = y * n + x;
          if (count[k] < 65535) count[k]++;
        }
      }
  }
  return count;
}

function withBuilder(Module, fn) {
  if (typeof Module?.TextureAtlasBuilder !== 'function')
    throw new Error('this build of the core has no TextureAtlasBuilder; rebuild it (npm run build:wasm)');
  const builder = new Module.TextureAtlasBuilder();
  try {
    return fn(builder);
  } finally {
    builder.delete();
  }
}

// Whether cornerUVs (6 per face) can serve as the synthesis atlas: {ok, reason, stats}.
export function checkAtlasUVs(Module, triangles, cornerUVs, { resolution = 512 } = {}) {
  const nF = triangles.length / 3;
  if (!cornerUVs || cornerUVs.length !== 6 * nF) return { ok: false, reason: 'the model has no TEXCOORD_0', stats: {} };
  const r = withBuilder(Module, (b) => JSON.parse(b.check(cornerUVs, nF, resolution)));
  const { usable, reason, ...stats } = r;
  return { ok: usable, reason, stats: { faces: nF, ...stats } };
}

// A generated atlas (core): {cornerUVs (6 per face), faceCharts, stats}. `gutter` texels of border that belong
// to each chart alone, at `resolution`.
export function generateAtlas(Module, positions, triangles, { resolution = 512, gutter = 3 } = {}) {
  return withBuilder(Module, (b) => {
    const err = b.generate(positions, triangles, resolution, gutter);
    if (err) throw new Error(`atlas generation failed: ${err}`);
    return {
      cornerUVs: Float32Array.from(b.cornerUVs()),
      faceCharts: Int32Array.from(b.faceCharts()),
      stats: JSON.parse(b.statsJson()),
    };
  });
}

// The atlas synthesis will use for a model: its TEXCOORD_0 when usable, else a generated one.
export function chooseAtlas(Module, { positions, triangles, cornerUVs }, { resolution = 512, gutter = 3 } = {}) {
  const check = checkAtlasUVs(Module, triangles, cornerUVs, { resolution });
  if (check.ok)
    return { cornerUVs: Float32Array.from(cornerUVs), source: 'TEXCOORD_0', reason: check.reason, stats: check.stats };
  const t0 = performance.now();
  const gen = generateAtlas(Module, positions, triangles, { resolution, gutter });
  return {
    cornerUVs: gen.cornerUVs,
    faceCharts: gen.faceCharts,
    source: 'generated',
    reason: `generated (${check.reason})`,
    stats: { ...gen.stats, check: check.stats, ms: performance.now() - t0 },
  };
}

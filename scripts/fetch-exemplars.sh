#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# fetch-exemplars.sh: real texture patterns for the exemplar-analysis tests, from Debian's gimp-data package
# (GIMP's tiling .pat patterns, GPL), converted to square power-of-two binary PPMs in an ignored folder.
# Nothing is installed and nothing is committed: the .deb is downloaded with apt-get into a temporary folder.
#
# Usage: scripts/fetch-exemplars.sh [OUT]   (default bench-data/exemplars; the native texture tests read it)
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
OUT=${1:-$ROOT/bench-data/exemplars}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
command -v apt-get >/dev/null || { echo "fetch-exemplars: apt-get not found (Debian/Ubuntu only)" >&2; exit 1; }
(cd "$TMP" && apt-get download gimp-data >&2)
dpkg-deb -x "$TMP"/gimp-data_*.deb "$TMP/x"
PAT=$(find "$TMP/x" -type d -name patterns | head -1)
[ -n "$PAT" ] || { echo "fetch-exemplars: no patterns folder in gimp-data" >&2; exit 1; }
mkdir -p "$OUT"
# GIMP .pat: big-endian header (header size, version, width, height, bytes per pixel, "GPAT", name), then pixels.
# Each pattern (they tile) is resampled as a whole, with wrap-around, to the largest power of two <= its shorter
# side, capped at 128 and at least 32 — so it still tiles — and written as P6.
node --input-type=module - "$PAT" "$OUT" <<'JS'
import { readdirSync, readFileSync, statSync, writeFileSync } from 'node:fs';
import { join, basename } from 'node:path';
const [dir, out] = process.argv.slice(2);
const walk = (d) => readdirSync(d).flatMap((f) => (statSync(join(d, f)).isDirectory() ? walk(join(d, f)) : [join(d, f)]));
let n = 0;
for (const file of walk(dir).filter((f) => f.endsWith('.pat')).sort()) {
  const b = readFileSync(file);
  if (b.toString('latin1', 20, 24) !== 'GPAT') continue;
  const header = b.readUInt32BE(0), w = b.readUInt32BE(8), h = b.readUInt32BE(12), bpp = b.readUInt32BE(16);
  if (![1, 2, 3, 4].includes(bpp) || b.length < header + w * h * bpp) continue;
  let size = 1;
  while (size * 2 <= Math.min(w, h, 128)) size *= 2;
  if (size < 32) continue;
  const px = (x, y, c) => {
    const o = header + (((y % h) + h) % h * w + (((x % w) + w) % w)) * bpp;
    return bpp >= 3 ? b[o + c] : b[o];
  };
  const img = Buffer.alloc(size * size * 3);
  for (let y = 0; y < size; y++)
    for (let x = 0; x < size; x++) {
      const sx = ((x + 0.5) * w) / size - 0.5, sy = ((y + 0.5) * h) / size - 0.5;
      const x0 = Math.floor(sx), y0 = Math.floor(sy), fx = sx - x0, fy = sy - y0;
      for (let c = 0; c < 3; c++) {
        const v = (px(x0, y0, c) * (1 - fx) + px(x0 + 1, y0, c) * fx) * (1 - fy) + (px(x0, y0 + 1, c) * (1 - fx) + px(x0 + 1, y0 + 1, c) * fx) * fy;
        img[3 * (y * size + x) + c] = Math.round(v);
      }
    }
  const name = basename(file, '.pat').replace(/[^A-Za-z0-9_-]+/g, '_');
  writeFileSync(join(out, `${name}.ppm`), Buffer.concat([Buffer.from(`P6\n${size} ${size}\n255\n`), img]));
  n++;
}
console.error(`fetch-exemplars: ${n} patterns written to ${out}`);
JS

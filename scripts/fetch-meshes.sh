#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# fetch-meshes.sh: real benchmark meshes from Debian's `libcgal-demo` package (CGAL's data/meshes/*.off,
# shipped inside /usr/share/doc/libcgal-dev/data.tar.gz), plus a ~1.25M-edge mesh made by two rounds of
# 1-to-4 midpoint subdivision of armadillo.off (scripts/subdivide-off.mjs), a ~1.8M-edge one of bunny00.off,
# and four low-poly curved models decimated from CGAL's (scripts/decimate-off.mjs).
#
# Usage: scripts/fetch-meshes.sh             # idempotent: does nothing when every mesh is already there
#        scripts/fetch-meshes.sh --fuzz-seeds # only the fuzzing seeds (see below), nothing else
# Output: bench-data/meshes/*.off (bench-data/ is git-ignored: never commit meshes)
#         bench-data/fuzz-seeds/{gltf,glb,off,obj,ply}/: seed corpora for scripts/fuzz.sh, from Debian's
#         `assimp-testmodels` (assimp's own test files, good and deliberately broken) and CGAL's small OFF meshes
# Needs: apt-get (download only; no root needed, nothing is installed), dpkg-deb, tar, node.
# The meshes keep their own licences (CGAL's data folder; see /usr/share/doc/libcgal-dev/copyright).

set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
DATA=$ROOT/bench-data
MESHES=$DATA/meshes
# Edge counts (from `tvf info`): homer 14.8k, knot2 17.3k, lion-head 25.0k, camel 29.3k, mannequin-devil 38.9k,
# man 52.5k, diplodocus 71.9k, armadillo 78.0k, bunny00 113.1k, refined_elephant 133.4k.
NAMES=(homer knot2 lion-head camel mannequin-devil man diplodocus armadillo bunny00 refined_elephant fandisk_large)
BIG=armadillo-sub2   # armadillo subdivided twice: 1,248,000 edges
BIGGER=bunny00-sub2  # bunny00 subdivided twice: 1,809,792 edges (the page's size limit, docs/benchmarks.md)

log() { printf '[fetch-meshes] %s\n' "$*" >&2; }
die() { printf '[fetch-meshes] ERROR: %s\n' "$*" >&2; exit 1; }

# Seeds for the libFuzzer harnesses: every file of the five formats up to 256 KB (larger ones only slow the
# fuzzer down), one folder per format. assimp's glTF samples with external buffers or textures are kept too:
# the loader must refuse them cleanly.
fuzz_seeds() {
  local SEEDS=$DATA/fuzz-seeds
  if [ -f "$SEEDS/.done" ]; then return 0; fi
  command -v apt-get >/dev/null || die "apt-get not found (the seeds come from Debian packages)"
  mkdir -p "$DATA/assimp" "$SEEDS"/{gltf,glb,off,obj,ply}
  local deb
  deb=$(ls "$DATA"/assimp/assimp-testmodels_*.deb 2>/dev/null | head -1 || true)
  if [ -z "$deb" ]; then
    log "downloading assimp-testmodels (~21 MB) into bench-data/assimp"
    (cd "$DATA/assimp" && apt-get download assimp-testmodels >&2) ||
      die "apt-get download assimp-testmodels failed (run 'apt-get update' first?)"
    deb=$(ls "$DATA"/assimp/assimp-testmodels_*.deb | head -1)
  fi
  rm -rf "$DATA/assimp/x"
  dpkg-deb -x "$deb" "$DATA/assimp/x"
  local f ext n=0
  while IFS= read -r -d '' f; do
    ext=${f##*.}
    ext=${ext,,}
    [ "$(stat -c %s "$f")" -le 262144 ] || continue
    cp "$f" "$SEEDS/$ext/assimp-$(echo "$f" | md5sum | cut -c1-12).$ext"
    n=$((n + 1))
  done < <(find "$DATA/assimp/x" -type f \( -iname '*.gltf' -o -iname '*.glb' -o -iname '*.off' -o -iname '*.obj' \
    -o -iname '*.ply' \) -print0)
  rm -rf "$DATA/assimp/x"
  # CGAL's small OFF meshes: every data/meshes/*.off of libcgal-demo under the size limit.
  mkdir -p "$DATA/cgal"
  deb=$(ls "$DATA"/cgal/libcgal-demo_*.deb 2>/dev/null | head -1 || true)
  if [ -z "$deb" ]; then
    log "downloading libcgal-demo (~24 MB) into bench-data/cgal"
    (cd "$DATA/cgal" && apt-get download libcgal-demo >&2) || die "apt-get download libcgal-demo failed"
    deb=$(ls "$DATA"/cgal/libcgal-demo_*.deb | head -1)
  fi
  rm -rf "$DATA/cgal/x" "$DATA/cgal/seeds"
  dpkg-deb -x "$deb" "$DATA/cgal/x"
  mkdir -p "$DATA/cgal/seeds"
  tar -xzf "$(find "$DATA/cgal/x" -name data.tar.gz | head -1)" -C "$DATA/cgal/seeds" --wildcards 'data/meshes/*.off'
  for f in "$DATA"/cgal/seeds/data/meshes/*.off; do
    [ "$(stat -c %s "$f")" -le 262144 ] && cp "$f" "$SEEDS/off/cgal-$(basename "$f")"
  done
  rm -rf "$DATA/cgal/x" "$DATA/cgal/seeds"
  touch "$SEEDS/.done"
  log "fuzz seeds: $n files from assimp-testmodels, $(ls "$SEEDS"/off/cgal-* 2>/dev/null | wc -l) from CGAL"
}

if [ "${1:-}" = "--fuzz-seeds" ]; then
  fuzz_seeds
  exit 0
fi

missing=()
for n in "${NAMES[@]}"; do [ -s "$MESHES/$n.off" ] || missing+=("$n"); done

if [ ${#missing[@]} -gt 0 ]; then
  command -v apt-get >/dev/null || die "apt-get not found (this script reads Debian's libcgal-demo package)"
  mkdir -p "$DATA/cgal" "$MESHES"
  deb=$(ls "$DATA"/cgal/libcgal-demo_*.deb 2>/dev/null | head -1 || true)
  if [ -z "$deb" ]; then
    log "downloading libcgal-demo (~24 MB) into bench-data/cgal"
    (cd "$DATA/cgal" && apt-get download libcgal-demo >&2) ||
      die "apt-get download libcgal-demo failed (run 'apt-get update' first?)"
    deb=$(ls "$DATA"/cgal/libcgal-demo_*.deb | head -1)
  fi
  rm -rf "$DATA/cgal/x"
  dpkg-deb -x "$deb" "$DATA/cgal/x"
  tarball=$(find "$DATA/cgal/x" -name data.tar.gz | head -1)
  [ -n "$tarball" ] || die "no data.tar.gz inside $deb"
  members=()
  for n in "${missing[@]}"; do members+=("data/meshes/$n.off"); done
  tar -xzf "$tarball" -C "$DATA/cgal" "${members[@]}"
  for n in "${missing[@]}"; do mv "$DATA/cgal/data/meshes/$n.off" "$MESHES/$n.off"; done
  rm -rf "$DATA/cgal/x" "$DATA/cgal/data"
  log "extracted: ${missing[*]}"
fi

# name base: two 1-to-4 subdivisions of base.off
for pair in "$BIG:armadillo" "$BIGGER:bunny00"; do
  name=${pair%%:*} base=${pair#*:}
  [ -s "$MESHES/$name.off" ] && continue
  command -v node >/dev/null || die "node not found (needed for scripts/subdivide-off.mjs)"
  log "making $name.off (two 1-to-4 subdivisions of $base.off)"
  node "$ROOT/scripts/subdivide-off.mjs" "$MESHES/$base.off" "$MESHES/$name.off.tmp" --levels 2 >&2
  mv "$MESHES/$name.off.tmp" "$MESHES/$name.off"
done

# A CAD model of about 100k faces for sharp features: fandisk_large (31,682 faces) split 1-to-4 once (flat
# subdivision keeps every crease).
if [ ! -s "$MESHES/fandisk-sub1.off" ]; then
  node "$ROOT/scripts/subdivide-off.mjs" "$MESHES/fandisk_large.off" "$MESHES/fandisk-sub1.off.tmp" --levels 1 >&2
  mv "$MESHES/fandisk-sub1.off.tmp" "$MESHES/fandisk-sub1.off"
fi

# Low-poly curved stand-ins (scripts/decimate-off.mjs, meshoptimizer's simplifier): the synthesized texture's
# defaults measured on coarse models (docs/texture-synthesis.md, "How the resolution and the feature size are
# chosen"); refined_elephant-5500 keeps its genus 3.
for pair in refined_elephant:5500 camel:6000 lion-head:7000 knot2:5000; do
  base=${pair%%:*} faces=${pair#*:}
  [ -s "$MESHES/$base-$faces.off" ] && continue
  node "$ROOT/scripts/decimate-off.mjs" "$MESHES/$base.off" "$MESHES/$base-$faces.off.tmp" "$faces" >&2
  mv "$MESHES/$base-$faces.off.tmp" "$MESHES/$base-$faces.off"
done

ls -1 "$MESHES"/*.off | sed "s|^$ROOT/||"

#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# fetch-meshes.sh: real benchmark meshes from Debian's `libcgal-demo` package (CGAL's data/meshes/*.off,
# shipped inside /usr/share/doc/libcgal-dev/data.tar.gz), plus a ~1.25M-edge mesh made by two rounds of
# 1-to-4 midpoint subdivision of armadillo.off (scripts/subdivide-off.mjs).
#
# Usage: scripts/fetch-meshes.sh        # idempotent: does nothing when every mesh is already there
# Output: bench-data/meshes/*.off (bench-data/ is git-ignored: never commit meshes)
# Needs: apt-get (download only; no root needed, nothing is installed), dpkg-deb, tar, node.
# The meshes keep their own licences (CGAL's data folder; see /usr/share/doc/libcgal-dev/copyright).

set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
DATA=$ROOT/bench-data
MESHES=$DATA/meshes
# Edge counts (from `tvf info`): homer 14.8k, knot2 17.3k, lion-head 25.0k, camel 29.3k, mannequin-devil 38.9k,
# man 52.5k, diplodocus 71.9k, armadillo 78.0k, bunny00 113.1k, refined_elephant 133.4k.
NAMES=(homer knot2 lion-head camel mannequin-devil man diplodocus armadillo bunny00 refined_elephant)
BIG=armadillo-sub2   # armadillo subdivided twice: 1,248,000 edges

log() { printf '[fetch-meshes] %s\n' "$*" >&2; }
die() { printf '[fetch-meshes] ERROR: %s\n' "$*" >&2; exit 1; }

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

if [ ! -s "$MESHES/$BIG.off" ]; then
  command -v node >/dev/null || die "node not found (needed for scripts/subdivide-off.mjs)"
  log "making $BIG.off (two 1-to-4 subdivisions of armadillo.off)"
  node "$ROOT/scripts/subdivide-off.mjs" "$MESHES/armadillo.off" "$MESHES/$BIG.off.tmp" --levels 2 >&2
  mv "$MESHES/$BIG.off.tmp" "$MESHES/$BIG.off"
fi

ls -1 "$MESHES"/*.off | sed "s|^$ROOT/||"

#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# build.sh: build the WebAssembly core, build-wasm/tvf_core.mjs + build-wasm/tvf_core.wasm (ES6 module,
# factory `createTvfCore`, runs in browsers, workers and node).
#
# Usage:
#   wasm/build.sh            # incremental; a rerun with nothing changed takes a few seconds
#   JOBS=4 wasm/build.sh     # parallel compile jobs (default: number of CPUs)
#   wasm/build.sh --clean    # drop build-wasm/core first (the CHOLMOD archive is kept)
#
# Steps: CHOLMOD via wasm/build-cholmod.sh (cached in build-wasm/cholmod), then the top-level CMake project
# configured with emcmake into build-wasm/core (Release, -O3 -msimd128 -fexceptions, Eigen from
# /usr/include/eigen3, nlohmann/tinygltf headers from /usr/include through a private include folder so that
# no other host header can leak into the wasm build), whose `tvf_core` target (wasm/CMakeLists.txt) links the
# module with embind. Prints the raw and gzipped size of the .wasm.

set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
OUT=$ROOT/build-wasm
BUILD=$OUT/core
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}
export NODE_PATH=${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs

log() { printf '[build-wasm] %s\n' "$*" >&2; }
die() { printf '[build-wasm] ERROR: %s\n' "$*" >&2; exit 1; }

for arg in "$@"; do
  case "$arg" in
    --clean) rm -rf "$BUILD" ;;
    -h|--help) sed -n '4,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -n 's/^# \{0,1\}//p' >&2; exit 0 ;;
    *) die "unknown argument: $arg (try --help)" ;;
  esac
done

command -v emcmake >/dev/null || die "emscripten not found (apt-get install emscripten, or npm run setup)"
command -v cmake >/dev/null || die "cmake not found"
[ -f /usr/include/eigen3/Eigen/Core ] || die "Eigen not found in /usr/include/eigen3 (apt-get install libeigen3-dev)"
[ -f /usr/include/nlohmann/json.hpp ] || die "nlohmann/json.hpp not found (apt-get install nlohmann-json3-dev)"
[ -f /usr/include/tiny_gltf.h ] || die "tiny_gltf.h not found (apt-get install libtinygltf-dev)"
[ -f /usr/include/stb/stb_image_write.h ] || die "stb_image_write.h not found (apt-get install libstb-dev)"
[ -f /usr/include/fast_float/fast_float.h ] || die "fast_float.h not found (apt-get install libfast-float-dev)"

start=$(date +%s.%N)

# Several sessions may run this at once (npm run build, tests): one build at a time in build-wasm/.
mkdir -p "$OUT"
if command -v flock >/dev/null; then
  exec 9>"$OUT/.build.lock"
  flock 9
fi

# 1. CHOLMOD for wasm (instant when cached).
CHOLMOD_WASM=$("$ROOT/wasm/build-cholmod.sh" | tail -1)
[ -f "$CHOLMOD_WASM/lib/libcholmod_wasm.a" ] || die "build-cholmod.sh gave no archive in $CHOLMOD_WASM"

# 2. Header-only dependencies, exposed one by one (never -I/usr/include: glibc headers must not shadow musl's).
INC=$OUT/include
mkdir -p "$INC"
ln -sfn /usr/include/nlohmann "$INC/nlohmann"
ln -sfn /usr/include/tiny_gltf.h "$INC/tiny_gltf.h"
ln -sfn /usr/include/stb "$INC/stb"  # stb_image_write for flow maps (libstb-dev)
ln -sfn /usr/include/fast_float "$INC/fast_float"  # number parsing for OFF/OBJ/PLY (libfast-float-dev)

# 3. Configure once (reconfigure only when the CHOLMOD folder changed or the cache is missing).
want="$CHOLMOD_WASM"
if [ ! -f "$BUILD/CMakeCache.txt" ] || [ "$(cat "$BUILD/.cholmod" 2>/dev/null)" != "$want" ]; then
  log "configuring $BUILD"
  emcmake cmake -S "$ROOT" -B "$BUILD" \
    -DCMAKE_BUILD_TYPE=Release \
    -DCMAKE_CXX_FLAGS="-isystem $INC" \
    -DCMAKE_CXX_FLAGS_RELEASE="-O3 -DNDEBUG" \
    -DEigen3_DIR=/usr/share/eigen3/cmake \
    -DCMAKE_FIND_ROOT_PATH_MODE_PACKAGE=BOTH \
    -DTVF_CHOLMOD_INCLUDE_DIR="$CHOLMOD_WASM/include" \
    -DTVF_CHOLMOD_LIBRARIES="$CHOLMOD_WASM/lib/libcholmod_wasm.a" \
    -DTVF_WASM_OUTPUT_DIR="$OUT" \
    -DCMAKE_CROSSCOMPILING_EMULATOR="$(command -v node)" >&2
  printf '%s\n' "$want" > "$BUILD/.cholmod"
fi

# 4. Build (make/ninja are incremental; the link reruns only when an object or the archive changed).
cmake --build "$BUILD" --target tvf_core -j "$JOBS" >&2

WASM=$OUT/tvf_core.wasm
[ -f "$WASM" ] && [ -f "$OUT/tvf_core.mjs" ] || die "the link produced no tvf_core.{mjs,wasm}"
raw=$(stat -c %s "$WASM")
gz=$(gzip -9 -c "$WASM" | wc -c)
js=$(stat -c %s "$OUT/tvf_core.mjs")
jsgz=$(gzip -9 -c "$OUT/tvf_core.mjs" | wc -c)
elapsed=$(echo "$(date +%s.%N) - $start" | bc)
printf '[build-wasm] %s: %d bytes (%.0f KiB), gzip -9 %d bytes (%.0f KiB)\n' \
  "${WASM#$ROOT/}" "$raw" "$(echo "$raw/1024" | bc -l)" "$gz" "$(echo "$gz/1024" | bc -l)" >&2
printf '[build-wasm] %s: %d bytes, gzip -9 %d bytes; done in %.1f s\n' \
  "build-wasm/tvf_core.mjs" "$js" "$jsgz" "$elapsed" >&2
limit=$((2 * 1024 * 1024))
[ "$gz" -le "$limit" ] || log "WARNING: the gzipped .wasm is over the 2 MiB budget"
echo "$OUT"

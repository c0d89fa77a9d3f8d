#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# build.sh: build the WebAssembly core, build-wasm/tvf_core.mjs + build-wasm/tvf_core.wasm (ES6 module,
# factory `createTvfCore`, runs in browsers, workers and node), and the same core with helper threads,
# build-wasm/tvf_core_threads.{mjs,wasm,worker.js} (cross-origin-isolated pages and node; see build_variant).
#
# Usage:
#   wasm/build.sh            # incremental; a rerun with nothing changed takes a few seconds
#   JOBS=4 wasm/build.sh     # parallel compile jobs (default: number of CPUs)
#   wasm/build.sh --clean    # drop build-wasm/core{,-threads} first (the CHOLMOD archives are kept)
#   wasm/build.sh --only plain|threads   # one of the two modules (default: both)
#
# Steps: CHOLMOD via wasm/build-cholmod.sh (cached in build-wasm/cholmod), then the top-level CMake project
# configured with emcmake into build-wasm/core and build-wasm/core-threads (Release, -O3 -msimd128 -fexceptions, the
# core compiled in batches (TVF_UNITY_CORE: Eigen parsed once a batch, and one em++ start each), Eigen from
# /usr/include/eigen3, nlohmann/tinygltf headers from /usr/include through a private include folder so that
# no other host header can leak into the wasm build), whose `tvf_core` target (wasm/CMakeLists.txt) links the
# module with embind. Prints the raw and gzipped size of the .wasm.

set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
OUT=$ROOT/build-wasm
JOBS=${JOBS:-$(nproc 2>/dev/null || echo 2)}
export NODE_PATH=${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs

log() { printf '[build-wasm] %s\n' "$*" >&2; }
die() { printf '[build-wasm] ERROR: %s\n' "$*" >&2; exit 1; }

VARIANTS="plain threads"
only=0
for arg in "$@"; do
  if [ "$only" = 1 ]; then
    case "$arg" in plain|threads) VARIANTS=$arg ;; *) die "--only takes plain or threads (got $arg)" ;; esac
    only=0
    continue
  fi
  case "$arg" in
    --clean) rm -rf "$OUT/core" "$OUT/core-threads" ;;
    --only) only=1 ;;
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

# One variant: $1 = plain | threads. plain: tvf_core.{mjs,wasm}, one thread, runs anywhere. threads:
# tvf_core_threads.{mjs,wasm,worker.js}, shared memory and up to 7 helper pthreads (PTHREAD_POOL_SIZE: the cores
# less one, wasm/node-pre.js; started with the module) for the factorization and the backward substitution;
# only cross-origin-isolated pages and node can run it
# (SharedArrayBuffer), so the page picks it when `crossOriginIsolated` and the plain one otherwise.
build_variant() {
  local variant=$1 build cholmod name extra
  if [ "$variant" = threads ]; then
    build=$OUT/core-threads name=tvf_core_threads extra="-pthread -DTVF_THREAD_HELPERS=7"
    cholmod=$("$ROOT/wasm/build-cholmod.sh" --threads | tail -1)
  else
    build=$OUT/core name=tvf_core extra=
    cholmod=$("$ROOT/wasm/build-cholmod.sh" | tail -1)
  fi
  [ -f "$cholmod/lib/libcholmod_wasm.a" ] || die "build-cholmod.sh gave no archive in $cholmod"

  # Configure once: again only when the cache is missing or the CHOLMOD folder, the flags or the settings changed
  # (the last word names them: "unity" since the core is compiled in batches).
  local want="$cholmod $extra unity"
  if [ ! -f "$build/CMakeCache.txt" ] || [ "$(cat "$build/.cholmod" 2>/dev/null)" != "$want" ]; then
    log "configuring $build"
    emcmake cmake -S "$ROOT" -B "$build" \
      -DCMAKE_BUILD_TYPE=Release \
      -DCMAKE_CXX_FLAGS="-isystem $INC $extra" \
      -DCMAKE_CXX_FLAGS_RELEASE="-O3 -DNDEBUG" \
      -DEigen3_DIR=/usr/share/eigen3/cmake \
      -DCMAKE_FIND_ROOT_PATH_MODE_PACKAGE=BOTH \
      -DTVF_CHOLMOD_INCLUDE_DIR="$cholmod/include" \
      -DTVF_CHOLMOD_LIBRARIES="$cholmod/lib/libcholmod_wasm.a" \
      -DTVF_WASM_OUTPUT_DIR="$OUT" \
      -DTVF_WASM_OUTPUT_NAME="$name" \
      -DTVF_WASM_THREADS="$([ "$variant" = threads ] && echo ON || echo OFF)" \
      -DTVF_UNITY_CORE=ON \
      -DCMAKE_CROSSCOMPILING_EMULATOR="$(command -v node)" >&2
    printf '%s\n' "$want" > "$build/.cholmod"
  fi

  # Build (make/ninja are incremental; the link reruns only when an object or the archive changed).
  cmake --build "$build" --target tvf_core -j "$JOBS" >&2

  local wasm=$OUT/$name.wasm
  [ -f "$wasm" ] && [ -f "$OUT/$name.mjs" ] || die "the link produced no $name.{mjs,wasm}"
  [ "$variant" = plain ] || [ -f "$OUT/$name.worker.js" ] || die "the link produced no $name.worker.js"
  local raw gz js jsgz
  raw=$(stat -c %s "$wasm")
  gz=$(gzip -9 -c "$wasm" | wc -c)
  js=$(stat -c %s "$OUT/$name.mjs")
  jsgz=$(gzip -9 -c "$OUT/$name.mjs" | wc -c)
  printf '[build-wasm] %s: %d bytes (%.0f KiB), gzip -9 %d bytes (%.0f KiB)\n' \
    "${wasm#$ROOT/}" "$raw" "$(echo "$raw/1024" | bc -l)" "$gz" "$(echo "$gz/1024" | bc -l)" >&2
  printf '[build-wasm] %s: %d bytes, gzip -9 %d bytes\n' "build-wasm/$name.mjs" "$js" "$jsgz" >&2
  local limit=$((2 * 1024 * 1024))
  [ "$gz" -le "$limit" ] || log "WARNING: the gzipped $name.wasm is over the 2 MiB budget"
}

# Header-only dependencies, exposed one by one (never -I/usr/include: glibc headers must not shadow musl's).
INC=$OUT/include
mkdir -p "$INC"
ln -sfn /usr/include/nlohmann "$INC/nlohmann"
ln -sfn /usr/include/tiny_gltf.h "$INC/tiny_gltf.h"
ln -sfn /usr/include/stb "$INC/stb"  # stb_image_write for flow maps (libstb-dev)
ln -sfn /usr/include/fast_float "$INC/fast_float"  # number parsing for OFF/OBJ/PLY (libfast-float-dev)

# tvf_core_threads.worker.js is a CommonJS script under node (worker_threads): the repository's package.json
# says "type": "module", so this folder says otherwise (the .mjs files stay ES modules by their extension).
printf '{ "type": "commonjs" }\n' > "$OUT/package.json"

for variant in $VARIANTS; do build_variant "$variant"; done
elapsed=$(echo "$(date +%s.%N) - $start" | bc)
printf '[build-wasm] done in %.1f s\n' "$elapsed" >&2
echo "$OUT"

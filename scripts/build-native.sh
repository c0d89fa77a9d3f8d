#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# The native build (`npm run build:native`): the core, `tvf` and the native tests in build/, linked against
# CHOLMOD compiled for this machine from Debian's source packages (wasm/build-cholmod.sh --native: the same
# sources as the wasm build). Where those sources cannot be had, it says so and links Debian's libcholmod3.
# Usage: scripts/build-native.sh [--target T]   (extra arguments go to `cmake --build`)
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
cd "$ROOT"

cholmod=()
if out=$(bash wasm/build-cholmod.sh --native | tail -n1) && [ -f "$out/lib/libcholmod_native.a" ]; then
  cholmod=(-DTVF_CHOLMOD_INCLUDE_DIR="$out/include" -DTVF_CHOLMOD_LIBRARIES="$out/lib/libcholmod_native.a;lapack;blas;m")
else
  echo "build-native: CHOLMOD could not be built from source here; linking the system's libcholmod3" >&2
  cholmod=(-DTVF_CHOLMOD_INCLUDE_DIR= -DTVF_CHOLMOD_LIBRARIES=)
fi
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
# The core compiled in batches (TVF_UNITY_CORE): 199 s -> 118 s here, its benchmarks within noise.
# The test files at -O1 (TVF_TEST_COMPILE_OPTIONS), the core they test at -O3: on the quiet 2-core machine their
# build took 146 s at -O3, 117 s at -O1 and 107 s at -O0, and the 301 tests ran in 30.0, 28.3 and 55.9 s.
cmake -S . -B build -DCMAKE_BUILD_TYPE=Release -DTVF_UNITY_CORE=ON -DTVF_TEST_COMPILE_OPTIONS=-O1 "${launcher[@]}" \
  "${cholmod[@]}" >/dev/null
cmake --build build -j2 "$@"

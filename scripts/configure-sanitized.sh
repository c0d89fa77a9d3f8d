#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Configures build-sanitized/, the one build that the bad-input tests under the sanitizers
# (scripts/test-native.sh) and the fuzzers (scripts/fuzz.sh) share, so that the core is compiled once for both:
# clang, AddressSanitizer + UBSan in every target, the core also with libFuzzer's coverage instrumentation
# (harmless to the tests and the CLI linked against it), assertions on (Eigen's and tinygltf's index checks are
# part of what the fuzzers look for), line tables for the sanitizers' stack traces, and the core compiled in
# batches. The core at -O1, everything else at -O0: measured on the quiet 2-core machine, the core took 146 s at
# -O1 (189 s with full -g, 85 s at -O0) and the tests 57 s at -O0 (94 s at -O1 -g); at -O0 the core made the
# fuzzers too slow to get past their seeds in their 10 s (the OFF target: 120 of CGAL's meshes in 24 s).
# Usage: scripts/configure-sanitized.sh [-DNAME=VALUE ...]   (extra settings, e.g. TVF_TEST_FILES); prints the folder.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
BUILD=$ROOT/build-sanitized
command -v clang++ >/dev/null || { echo "configure-sanitized: clang++ not found (npm run setup)" >&2; exit 2; }
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O0 -gline-tables-only" \
  -DTVF_CORE_COMPILE_OPTIONS=-O1 \
  -DTVF_SANITIZE=ON -DTVF_FUZZ=ON -DTVF_UNITY_CORE=ON "${launcher[@]}" "$@" >/dev/null
echo "$BUILD"

#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
# Configures build-sanitized/, the one build that the bad-input tests under the sanitizers
# (scripts/test-native.sh) and the fuzzers (scripts/fuzz.sh) share, so that the core is compiled once for both:
# clang, AddressSanitizer + UBSan in every target, the core also with libFuzzer's coverage instrumentation
# (harmless to the tests and the CLI linked against it), -O1 -g with assertions on (Eigen's and tinygltf's
# index checks are part of what the fuzzers look for), and the core compiled in batches.
# Usage: scripts/configure-sanitized.sh [-DNAME=VALUE ...]   (extra settings, e.g. TVF_TEST_FILES); prints the folder.
set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
BUILD=$ROOT/build-sanitized
command -v clang++ >/dev/null || { echo "configure-sanitized: clang++ not found (npm run setup)" >&2; exit 2; }
launcher=()
command -v ccache >/dev/null && launcher=(-DCMAKE_CXX_COMPILER_LAUNCHER=ccache)
CC=clang CXX=clang++ cmake -S "$ROOT" -B "$BUILD" -DCMAKE_BUILD_TYPE=Debug "-DCMAKE_CXX_FLAGS_DEBUG=-O1 -g" \
  -DTVF_SANITIZE=ON -DTVF_FUZZ=ON -DTVF_UNITY_CORE=ON "${launcher[@]}" "$@" >/dev/null
echo "$BUILD"

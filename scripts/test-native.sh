#!/usr/bin/env bash
# Native tests: the whole suite on the release build, then every bad-input test again under
# AddressSanitizer + UBSan, where a loader or check that reads out of bounds would show, then a bounded
# libFuzzer run (60 s over the five loaders and the design parser; scripts/fuzz.sh --seconds N for longer).
set -euo pipefail
cd "$(dirname "$0")/.."
ctest --test-dir build --output-on-failure -j2
cmake -S . -B build-asan -DCMAKE_BUILD_TYPE=Debug -DTVF_SANITIZE=ON > /dev/null
cmake --build build-asan -j2
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
  ctest --test-dir build-asan --output-on-failure -j2 \
  -R 'MeshIo|MeshChecks|Cli\.BadInput|Impossible|BadEntries|Robust|Fuzz|Truncat|Error'
bash scripts/fuzz.sh --seconds "${TVF_FUZZ_SECONDS:-60}"

#!/usr/bin/env bash
# Native tests: the whole suite on the release build, then every bad-input test (and the wasm build's dense
# kernels, solver/lane_kernels.h, whose vector loads run past an edge there first) again under
# AddressSanitizer + UBSan, where a loader or check that reads out of bounds would show, then a bounded
# libFuzzer run (60 s over the five loaders and the design parser; scripts/fuzz.sh --seconds N for longer).
# The tests and the fuzzers share one sanitizer build (scripts/configure-sanitized.sh), which compiles the core
# once for both, the CLI, and only the test files that hold the bad-input tests (found in the release build's
# list); it checks afterwards that it ran every one of them.
set -euo pipefail
cd "$(dirname "$0")/.."
SANITIZED='MeshIo|MeshChecks|Cli\.BadInput|Impossible|BadEntries|Robust|Fuzz|Truncat|Error|LaneKernels|SupernodalSolve|SymbolicAnalysis|FactorMemory|LdlConversion'
ctest --test-dir build --output-on-failure -j2

# The selected tests of a build tree, by name.
listed() { ctest --test-dir "$1" -N -R "$SANITIZED" | sed -n 's/^ *Test *#[0-9]*: //p' | sort; }
# The files that declare the selected tests (TEST/TEST_F/TEST_P(Suite, Name); a parameterized test's
# instances as Prefix/Suite.Name/N), or their suite where a macro names the test.
files=()
for test in $(listed build | sed -E 's/^([^/]*\/)?([A-Za-z0-9_]+)\.([A-Za-z0-9_]+).*/\2.\3/' | sort -u); do
  suite=${test%%.*} name=${test#*.}
  found=$(grep -lE "^(TEST|TEST_F|TEST_P)\(${suite}, *${name}\)" tests/native/*_test.cpp ||
    grep -lE "^(TEST|TEST_F|TEST_P)\(${suite}," tests/native/*_test.cpp || true)
  for f in $found; do files+=("$(basename "$f" _test.cpp)"); done
done
stems=$(printf '%s\n' "${files[@]}" | sort -u | paste -sd';')
[ -n "$stems" ] || { echo "test-native: no test file holds the sanitizer's tests" >&2; exit 1; }

sanitized=$(bash scripts/configure-sanitized.sh "-DTVF_TEST_FILES=$stems")
cmake --build "$sanitized" -j2 --target tvf_tests
ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
  ctest --test-dir "$sanitized" --output-on-failure -j2 -R "$SANITIZED"
if [ "$(listed build)" != "$(listed "$sanitized")" ]; then
  echo "test-native: the sanitizer build lacks some of the release build's bad-input tests:" >&2
  diff <(listed build) <(listed "$sanitized") >&2 || true
  exit 1
fi
# TVF_FUZZ_SECONDS=0: no fuzzing here (scripts/test-all.sh runs it at its own priority after this).
[ "${TVF_FUZZ_SECONDS:-60}" = 0 ] || bash scripts/fuzz.sh --seconds "${TVF_FUZZ_SECONDS:-60}"

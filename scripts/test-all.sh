#!/usr/bin/env bash
# Every test, after `npm run build` (the last step of `npm test`). Two chains run side by side:
# - the native tests (scripts/test-native.sh: ctest, the sanitizer build and its bad-input tests, 60 s of
#   fuzzing), compiler-bound, with their output in build/test-native.log, shown when they fail;
# - the wasm node tests, the export validation, the node unit tests and the browser tests (`npm run test:js`),
#   whose one Playwright worker with software GL keeps about one of two cores busy.
# Side by side they take the time of the longer one and a part of the other's, not the sum (docs/benchmarks.md,
# "The test suite's time"). Exits non-zero when either chain failed.
set -uo pipefail
cd "$(dirname "$0")/.."
mkdir -p build
log=build/test-native.log
start=$(date +%s)

# In a process group of its own (setsid), so that an interrupt ends all of it, compilers and ctest included.
setsid bash scripts/test-native.sh > "$log" 2>&1 &
native=$!
trap 'kill -TERM -- "-$native" 2>/dev/null; exit 130' INT TERM

npm run --silent test:js
js=$?
echo "test-all: the wasm, node and browser tests finished ($(($(date +%s) - start)) s); waiting for the native tests"
wait "$native"
nat=$?
if [ "$nat" -ne 0 ]; then
  echo "test-all: the native tests FAILED (exit $nat); their output, $log:"
  cat "$log"
else
  # ctest's summaries and the fuzzing's lines.
  grep -E 'tests passed|^\[fuzz\]' "$log"
fi
echo "test-all: done in $(($(date +%s) - start)) s (native tests: exit $nat; wasm, node and browser tests: exit $js)"
[ "$js" -eq 0 ] && [ "$nat" -eq 0 ]

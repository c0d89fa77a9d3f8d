#!/usr/bin/env bash
# Every test, after `npm run build` (the last step of `npm test`). Two chains run side by side:
# - the native tests (scripts/test-native.sh: ctest, the sanitizer build and its bad-input tests, 60 s of
#   fuzzing), compiler-bound, with their output in build/test-native.log, shown when they fail; then, on the
#   core they leave idle, a second runner of the browser tests;
# - the wasm node tests, the export validation and the node unit tests (`npm run test:js` without its
#   Playwright run), then the first runner of the browser tests, whose Playwright with software GL keeps about
#   one of two cores busy.
# The browser tests are one queue of spec files that both runners take from (scripts/e2e-queue.mjs), so that
# neither core idles while the other still has tests to run. Exits non-zero when any part failed.
set -uo pipefail
cd "$(dirname "$0")/.."
mkdir -p build
log=build/test-native.log
start=$(date +%s)
rm -f build/test-native.rc
node scripts/e2e-queue.mjs init || exit 1

# In a process group of its own (setsid), so that an interrupt ends all of it, compilers and ctest included.
setsid bash -c "bash scripts/test-native.sh > '$log' 2>&1; echo \$? > build/test-native.rc
  echo \"test-all: the native tests finished (\$((\$(date +%s) - $start)) s); a second browser-test runner starts\"
  node scripts/e2e-queue.mjs run --runner B --port 8193" &
native=$!
trap 'kill -TERM -- "-$native" 2>/dev/null; exit 130' INT TERM

js=0
node --disallow-code-generation-from-strings wasm/test-node.mjs || js=1
node --disallow-code-generation-from-strings wasm/test-node.mjs build-wasm/tvf_core_threads.mjs || js=1
node tests/node/export-validate.mjs || js=1
npm run --silent test:unit || js=1
echo "test-all: the wasm and node tests finished ($(($(date +%s) - start)) s); the browser tests' runner A starts"
node scripts/e2e-queue.mjs run --runner A --port 8191 || js=1
echo "test-all: runner A found the queue empty ($(($(date +%s) - start)) s); waiting for the native chain"
wait "$native"
node scripts/e2e-queue.mjs summary || js=1
nat=$(cat build/test-native.rc 2>/dev/null || echo 1)
if [ "$nat" -ne 0 ]; then
  echo "test-all: the native tests FAILED (exit $nat); their output, $log:"
  cat "$log"
else
  # ctest's summaries and the fuzzing's lines.
  grep -E 'tests passed|^\[fuzz\]' "$log"
fi
echo "test-all: done in $(($(date +%s) - start)) s (native tests: exit $nat; wasm, node and browser tests: exit $js)"
[ "$js" -eq 0 ] && [ "$nat" -eq 0 ]

#!/usr/bin/env bash
# Every test, after `npm run build` (the last step of `npm test`). Three lines of work run side by side:
# - the native tests (scripts/test-native.sh: ctest, the sanitizer build and its bad-input tests) at a lower
#   priority (nice), then 60 s of fuzzing at the normal one (two targets at a time), with their output in
#   build/test-native.log, shown when they fail;
# - a browser-test runner from the start;
# - the wasm node tests, the export validation and the node unit tests (`npm run test:js` without its
#   Playwright run), then a second browser-test runner.
# The browser tests are the longest line of work: a runner keeps about 1.4 cores busy (its page and the core's
# worker, SwiftShader's GL, the test process; views.spec.mjs: 35 s of CPU in 24.5 s), so they have the cores
# first and the compiling takes what they leave, instead of the browser tests waiting for a core the compiler
# holds. The fuzzing runs for a fixed time, so it must not wait: niced under two runners it made a few hundred
# executions a target where it makes thousands.
# The browser tests are one queue of spec files that both runners take from (scripts/e2e-queue.mjs), so that
# neither idles while the other still has tests to run. Each line says when it ended and the CPU seconds of the
# processes it waited for (a runner's count misses most of Chromium's, whose processes its launcher does not
# wait for). Exits non-zero when any part failed.
set -uo pipefail
cd "$(dirname "$0")/.."
mkdir -p build
export TEST_ALL_LOG=build/test-native.log TEST_ALL_START=$(date +%s)
rm -f build/test-native.rc
node scripts/e2e-queue.mjs init || exit 1

# "<what> (<s> s, <cpu> s of CPU)": the time since the start, and the user + system time of the calling
# shell's finished children (/proc/PID/stat's cutime and cstime, in clock ticks).
ended() {
  local ticks
  ticks=$(awk -v hz="$(getconf CLK_TCK)" '{ sub(/^.*\) /, ""); printf "%.0f", ($14 + $15) / hz }' "/proc/$1/stat")
  echo "test-all: $2 ($(($(date +%s) - TEST_ALL_START)) s, $ticks s of CPU)"
}
native_chain() {
  nice -n 10 env TVF_FUZZ_SECONDS=0 bash scripts/test-native.sh > "$TEST_ALL_LOG" 2>&1 &&
    nice -n 10 bash scripts/fuzz.sh --build-only >> "$TEST_ALL_LOG" 2>&1 &&
    bash scripts/fuzz.sh --seconds "${TVF_FUZZ_SECONDS:-60}" --jobs 2 >> "$TEST_ALL_LOG" 2>&1
  echo $? > build/test-native.rc
  ended $$ "the native tests finished"
}
runner_b() {
  node scripts/e2e-queue.mjs run --runner B --port 8193
  ended $$ "runner B found the queue empty"
}
export -f ended native_chain runner_b

# Each in a process group of its own (setsid), so that an interrupt ends all of it, compilers and ctest included.
setsid bash -c native_chain &
native=$!
setsid bash -c runner_b &
runnerB=$!
trap 'kill -TERM -- "-$native" "-$runnerB" 2>/dev/null; exit 130' INT TERM

js=0
node --disallow-code-generation-from-strings wasm/test-node.mjs || js=1
node --disallow-code-generation-from-strings wasm/test-node.mjs build-wasm/tvf_core_threads.mjs || js=1
node tests/node/export-validate.mjs || js=1
npm run --silent test:unit || js=1
ended $$ "the wasm and node tests finished; the browser tests' runner A starts"
node scripts/e2e-queue.mjs run --runner A --port 8191 || js=1
ended $$ "runner A found the queue empty"
wait "$runnerB"
wait "$native"
node scripts/e2e-queue.mjs summary || js=1
nat=$(cat build/test-native.rc 2>/dev/null || echo 1)
if [ "$nat" -ne 0 ]; then
  echo "test-all: the native tests FAILED (exit $nat); their output, $TEST_ALL_LOG:"
  cat "$TEST_ALL_LOG"
else
  # ctest's summaries and the fuzzing's lines.
  grep -E 'tests passed|^\[fuzz\]' "$TEST_ALL_LOG"
fi
echo "test-all: done in $(($(date +%s) - TEST_ALL_START)) s (native tests: exit $nat; wasm, node and browser" \
  "tests: exit $js)"
[ "$js" -eq 0 ] && [ "$nat" -eq 0 ]

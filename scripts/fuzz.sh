#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# fuzz.sh: builds the libFuzzer harnesses (tests/fuzz, clang + ASan + UBSan, in build-sanitized/, which the
# sanitizer's tests share: scripts/configure-sanitized.sh) and runs each for its share of the time: the glTF, GLB,
# OFF, OBJ and PLY loaders and the design-JSON parser.
#
# Usage: scripts/fuzz.sh [--seconds N] [--jobs J] [--build-only] [target ...]
#   --seconds N   total fuzzing time, split evenly over the targets (default 60)
#   --jobs J      targets fuzzed at a time (default 1): J cores for N / J seconds
#   --build-only  build the harnesses and stop (scripts/test-all.sh builds them at a low priority first)
#   target        gltf glb off obj ply design (default: all)
# Seeds: tests/fuzz/seeds/<target>/ (small files of our own), tests/native/data/, and bench-data/fuzz-seeds/
# (assimp's test models and CGAL's small meshes, fetched by scripts/fetch-meshes.sh --fuzz-seeds; without
# network the run goes on with the other seeds). The growing corpus lives in build-sanitized/corpus/<target>/.
# Findings: libFuzzer writes the input to build-sanitized/findings/<target>/ and the script exits 1; turn each
# into a regression test in tests/native (see io_test.cpp / robust_test.cpp) before fixing it.
# Prints one line per target: executions, corpus size, findings.

set -euo pipefail
ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
BUILD=$ROOT/build-sanitized
SECONDS_TOTAL=60
TARGETS=()
JOBS=1
BUILD_ONLY=0

log() { printf '[fuzz] %s\n' "$*" >&2; }
die() { printf '[fuzz] ERROR: %s\n' "$*" >&2; exit 2; }

while [ $# -gt 0 ]; do
  case "$1" in
    --seconds) SECONDS_TOTAL=${2:?--seconds needs a number}; shift 2 ;;
    --jobs) JOBS=${2:?--jobs needs a number}; shift 2 ;;
    --build-only) BUILD_ONLY=1; shift ;;
    -h|--help) sed -n '4,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -n 's/^# \{0,1\}//p' >&2; exit 0 ;;
    gltf|glb|off|obj|ply|design) TARGETS+=("$1"); shift ;;
    *) die "unknown argument: $1 (try --help)" ;;
  esac
done
[ ${#TARGETS[@]} -gt 0 ] || TARGETS=(gltf glb off obj ply design)

command -v clang++ >/dev/null || die "clang++ not found (apt-get install clang libclang-rt-14-dev, or npm run setup)"

# Seeds from Debian's assimp-testmodels and CGAL's data; a machine without network still fuzzes from ours.
bash "$ROOT/scripts/fetch-meshes.sh" --fuzz-seeds >/dev/null 2>&1 || log "no assimp/CGAL seeds (offline?); using the project's own"

# Configured once; scripts/test-native.sh configures it first, with the test files it needs.
[ -f "$BUILD/CMakeCache.txt" ] || bash "$ROOT/scripts/configure-sanitized.sh" >/dev/null
targets=()
for t in "${TARGETS[@]}"; do targets+=("fuzz_$t"); done
cmake --build "$BUILD" -j2 --target "${targets[@]}" >/dev/null
[ "$BUILD_ONLY" = 0 ] || exit 0

per=$((SECONDS_TOTAL / ${#TARGETS[@]}))
[ "$per" -ge 1 ] || per=1

# One target's run; its line, ending in "ok" or naming the finding, goes to $BUILD/fuzz-$t.line.
fuzz_one() {
  local t=$1 corpus=$BUILD/corpus/$1 findings=$BUILD/findings/$1 seeds existing=() logfile result runs
  mkdir -p "$corpus" "$findings"
  seeds=("$ROOT/tests/fuzz/seeds/$t")
  case "$t" in
    off) seeds+=("$ROOT/bench-data/fuzz-seeds/off") ;;
    obj) seeds+=("$ROOT/bench-data/fuzz-seeds/obj") ;;
    ply) seeds+=("$ROOT/bench-data/fuzz-seeds/ply") ;;
    gltf) seeds+=("$ROOT/bench-data/fuzz-seeds/gltf") ;;
    glb) seeds+=("$ROOT/bench-data/fuzz-seeds/glb" "$ROOT/bench-data/fuzz-seeds/gltf") ;;
  esac
  for s in "${seeds[@]}"; do [ -d "$s" ] && existing+=("$s"); done
  if [ "$t" = off ] || [ "$t" = obj ]; then existing+=("$ROOT/tests/native/data"); fi
  logfile=$BUILD/fuzz-$t.log
  # -timeout: one input taking longer than 10 s is a hang (a finding); -rss_limit_mb bounds a runaway parse.
  if ASAN_OPTIONS=detect_leaks=1:abort_on_error=1 UBSAN_OPTIONS=halt_on_error=1:print_stacktrace=1 \
    "$BUILD/tests/fuzz/fuzz_$t" -max_total_time="$per" -timeout=10 -rss_limit_mb=2048 -max_len=262144 \
    -artifact_prefix="$findings/" -print_final_stats=1 "$corpus" "${existing[@]}" >"$logfile" 2>&1; then
    result=ok
  else
    result="FINDING (see $logfile and $findings/)"
  fi
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "$logfile" | grep -o '[0-9]*$' || echo '?')
  printf '[fuzz] %-6s %ss  %s executions  corpus %s files  %s\n' "$t" "$per" "$runs" \
    "$(ls "$corpus" | wc -l)" "$result" > "$BUILD/fuzz-$t.line"
}

# JOBS targets at a time; the lines in the targets' order, a finding's saying so.
for t in "${TARGETS[@]}"; do rm -f "$BUILD/fuzz-$t.line"; done
for t in "${TARGETS[@]}"; do
  while [ "$(jobs -rp | wc -l)" -ge "$JOBS" ]; do wait -n || true; done
  fuzz_one "$t" &
done
wait
status=0
for t in "${TARGETS[@]}"; do
  if [ -f "$BUILD/fuzz-$t.line" ]; then cat "$BUILD/fuzz-$t.line"; else echo "[fuzz] $t: no result"; status=1; fi
  grep -q ' ok$' "$BUILD/fuzz-$t.line" 2>/dev/null || status=1
done
exit $status

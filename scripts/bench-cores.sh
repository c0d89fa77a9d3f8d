#!/usr/bin/env bash
# How the core's factorization and edits scale with the machine's cores, on bunny00 and armadillo-sub2: natively
# (`tvf bench --threads N`: the factorization's subtrees and the backward substitution on N threads, OpenBLAS on N)
# at 1, 2, 4, 8 and 16 threads, and in wasm under node (wasm/bench.mjs) at the same counts up to the module's
# (the module with pthreads has one helper fewer than the cores, at most 7: up to 8 threads). Prints one JSON
# object {machine, rows: [{mesh, edges, build, threads, groups (the factorization's groups of subtrees), analyzeMs,
# dissectionMs, factorMs, solveMs, updateMs, strokeUpdateSolveMs}]} (medians over the repeats) and writes it to
# bench-data/bench-cores.json.
# Each run's result is also kept as it comes, a line of bench-data/bench-cores.jsonl (and on stderr), so that a
# run stopped early (a lent machine's time running out: the whole set took over 400 s on a 16-core one) still
# leaves what it measured; a run that fails is named on stderr and the others go on.
# Both benches run with --scaling: the factorization, solves, updates and strokes alone (`tvf bench`'s singularity
# edits, plain CHOLMOD's baseline and the threads' field check each refactor; on the 16-core machine they made an
# armadillo-sub2 run about 150 s); --full runs them too.
#   bash scripts/bench-cores.sh [--threads "1 2 4 8 16"] [--repeat N] [--big-repeat N] [--tvf PATH] [--no-wasm]
#                               [--full]
# Run it on the biggest machine at hand; docs/benchmarks.md ("Every core") records the tables with the machine.
set -euo pipefail
cd "$(dirname "$0")/.."
threads="1 2 4 8 16" repeat=5 big_repeat=2 tvf=build/tvf wasm=1 scaling=--scaling
while [ $# -gt 0 ]; do
  case $1 in
    --threads) threads=$2; shift 2 ;;
    --repeat) repeat=$2; shift 2 ;;
    --big-repeat) big_repeat=$2; shift 2 ;;
    --tvf) tvf=$2; shift 2 ;;
    --no-wasm) wasm=0; shift ;;
    --full) scaling=; shift ;;
    *) echo "bench-cores: unknown option $1" >&2; exit 2 ;;
  esac
done
m=bench-data/meshes
[ -f $m/bunny00.off ] && [ -f $m/armadillo.off ] || bash scripts/fetch-meshes.sh >&2
[ -f $m/armadillo-sub2.off ] || node scripts/subdivide-off.mjs $m/armadillo.off $m/armadillo-sub2.off --levels 2 >&2
mkdir -p bench-data; rows=bench-data/bench-cores.jsonl; : > "$rows"
keep() { tee -a "$rows" >&2; }
cores=$(nproc); wasm_max=$(( cores < 8 ? cores : 8 ))
for mesh in bunny00 armadillo-sub2; do
  r=$repeat; [ $mesh = armadillo-sub2 ] && r=$big_repeat
  for n in $threads; do
    echo "bench-cores: $mesh native, $n thread(s)" >&2
    OPENBLAS_NUM_THREADS=$n "$tvf" bench $m/$mesh.off --json --repeat "$r" --threads "$n" $scaling |
      node -e 'let s="";process.stdin.on("data",d=>s+=d).on("end",()=>console.log(JSON.stringify({...JSON.parse(s),
        build:"native",meshName:process.argv[1]})))' $mesh | keep || echo "bench-cores: $mesh native, $n failed" >&2
  done
  [ $wasm = 1 ] || continue
  for n in $threads; do
    [ "$n" -le $wasm_max ] || continue
    echo "bench-cores: $mesh wasm, $n thread(s)" >&2
    node wasm/bench.mjs --json --no-native --threads "$n" --repeat "$r" --big-repeat "$r" $scaling \
      $m/$mesh.off |
      node -e 'let s="";process.stdin.on("data",d=>s+=d).on("end",()=>{const j=JSON.parse(s);
        console.log(JSON.stringify({...j.wasm,edges:j.edges,threads:j.wasm.threads,build:"wasm",meshName:process.argv[1]}))})' \
        $mesh | keep || echo "bench-cores: $mesh wasm, $n failed" >&2
  done
done
node -e '
const fs = require("fs"), os = require("os");
const keys = ["analyzeMs", "dissectionMs", "factorMs", "solveMs", "updateMs", "strokeUpdateSolveMs"];
const rows = fs.readFileSync(process.argv[1], "utf8").trim().split("\n").map((l) => JSON.parse(l)).map((j) =>
  ({ mesh: j.meshName, edges: j.edges, build: j.build, threads: j.threads, groups: j.factorGroups ?? null,
     ...Object.fromEntries(keys.map((k) => [k, j[k] == null ? null : Math.round(100 * j[k]) / 100])) }));
const machine = { cpus: os.cpus().length, model: os.cpus()[0]?.model, node: process.version };
const out = JSON.stringify({ date: new Date().toISOString(), machine, rows }, null, 1);
fs.mkdirSync("bench-data", { recursive: true });
fs.writeFileSync("bench-data/bench-cores.json", out);
console.log(out);' "$rows"

#!/usr/bin/env bash
# The page's benchmarks on a machine with a GPU (docs/benchmarks.md, "The page on a GPU"): the synthesis kernel,
# bunny00's and armadillo-sub2's strokes and textures on the hardware renderer, then bunny00's on SwiftShader on the
# same machine. Each result names the renderer the page got. Run in the project
# (dist/ built, bench-data/meshes fetched), with TVF_CHROMIUM and the GPU's environment set as
# scripts/gpu-page/remote.sh b sets them:  bash scripts/bench-gpu.sh [OUT_DIR]   (default bench-data/gpu)
set -uo pipefail
cd "$(dirname "$0")/.."; out=${1:-bench-data/gpu}; mkdir -p "$out"; m=bench-data/meshes
run() { # NAME SECONDS ARGS...: one benchmark, its JSON to OUT/NAME.json, its log to OUT/NAME.log
  local name=$1 secs=$2; shift 2; local t0=$SECONDS
  timeout "$secs" node scripts/bench-web.mjs "$@" > "$out/$name.json" 2> "$out/$name.log"
  echo "bench-gpu: $name rc=$? in $((SECONDS - t0)) s"
}
[ -f $m/armadillo-sub2.off ] || node scripts/subdivide-off.mjs $m/armadillo.off $m/armadillo-sub2.off --levels 2
t0=$SECONDS; timeout 120 node scripts/bench-web.mjs --gpu --sizes 512,1024 > "$out/sizes.txt" 2>&1
echo "bench-gpu: sizes rc=$? in $((SECONDS - t0)) s"; cat "$out/sizes.txt"
run bunny00-gpu 150 --gpu --json --stroke $m/bunny00.off --strokes 5 --texture 5 --reopen
run armadillo-sub2-gpu 240 --gpu --json --stroke $m/armadillo-sub2.off --strokes 3 --texture 3 --reopen
# SwiftShader: the variables that send ANGLE's Vulkan to the GPU's driver would override its own.
(unset VK_ICD_FILENAMES VK_DRIVER_FILES; run bunny00-swiftshader 150 --json --stroke $m/bunny00.off --strokes 5 --texture 5)
for f in "$out"/*.json; do echo "== $f"; head -c 6000 "$f"; echo; done

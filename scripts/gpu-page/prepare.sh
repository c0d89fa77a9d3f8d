#!/usr/bin/env bash
# Lays out what the page needs on a remote GPU machine that has no browser and no node, and takes at most 64 MiB
# per command (the device tool's limit): .gpu/a1 and .gpu/a2 carry the two halves of Debian's
# chromium-headless-shell package (61 MiB alone), .gpu/b node, the shell's libraries, fonts and the built project.
# On the remote machine, three commands issued one right after the other (it keeps /opt between them only while
# warm): `bash .gpu/a1/remote.sh a1`, `bash .gpu/a2/remote.sh a2`, `bash .gpu/b/remote.sh b COMMAND...`, each with
# its folder carried. docs/benchmarks.md (the GPU table) says what was run that way.
# Run from the project's root after `npm run build` (and scripts/fetch-meshes.sh for the benchmark's meshes).
# With --cores, .gpu/c alone: node, the native `tvf` with its libraries, the wasm build and the two meshes of
# scripts/bench-cores.sh, for one command on the same kind of machine: `bash .gpu/c/remote.sh c COMMAND...`.
set -euo pipefail
if [ "${1:-}" = --cores ]; then
  root=$(git rev-parse --show-toplevel); cd "$root"; here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
  mkdir -p .git/info; grep -qx '/.gpu/' .git/info/exclude 2>/dev/null || echo '/.gpu/' >> .git/info/exclude
  rm -rf .gpu/c; mkdir -p .gpu/c; t=$(mktemp -d); trap 'rm -rf "$t"' EXIT
  p=$t/pack; mkdir -p "$p/lib" "$p/proj/build" "$p/proj/bench-data/meshes" "$p/proj/wasm" "$p/proj/scripts"
  for l in $(ldd build/tvf | awk '$3 ~ /^\// {print $3}'); do
    case $(basename "$l") in libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*) ;; *) cp -L "$l" "$p/lib/";; esac
  done
  mkdir -p "$p/proj/build-wasm"; cp build/tvf "$p/proj/build/"
  cp build-wasm/*.mjs build-wasm/*.js build-wasm/*.wasm build-wasm/package.json "$p/proj/build-wasm/"
  cp package.json "$p/proj/"; cp wasm/bench.mjs wasm/quad-bench.mjs "$p/proj/wasm/"
  cp scripts/bench-cores.sh scripts/bench.mjs scripts/subdivide-off.mjs "$p/proj/scripts/"
  cp bench-data/meshes/{bunny00,armadillo}.off "$p/proj/bench-data/meshes/"
  (cd "$p" && tar cf - . | xz -T2 -6 > "$root/.gpu/c/c.tar.xz"); xz -6 -T2 -c "$(command -v node)" > .gpu/c/node.xz
  cp "$here/remote.sh" .gpu/c/remote.sh; du -sh .gpu/c; exit 0
fi
root=$(git rev-parse --show-toplevel); cd "$root"; here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
mkdir -p .git/info; grep -qx '/.gpu/' .git/info/exclude 2>/dev/null || echo '/.gpu/' >> .git/info/exclude
rm -rf .gpu; mkdir -p .gpu/a1 .gpu/a2 .gpu/b; t=$(mktemp -d); trap 'rm -rf "$t"' EXIT
(cd "$t" && apt-get download chromium-headless-shell chromium-common >/dev/null 2>&1)
deb=$(ls "$t"/chromium-headless-shell_*.deb); half=$(( ($(stat -c %s "$deb") + 1) / 2 ))
head -c "$half" "$deb" > .gpu/a1/part; tail -c +$((half + 1)) "$deb" > .gpu/a2/part
for d in a1 a2 b; do cp "$here/remote.sh" .gpu/$d/remote.sh; done
dpkg -x "$deb" "$t/shell"; dpkg -x "$t"/chromium-common_*.deb "$t/common"
p=$t/pack; mkdir -p "$p/lib" "$p/chs/locales" "$p/fonts" "$p/proj/node_modules" "$p/proj/bench-data"
# The shell's libraries as ldd finds them here, but not the C library's own (the remote machine has those), and
# the ones loaded by name at run time (NSS, glvnd's EGL).
for l in $(ldd "$t/shell/usr/lib/chromium/chromium-headless-shell" | awk '$3 ~ /^\// {print $3}'); do
  case $(basename "$l") in libc.so*|libm.so*|libdl.so*|libpthread.so*|librt.so*|ld-linux*) ;; *) cp -L "$l" "$p/lib/";; esac
done
cp -L /usr/lib/x86_64-linux-gnu/nss/*.so /usr/lib/x86_64-linux-gnu/libEGL.so.1 \
  /usr/lib/x86_64-linux-gnu/libGLdispatch.so.0 "$p/lib/" 2>/dev/null || true
c=$t/common/usr/lib/chromium
cp "$c"/{icudtl.dat,v8_context_snapshot.bin,snapshot_blob.bin,libvulkan.so.1,libvk_swiftshader.so,vk_swiftshader_icd.json} "$p/chs/"
cp "$c/locales/en-US.pak" "$p/chs/locales/"
cp $(fc-list | grep -i 'DejaVuSans' | head -3 | cut -d: -f1) "$p/fonts/"
cp -r dist scripts package.json "$p/proj/"; rm -f "$p"/proj/dist/*.map
mkdir -p "$p/proj/tests"; cp -r tests/e2e "$p/proj/tests/"  # the benchmark takes its strokes from helpers.mjs
cp -r node_modules/@playwright node_modules/playwright node_modules/playwright-core "$p/proj/node_modules/"
# The meshes but the subdivided ones (scripts/bench-gpu.sh makes those there, in a second).
if [ -d bench-data/meshes ]; then
  mkdir -p "$p/proj/bench-data/meshes"; cp bench-data/meshes/*.off "$p/proj/bench-data/meshes/"
  rm -f "$p"/proj/bench-data/meshes/*-sub[0-9].off
fi
(cd "$p" && tar cf - . | xz -T2 -6 > "$root/.gpu/b/b.tar.xz"); xz -6 -T2 -c "$(command -v node)" > .gpu/b/node.xz
du -sh .gpu/a1 .gpu/a2 .gpu/b

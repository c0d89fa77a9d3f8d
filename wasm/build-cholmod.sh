#!/usr/bin/env bash
# SPDX-License-Identifier: GPL-2.0-or-later
#
# build-cholmod.sh: build CHOLMOD (SuiteSparse) with METIS + a BLAS/LAPACK (Eigen's C++ one) as ONE static
# WebAssembly archive with Debian's emscripten, from Debian's own source packages.
#
# Usage:
#   CHOLMOD_WASM=$(wasm/build-cholmod.sh | tail -1)     # build once; later runs are instant
#   wasm/build-cholmod.sh --smoke                       # build (if needed), then run wasm/cholmod-smoke.c under node
#   wasm/build-cholmod.sh --refresh                     # re-read the archive's Sources index (new Debian revision?)
#   JOBS=4 wasm/build-cholmod.sh                        # parallel compile jobs (default 2)
#   CHOLMOD_NATIVE=$(wasm/build-cholmod.sh --native | tail -1)   # the same sources built for this machine (below)
#   CHOLMOD_THREADS=$(wasm/build-cholmod.sh --threads | tail -1) # the wasm archive for shared memory (below)
# The last line on stdout is the absolute path of the output folder; all progress goes to stderr.
#
# Output (ignored: build-wasm/ matches build-*/ in .gitignore):
#   build-wasm/cholmod/suitesparse-<deb version>_eigen3-<deb version>_metis-<deb version>_r<recipe>/
#     include/   cholmod.h, cholmod_*.h, SuiteSparse_config.h, amd.h, camd.h, colamd.h, ccolamd.h, metis.h
#                (cholmod_blas.h is a patched copy, see below)
#     lib/libcholmod_wasm.a   SuiteSparse_config + AMD + CAMD + COLAMD + CCOLAMD + CHOLMOD (int32 API, cholmod_*)
#                             + METIS 5.1 with its GKlib (idx_t 32-bit, as Debian's libmetis5)
#                             + Eigen BLAS (double, xerbla) + Eigen LAPACK potrf/potrs (d) + complex stand-ins
#     versions   the source package versions and flags used
#     stamp      written last; its presence (with the current recipe number) means "complete"
#   build-wasm/cholmod/current  name of the last completed folder (the instant path of a rerun reads only this)
#   build-wasm/cholmod-work/    scratch: private apt lists/cache, downloaded sources, extracted trees, objects, smoke
# Consumers: emcc -I$CHOLMOD_WASM/include ... $CHOLMOD_WASM/lib/libcholmod_wasm.a   (plain C; C++ consumers need
# no extra runtime: the Eigen objects are C++ but em++/emcc links libc++ as needed, link with em++ to be safe).
#
# Notes / caveats:
# * Sources: `apt-get source --download-only` + `dpkg-source -x` of Debian's `suitesparse`, `metis` and `eigen3`
#   source packages (bookworm: 1:5.12.0+dfsg-2, 5.1.0.dfsg-7 and 3.4.0-4), through a PRIVATE deb-src list derived at run time from the
#   machine's /etc/apt/sources.list.d/debian.sources (Types: deb -> deb-src) or /etc/apt/sources.list (deb -> deb-src).
#   apt runs with Dir::Etc::SourceList=/dev/null, Dir::Etc::SourceParts, Dir::State::Lists and Dir::Cache all
#   pointing into build-wasm/cholmod-work/apt, so the system's apt state is untouched. If the update fails with
#   the security stanza, it is retried with the non-security stanzas only.
# * Flags: C with emcc -O3 -DNDEBUG -msimd128; AMD/CAMD with -DDINT (int variants only, like the
#   Makefiles' amd_i_*.o); CHOLMOD modules Core, Check, Cholesky, MatrixOps, Modify, Supernodal, Partition
#   (cholmod_*.c, never t_*.c), Partition with METIS (cholmod_metis.c: METIS_NodeND; cholmod_nesdis.c: CHOLMOD's
#   own nested dissection over METIS_ComputeVertexSeparator, with CAMD/CCOLAMD for the constrained orderings).
#   METIS: GKlib/*.c and libmetis/*.c with the flags of METIS's own CMake build on Linux (-DLINUX
#   -D_FILE_OFFSET_BITS=64 -std=c99 -fno-strict-aliasing -DNDEBUG -DNDEBUG2). Only the int32 API (cholmod_*) is
#   built, no cholmod_l_*.
# * BLAS/LAPACK: Eigen's blas/{double,xerbla}.cpp; for LAPACK only lapack/cholesky.cpp (dpotrf_, dpotrs_) is
#   compiled, through a tiny generated wrapper that sets SCALAR like lapack/double.cpp does: CHOLMOD needs no
#   other LAPACK routine, and lu/svd/eigenvalues would only add compile time. Symbols CHOLMOD uses: d/z gemm,
#   gemv, trsm, trsv, dsyrk, zherk, d/z potrf (checked at the end by `llvm-nm`-style inspection of the archive).
#   The complex ones (z*) come from wasm/cholmod-complex-blas.c, which stops the program if one is ever called:
#   the project factors real matrices only, and Eigen's complex BLAS was the build's slowest file (recipe 4
#   compiled it and the complex Cholesky).
# * PATCH 1 (wasm): the build uses a copy of CHOLMOD/Include in the work tree, with cholmod_blas.h's BLAS/LAPACK
#   prototypes changed from `void` to `int` (Eigen's return int; in wasm the mismatch links with only a warning
#   and then traps with "unreachable" at run time).
# * PATCH 2 (both targets): wasm/patches/*.patch, applied with `patch -p1` to a copy of the CHOLMOD modules
#   they touch (the extracted tree stays pristine). cholmod-updown-row-pairs.patch: cholmod_updown's numeric
#   kernel updates two rows of L at a time in the lanes of a two-double vector (simd128 in wasm), with each
#   lane doing the scalar code's exact operations; a 50-edge stroke's update on bunny00 goes from 22 to about
#   10.5 ms in wasm (docs/benchmarks.md). metis-gklib-thread-random.patch: GKlib's random generator (built with
#   -DUSE_GKRAND, as METIS's own CMake build can, not libc's rand()) keeps its state per thread, so that METIS
#   calls on several threads give the results each gives alone. Nothing else is patched.
# * Link consumers with -Wl,--fatal-warnings so any future signature mismatch fails the link instead of trapping.
# * Debian's emscripten 3.1.6 has a frozen cache (no ports); node links at -O1+ need NODE_PATH=/usr/share/nodejs.
# * The output folder name carries a RECIPE number (bump it when flags/sources in this script change) and the
#   checksum of wasm/patches/*.patch.
# * As root the script apt-get installs what is missing (dpkg-dev, emscripten); otherwise it stops with a message.
# * Licence: CHOLMOD Modify/MatrixOps/Supernodal are GPL-2.0-or-later, so the archive is GPL; Eigen is MPL-2.0.
# * --native: the same CHOLMOD, AMD/CAMD/COLAMD/CCOLAMD and METIS sources compiled with gcc for this machine
#   (-O3, and -march=x86-64-v3 where the CPU has AVX2 and FMA) into build-native/cholmod/<key>/lib/
#   libcholmod_native.a, with the original headers (no patch) and the system's BLAS/LAPACK (link -llapack
#   -lblas). The native CLI links it instead of Debian's libcholmod3 (built -O2 for any x86-64, with OpenMP):
#   on bunny00 a 50-edge stroke's rank-50 update goes from 12-15 to 7.5-8 ms and the factorization from
#   ~360 to ~170 ms (docs/benchmarks.md), and native and wasm then run one CHOLMOD, from one source package.
# * --threads: the wasm archive for a module linked with shared memory (wasm/build.sh builds
#   tvf_core_threads.mjs for cross-origin-isolated pages), into build-wasm/cholmod-threads/<key>_pthread/. It
#   is the plain archive's objects (compiled once, shared with it in cholmod-work/build/<plain key>/obj)
#   except the few that lost thread-local storage or atomics to the plain build (GKlib's error and memory
#   state, METIS's entry points that use them: the linker refuses those objects in shared memory, marked
#   `-shared-mem` in their target features), which are compiled again with -pthread. An object with neither
#   is the same code either way, and CHOLMOD runs on one thread there too; the core's own backward
#   substitution uses the others. Compiling every source twice cost about a minute of a fresh `npm test`.

set -euo pipefail

RECIPE=5
SMOKE=0
REFRESH=0
NATIVE=0
THREADS=0
for arg in "$@"; do
  case "$arg" in
    --smoke) SMOKE=1 ;;
    --refresh) REFRESH=1 ;;
    --native) NATIVE=1 ;;
    --threads) THREADS=1 ;;
    -h|--help) sed -n '4,/^set -euo/p' "${BASH_SOURCE[0]}" | sed -n 's/^# \{0,1\}//p' >&2; exit 0 ;;
    *) echo "build-cholmod.sh: unknown argument: $arg (try --help)" >&2; exit 2 ;;
  esac
done

# The threads archive has a recipe of its own (plain objects with -pthread twins of the marked ones).
PLAIN_RECIPE=$RECIPE
[ "$THREADS" = 0 ] || RECIPE=${RECIPE}t2

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd -P)
WORK=$ROOT/build-wasm/cholmod-work  # sources and apt state, shared by both targets
if [ "$NATIVE" = 1 ]; then
  TOP=$ROOT/build-native/cholmod
  # Vector ISA of this machine: the CLI built here runs here.
  ISA=generic
  if grep -qw avx2 /proc/cpuinfo 2>/dev/null && grep -qw fma /proc/cpuinfo && grep -qw bmi2 /proc/cpuinfo &&
    gcc -march=x86-64-v3 -E -x c /dev/null >/dev/null 2>&1; then ISA=x86-64-v3; fi
elif [ "$THREADS" = 1 ]; then
  TOP=$ROOT/build-wasm/cholmod-threads
else
  TOP=$ROOT/build-wasm/cholmod
fi
JOBS=${JOBS:-2}
export NODE_PATH=${NODE_PATH:+$NODE_PATH:}/usr/share/nodejs

log() { printf '[build-cholmod] %s\n' "$*" >&2; }
die() { printf '[build-cholmod] ERROR: %s\n' "$*" >&2; exit 1; }

# ---------------------------------------------------------------- smoke test (wasm/cholmod-smoke.c under node)
run_smoke() {
  local out=$1 sd=$WORK/smoke
  command -v node >/dev/null || die "node not found (needed for --smoke)"
  mkdir -p "$sd"
  # the repo's package.json may say "type": "module"; emscripten 3.1.6's output is CommonJS
  echo '{ "type": "commonjs" }' > "$sd/package.json"
  log "smoke: compiling wasm/cholmod-smoke.c against $out"
  # WASM_ASYNC_COMPILATION=0: emscripten 3.1.6 + node >= 18 would try to fetch() the .wasm by path otherwise.
  local pthread=; [ "$THREADS" = 0 ] || pthread=-pthread
  emcc -O2 -std=c11 -Wall $pthread -I"$out/include" "$ROOT/wasm/cholmod-smoke.c" "$out/lib/libcholmod_wasm.a" \
    -Wl,--fatal-warnings -sALLOW_MEMORY_GROWTH=1 -sWASM_ASYNC_COMPILATION=0 -sENVIRONMENT=node \
    -o "$sd/cholmod-smoke.js" >&2
  log "smoke: running with node ($(node --version))"
  node "$sd/cholmod-smoke.js" >&2
}

finish() {  # $1 = output folder
  if [ "$SMOKE" = 1 ] && [ "$NATIVE" = 0 ]; then run_smoke "$1"; fi
  printf '%s\n' "$1"
  exit 0
}

# The patches' checksum is part of the recipe: editing one rebuilds, like bumping RECIPE.
PATCHSUM=$(cat "$ROOT"/wasm/patches/*.patch | cksum | cut -d' ' -f1)
stamp_ok() { [ -f "$1/stamp" ] && [ "$(head -n1 "$1/stamp")" = "recipe=$RECIPE patches=$PATCHSUM" ]; }

# ---------------------------------------------------------------- instant path
if [ "$REFRESH" = 0 ] && [ -f "$TOP/current" ]; then
  cur=$TOP/$(cat "$TOP/current")
  if stamp_ok "$cur"; then finish "$cur"; fi
fi

mkdir -p "$TOP" "$WORK"
exec 9>"$TOP/.lock"
if ! flock -n 9; then log "another build-cholmod.sh holds $TOP/.lock; waiting"; flock 9; fi
# (another run may have finished while we waited)
if [ "$REFRESH" = 0 ] && [ -f "$TOP/current" ]; then
  cur=$TOP/$(cat "$TOP/current")
  if stamp_ok "$cur"; then finish "$cur"; fi
fi

T0=$(date +%s.%N)
elapsed() { awk -v a="$T0" -v b="$(date +%s.%N)" 'BEGIN{printf "%.1f s", b-a}'; }

# ---------------------------------------------------------------- tools
need_pkgs=()
if [ "$NATIVE" = 1 ]; then
  command -v gcc >/dev/null && command -v ar >/dev/null || need_pkgs+=(build-essential)
  [ -e /usr/lib/x86_64-linux-gnu/liblapack.so ] || [ -n "$(ls /usr/lib/*/liblapack.so 2>/dev/null)" ] || need_pkgs+=(liblapack-dev)
else
  command -v emcc >/dev/null && command -v em++ >/dev/null && command -v emar >/dev/null || need_pkgs+=(emscripten)
fi
command -v dpkg-source >/dev/null || need_pkgs+=(dpkg-dev)
command -v patch >/dev/null || need_pkgs+=(patch)
command -v apt-get >/dev/null || die "apt-get not found: this script expects a Debian machine"
command -v flock >/dev/null || die "flock (util-linux) not found"
if [ ${#need_pkgs[@]} -gt 0 ]; then
  [ "$(id -u)" = 0 ] || die "missing packages: ${need_pkgs[*]} (run as root, or: sudo apt-get install ${need_pkgs[*]})"
  log "installing ${need_pkgs[*]} (apt-get update first)"
  DEBIAN_FRONTEND=noninteractive apt-get -qq update >&2
  DEBIAN_FRONTEND=noninteractive apt-get -qq install -y --no-install-recommends "${need_pkgs[@]}" >&2
fi

# ---------------------------------------------------------------- private apt: deb-src list from the machine's own
APT=$WORK/apt
mkdir -p "$APT/parts" "$APT/lists/partial" "$APT/cache/archives/partial"
write_src_list() {  # $1 = 1 to drop security stanzas/lines
  local nosec=$1
  rm -f "$APT/parts/"*
  if [ -f /etc/apt/sources.list.d/debian.sources ]; then
    # deb822: keep stanzas whose Types include "deb", turn them into deb-src
    awk -v nosec="$nosec" '
      function flush() { if (keep && (!nosec || !sec)) printf "%s\n", buf; buf=""; keep=0; sec=0 }
      /^[ \t]*$/ { flush(); next }
      { if ($1 == "Types:") { keep = 0; for (i = 2; i <= NF; i++) if ($i == "deb") keep = 1; $0 = "Types: deb-src" }
        if ($1 == "Suites:" && $0 ~ /security/) sec = 1
        buf = buf $0 "\n" }
      END { flush() }' /etc/apt/sources.list.d/debian.sources > "$APT/parts/src.sources"
  fi
  if [ ! -s "$APT/parts/src.sources" ] && [ -f /etc/apt/sources.list ]; then
    rm -f "$APT/parts/src.sources"
    # one-line format: "deb [opts] uri suite comps" -> "deb-src [opts] uri suite comps"
    grep -E '^[[:space:]]*deb[[:space:]]' /etc/apt/sources.list | { if [ "$nosec" = 1 ]; then grep -v security; else cat; fi; } \
      | sed -E 's/^[[:space:]]*deb[[:space:]]/deb-src /' > "$APT/parts/src.list" || true
    [ -s "$APT/parts/src.list" ] || rm -f "$APT/parts/src.list"
  fi
  ls "$APT/parts/"* >/dev/null 2>&1 || die "no 'deb' entries found in /etc/apt/sources.list.d/debian.sources or /etc/apt/sources.list"
}
AO=(-o Dir::Etc::SourceList=/dev/null -o "Dir::Etc::SourceParts=$APT/parts" -o "Dir::State::Lists=$APT/lists"
    -o "Dir::Cache=$APT/cache")
# downloads land in a root-owned folder that the _apt sandbox user cannot write; apt would fall back to
# root anyway (with a warning), and every file is checked against the signed index's hashes
[ "$(id -u)" = 0 ] && AO+=(-o APT::Sandbox::User=root)
apt_update() {
  write_src_list 0
  if ! apt-get "${AO[@]}" -qq update >&2; then
    log "private apt-get update failed; retrying without the security stanza"
    write_src_list 1
    apt-get "${AO[@]}" -qq update >&2 || die "private apt-get update failed"
  fi
}
if [ "$REFRESH" = 1 ] || ! ls "$APT/lists/"*_Sources* >/dev/null 2>&1; then
  log "private apt-get update (deb-src derived from the machine's apt sources)"
  apt_update
fi
src_version() {  # candidate source version of package $1 (epoch stripped, as in file names)
  apt-get "${AO[@]}" -qq source --print-uris "$1" 2>/dev/null \
    | awk -v p="$1" '$2 ~ "^" p "_.*\\.dsc$" { v = $2; sub("^" p "_", "", v); sub("\\.dsc$", "", v); print v; exit }'
}
SS_VER=$(src_version suitesparse)
EIG_VER=$(src_version eigen3)
METIS_VER=$(src_version metis)
if [ -z "$SS_VER" ] || [ -z "$EIG_VER" ] || [ -z "$METIS_VER" ]; then
  log "source versions not resolvable from the cached lists; refreshing"
  apt_update
  SS_VER=$(src_version suitesparse); EIG_VER=$(src_version eigen3); METIS_VER=$(src_version metis)
  [ -n "$SS_VER" ] && [ -n "$EIG_VER" ] && [ -n "$METIS_VER" ] ||
    die "apt-get source cannot find suitesparse/eigen3/metis in the deb-src index"
fi
KEY=suitesparse-${SS_VER}_eigen3-${EIG_VER}_metis-${METIS_VER}_r${RECIPE}_p${PATCHSUM}
[ "$NATIVE" = 0 ] || KEY=suitesparse-${SS_VER}_metis-${METIS_VER}_${ISA}_r${RECIPE}_p${PATCHSUM}
# The plain archive's folder, whose objects the threads archive shares.
PLAIN_KEY=suitesparse-${SS_VER}_eigen3-${EIG_VER}_metis-${METIS_VER}_r${PLAIN_RECIPE}_p${PATCHSUM}
[ "$THREADS" = 0 ] || KEY=${KEY}_pthread
OUT=$TOP/$KEY
log "suitesparse $SS_VER, eigen3 $EIG_VER, metis $METIS_VER -> $OUT"
if stamp_ok "$OUT"; then printf '%s\n' "$KEY" > "$TOP/current"; finish "$OUT"; fi

# ---------------------------------------------------------------- download + extract
DL=$WORK/dl
mkdir -p "$DL" "$WORK/src"
fetch_extract() {  # $1 = package, $2 = version; prints the extracted tree
  local pkg=$1 ver=$2 tree=$WORK/src/$1-$2
  if [ ! -f "$tree/.extracted" ]; then
    if [ ! -f "$DL/${pkg}_${ver}.dsc" ]; then
      log "apt-get source --download-only $pkg ($ver)"
      (cd "$DL" && apt-get "${AO[@]}" -qq source --download-only "$pkg" >&2) || die "download of $pkg failed"
    fi
    log "dpkg-source -x ${pkg}_${ver}.dsc"
    rm -rf "$tree" "$tree.tmp"
    # --no-check: the .dsc and tarballs were already verified by apt against the signed archive index
    (cd "$DL" && dpkg-source --no-check -x "${pkg}_${ver}.dsc" "$tree.tmp" >&2)
    mv "$tree.tmp" "$tree"
    touch "$tree/.extracted"
  fi
  printf '%s\n' "$tree"
}
SS=$(fetch_extract suitesparse "$SS_VER")
EIG=$(fetch_extract eigen3 "$EIG_VER")
METIS=$(fetch_extract metis "$METIS_VER")
log "sources ready ($(elapsed))"

# ---------------------------------------------------------------- build tree: patched include copy + objects
BLD=$WORK/build/$KEY
TWINS=
if [ "$THREADS" = 1 ]; then
  # Sources, headers and objects are the plain archive's (built here if it was not): one build at a time there.
  TWINS=$BLD/obj
  mkdir -p "$TWINS" "$ROOT/build-wasm/cholmod"
  exec 8>"$ROOT/build-wasm/cholmod/.lock"
  if ! flock -n 8; then log "a plain build-cholmod.sh holds build-wasm/cholmod/.lock; waiting"; flock 8; fi
  BLD=$WORK/build/$PLAIN_KEY
fi
INC=$BLD/include
OBJ=$BLD/obj
GEN=$BLD/gen
mkdir -p "$OBJ" "$GEN"
rm -rf "$INC"; mkdir -p "$INC"
cp "$SS"/CHOLMOD/Include/*.h "$SS"/SuiteSparse_config/SuiteSparse_config.h \
   "$SS"/AMD/Include/amd.h "$SS"/CAMD/Include/camd.h "$SS"/COLAMD/Include/colamd.h "$SS"/CCOLAMD/Include/ccolamd.h \
   "$METIS"/include/metis.h "$INC"/
# METIS's idx_t must be CHOLMOD's Int (32-bit) for cholmod_metis.c to pass its arrays through without copies
grep -q '^#define IDXTYPEWIDTH 32' "$INC/metis.h" || die "metis.h does not define a 32-bit idx_t"
# PATCH 1: BLAS/LAPACK prototypes return int (Eigen's do); the native build links Fortran-ABI BLAS as written
[ "$NATIVE" = 1 ] || sed -E -i 's/^void([[:space:]]+)(BLAS_|LAPACK_)/int\1\2/' "$INC/cholmod_blas.h"
nvoid=$(grep -cE '^void[[:space:]]+(BLAS_|LAPACK_)' "$INC/cholmod_blas.h" || true)
nint=$(grep -cE '^int[[:space:]]+(BLAS_|LAPACK_)' "$INC/cholmod_blas.h" || true)
[ "$NATIVE" = 1 ] || { [ "$nvoid" = 0 ] && [ "$nint" -ge 12 ]; } || die "cholmod_blas.h patch did not apply as expected (void=$nvoid int=$nint)"

# PATCH 2: our patches, onto a copy of the modules they touch
PSRC=$BLD/src
rm -rf "$PSRC"; mkdir -p "$PSRC/CHOLMOD"
cp -r "$SS/CHOLMOD/Modify" "$PSRC/CHOLMOD/"
mkdir -p "$PSRC/GKlib"; cp "$METIS/GKlib/random.c" "$PSRC/GKlib/"
for p in "$ROOT"/wasm/patches/*.patch; do
  patch --quiet --forward --no-backup-if-mismatch -d "$PSRC" -p1 < "$p" >&2 || die "$(basename "$p") did not apply"
done
moddir() { if [ "$1" = Modify ]; then echo "$PSRC/CHOLMOD/Modify"; else echo "$SS/CHOLMOD/$1"; fi; }

# LAPACK subset: only the real Cholesky routines, set up exactly like lapack/double.cpp
printf '#define SCALAR        double\n#define SCALAR_SUFFIX d\n#define SCALAR_SUFFIX_UP "D"\n#define ISCOMPLEX     0\n#include "%s/lapack/cholesky.cpp"\n' \
  "$EIG" > "$GEN/lapack_cholesky_d.cpp"

CFLAGS="-O3 -DNDEBUG -msimd128"
# METIS's own CMake flags on Linux (GKlibSystem.cmake), without OpenMP, with GKlib's own random generator (its
# GKRAND option) for a state per thread
METISFLAGS="-O3 -msimd128 -DLINUX -D_FILE_OFFSET_BITS=64 -std=c99 -fno-strict-aliasing -DNDEBUG -DNDEBUG2 -DUSE_GKRAND -I$METIS/include -I$METIS/GKlib -I$METIS/libmetis"
CXXFLAGS="-O3 -DNDEBUG -msimd128"
CC=emcc CXX=em++ AR=emar ARCHIVE=libcholmod_wasm.a
if [ "$NATIVE" = 1 ]; then
  march=; [ "$ISA" = generic ] || march=-march=$ISA
  CFLAGS="-O3 -DNDEBUG -fPIC $march"
  METISFLAGS="${METISFLAGS/-msimd128/-fPIC $march}"
  CC=gcc CXX=g++ AR=ar ARCHIVE=libcholmod_native.a
fi
EIGFLAGS="-I$EIG"   # <Eigen/...> from the extracted eigen3 source, never the system's
IFLAGS="-I$INC -I$SS/AMD/Include -I$SS/CAMD/Include -I$SS/COLAMD/Include -I$SS/CCOLAMD/Include -I$SS/SuiteSparse_config"

# job list: "<compiler> <extra flags (comma-separated)> <source> <object>", slowest (C++) first
JOBLIST=$BLD/jobs.txt
: > "$JOBLIST"
add() { printf '%s %s %s %s\n' "$1" "$2" "$3" "$OBJ/$4.o" >> "$JOBLIST"; }
if [ "$NATIVE" = 0 ]; then
  add em++ - "$EIG/blas/double.cpp" eigen_blas_double
  add em++ - "$GEN/lapack_cholesky_d.cpp" eigen_lapack_cholesky_d
  add em++ - "$EIG/blas/xerbla.cpp" eigen_blas_xerbla
  add emcc - "$ROOT/wasm/cholmod-complex-blas.c" cholmod_complex_blas
fi
for m in Supernodal Cholesky Modify MatrixOps Core Check Partition; do
  for f in "$(moddir "$m")"/cholmod_*.c; do add emcc - "$f" "$(basename "$f" .c)"; done
done
for f in "$SS"/AMD/Source/amd_*.c; do
  case "$f" in *_global.c) continue ;; esac
  add emcc -DDINT "$f" "$(basename "$f" .c | sed 's/^amd_/amd_i_/')"
done
for f in "$SS"/CAMD/Source/camd_*.c; do
  case "$f" in *_global.c) continue ;; esac
  add emcc -DDINT "$f" "$(basename "$f" .c | sed 's/^camd_/camd_i_/')"
done
add emcc - "$SS/COLAMD/Source/colamd.c" colamd
add emcc - "$SS/CCOLAMD/Source/ccolamd.c" ccolamd
add emcc - "$SS/SuiteSparse_config/SuiteSparse_config.c" SuiteSparse_config
for f in "$METIS"/GKlib/*.c; do
  p=$PSRC/GKlib/$(basename "$f"); [ -f "$p" ] || p=$f  # the patched copy where there is one
  add metis - "$p" "gklib_$(basename "$f" .c)"
done
for f in "$METIS"/libmetis/*.c; do add metis - "$f" "metis_$(basename "$f" .c)"; done

compile_one() {  # cc extra src obj
  local cc=$1 extra=$2 src=$3 obj=$4 flags
  [ -f "$obj" ] && return 0              # resumable: objects are only ever renamed into place when complete
  [ "$extra" = - ] && extra=
  case "$cc" in
    em++) flags="$CXXFLAGS $EIGFLAGS" ;;
    metis) cc=$CC; flags=$METISFLAGS ;;
    *) cc=$CC; flags="$CFLAGS $IFLAGS" ;;
  esac
  # shellcheck disable=SC2086
  "$cc" $flags ${extra//,/ } -c "$src" -o "$obj.tmp.$$" || { rm -f "$obj.tmp.$$"; echo "FAILED: $src" >&2; return 255; }
  mv "$obj.tmp.$$" "$obj"
}
export -f compile_one
export CFLAGS CXXFLAGS IFLAGS EIGFLAGS METISFLAGS CC
njobs=$(wc -l < "$JOBLIST")
log "compiling $njobs sources with $JOBS jobs ($CFLAGS; C++: $CXXFLAGS)"
xargs -P "$JOBS" -L 1 bash -c 'compile_one "$@"' _ < "$JOBLIST" >&2 || die "compilation failed"
log "compiled ($(elapsed))"

# --threads: the objects the plain build marked `-shared-mem` (thread-local storage or atomics lowered away)
# are compiled again with -pthread into $TWINS, and the archive takes those copies instead.
if [ "$THREADS" = 1 ]; then
  TWINLIST=$TWINS/../jobs.txt
  while read -r cc extra src obj; do
    if LC_ALL=C grep -qa 'shared-mem' "$obj"; then printf '%s %s %s %s\n' "$cc" "$extra" "$src" "$TWINS/$(basename "$obj")"; fi
  done < "$JOBLIST" > "$TWINLIST"
  CFLAGS="$CFLAGS -pthread" METISFLAGS="$METISFLAGS -pthread" CXXFLAGS="$CXXFLAGS -pthread" \
    xargs -P "$JOBS" -L 1 bash -c 'compile_one "$@"' _ < "$TWINLIST" >&2 || die "compilation failed"
  log "compiled again with -pthread: $(awk '{print $4}' "$TWINLIST" | xargs -r -n1 basename | tr '\n' ' ')($(elapsed))"
fi

# ---------------------------------------------------------------- archive + output folder
STAGE=$TOP/.$KEY.tmp.$$
rm -rf "$STAGE"; mkdir -p "$STAGE/lib" "$STAGE/include"
OBJECTS=$STAGE/objects.txt
while read -r _ _ _ obj; do
  if [ -n "$TWINS" ] && [ -f "$TWINS/$(basename "$obj")" ]; then echo "$TWINS/$(basename "$obj")"; else echo "$obj"; fi
done < "$JOBLIST" > "$OBJECTS"
# shellcheck disable=SC2046
$AR rcs "$STAGE/lib/$ARCHIVE" $(cat "$OBJECTS")
rm -f "$OBJECTS"
cp "$INC"/*.h "$STAGE/include/"
rm -f "$STAGE"/include/cholmod_gpu*.h "$STAGE/include/cholmod_internal.h" "$STAGE/include/cholmod_template.h"

# every BLAS/LAPACK symbol the CHOLMOD objects need must be defined in the archive
NM=$(command -v llvm-nm || ls /usr/bin/llvm-nm-* /usr/lib/llvm-*/bin/llvm-nm 2>/dev/null | head -n1 || true)
if [ -n "$NM" ] && [ "$NATIVE" = 0 ]; then
  defined=$("$NM" --defined-only -j "$STAGE/lib/$ARCHIVE" 2>/dev/null | sort -u)
  for s in dgemm_ dgemv_ dtrsm_ dtrsv_ dsyrk_ dpotrf_ zgemm_ zgemv_ ztrsm_ ztrsv_ zherk_ zpotrf_; do
    grep -qx "$s" <<<"$defined" || die "archive lacks $s"
  done
  log "BLAS/LAPACK symbols present (checked with $NM)"
fi

{
  echo "suitesparse $SS_VER"
  echo "eigen3 $EIG_VER"
  echo "metis $METIS_VER"
  echo "METISFLAGS $METISFLAGS"
  echo "$CC $("$CC" --version 2>/dev/null | sed -n 1p)"
  echo "CFLAGS $CFLAGS"
  echo "CXXFLAGS $CXXFLAGS"
  [ -z "$TWINS" ] || echo "with -pthread as well: $(awk '{print $4}' "$TWINLIST" | xargs -r -n1 basename | tr '\n' ' ')"
  if [ "$NATIVE" = 1 ]; then
    echo "blas/lapack: the system's (link -llapack -lblas); headers unpatched"
    echo "patches: $(cd "$ROOT/wasm/patches" && echo *.patch)"
  else
    echo "patches: cholmod_blas.h void->int BLAS/LAPACK prototypes; $(cd "$ROOT/wasm/patches" && echo *.patch)"
    echo "lapack: Eigen lapack/cholesky.cpp only (d); complex BLAS/LAPACK: wasm/cholmod-complex-blas.c (stops)"
  fi
} > "$STAGE/versions"
printf 'recipe=%s patches=%s\nbuilt %s in %s\n' "$RECIPE" "$PATCHSUM" "$(date -u +%Y-%m-%dT%H:%M:%SZ)" "$(elapsed)" > "$STAGE/stamp.tmp"
rm -rf "$OUT"
mv "$STAGE/stamp.tmp" "$STAGE/stamp"
mv "$STAGE" "$OUT"
printf '%s\n' "$KEY" > "$TOP/current"
log "done: $(du -h "$OUT/lib/$ARCHIVE" | cut -f1) archive, $(elapsed) in all"
finish "$OUT"

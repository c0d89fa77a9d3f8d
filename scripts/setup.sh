#!/usr/bin/env bash
# Brings a Debian 12 machine to the point where `npm run build` and `npm test` work.
# Idempotent and quick when everything is present: apt is only touched when a package is missing,
# and `npm ci` only runs when node_modules is absent or older than the lockfile.
# Never downloads a browser: Playwright drives Debian's /usr/bin/chromium.
set -euo pipefail

cd "$(dirname "${BASH_SOURCE[0]}")/.."

DEB_PACKAGES=(build-essential cmake libeigen3-dev libsuitesparse-dev libtinygltf-dev nlohmann-json3-dev
  libgtest-dev libopenblas0 libmetis-dev emscripten chromium dpkg-dev clang libclang-rt-14-dev libstb-dev libpng-dev
  libfast-float-dev)
# libstb-dev: stb_image_write encodes flow maps (native and wasm alike); libpng-dev: the tests decode them with
# an independent reader.
# libfast-float-dev: exact, locale-independent number parsing for OFF/OBJ/PLY (emscripten's libc++ has no
# floating-point from_chars, and its strtod is slow).
# libopenblas0: CHOLMOD's supernodal factorization runs 2-3x faster on it than on the reference BLAS.
# clang + libclang-rt-14-dev: libFuzzer (libclang_rt.fuzzer-x86_64.a) and its sanitizers, for scripts/fuzz.sh.

missing=()
for pkg in "${DEB_PACKAGES[@]}"; do
  status=$(dpkg-query -W -f='${Status}' "$pkg" 2>/dev/null || true)
  [[ "$status" == "install ok installed" ]] || missing+=("$pkg")
done

if ((${#missing[@]})); then
  echo "setup: installing Debian packages: ${missing[*]}"
  SUDO=()
  if [[ $(id -u) -ne 0 ]]; then
    if command -v sudo >/dev/null; then SUDO=(sudo); else
      echo "setup: missing Debian packages (${missing[*]}) and not root; install them and re-run" >&2
      exit 1
    fi
  fi
  export DEBIAN_FRONTEND=noninteractive
  "${SUDO[@]}" apt-get update
  "${SUDO[@]}" apt-get install -y "${missing[@]}"
fi

# The lockfile is newer than node_modules after a dependency change: reinstall exactly what it records.
if [[ ! -d node_modules || package-lock.json -nt node_modules ]]; then
  echo "setup: npm ci"
  PLAYWRIGHT_SKIP_BROWSER_DOWNLOAD=1 npm ci --no-audit --no-fund
  # npm ci leaves the directory mtime at install time; make it explicit so the check above settles.
  touch node_modules
fi

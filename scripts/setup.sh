#!/usr/bin/env bash
# Install what is missing (Debian packages), then configure and build.
#   scripts/setup.sh [BUILD_DIR] [extra cmake args...]
# Default BUILD_DIR: build (Release). Use e.g. `scripts/setup.sh build-asan -DSS_SANITIZE=ON`.
set -euo pipefail
cd "$(dirname "$0")/.."

# (locales: the data test_c_locale builds its comma-decimal locale from)
pkgs=(cmake make gcc pkg-config libsuitesparse-dev libarpack2-dev libopenblas-dev liblapacke-dev libpng-dev libassimp-dev
      python3 python3-numpy python3-venv python3-pip python3-setuptools python3-wheel
      locales)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "setup: installing ${missing[*]}" >&2
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

build=${1:-build}
shift || true
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release "$@" >/dev/null
cmake --build "$build" -j"$(nproc)"

#!/usr/bin/env bash
# Streamlining benchmark: ss_remesh vs CGAL isotropic_remeshing and ss_cmcf_smooth vs CGAL smooth_shape
# on FAUST, in one process.
# Installs Debian's CGAL (header-only, with GMP/MPFR; Eigen for smooth_shape) and a C++ compiler when
# missing, then builds the optional bench_remesh_cgal target.
#   scripts/bench_remesh_cgal.sh [BUILD_DIR] [bench_remesh_cgal args, e.g. --count 100 --rounds 3 --raw]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true

pkgs=(g++ libcgal-dev libgmp-dev libmpfr-dev libeigen3-dev)
missing=()
for p in "${pkgs[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "bench_remesh_cgal: installing ${missing[*]}" >&2
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# CMake decides about the optional target at configure time: configure again now that CGAL is there
cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
cmake --build "$build" -j2 --target bench_remesh_cgal
"$build/bench_remesh_cgal" "$@"

#!/usr/bin/env bash
# Eigensolver benchmark: specseg vs SciPy eigsh(W, k=100, M=M, sigma=-1e-8) on the same matrices,
# FAUST tr_reg_000 (6,890 vertices) and its 2x subdivision (~110k vertices).
#   scripts/bench_eigs.sh [BUILD_DIR] [extra bench_eigs args, e.g. --reps 5 --levels 0]
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
shift || true

# Debian's SciPy lives with the system interpreter; install it when missing.
py=/usr/bin/python3
[ -x "$py" ] || py=$(command -v python3)
if ! "$py" -c "import scipy, numpy" 2>/dev/null; then
  echo "bench_eigs: installing python3-scipy" >&2
  SUDO=""
  [ "$(id -u)" -ne 0 ] && SUDO="sudo"
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq --no-install-recommends python3-scipy python3-numpy >/dev/null
  py=/usr/bin/python3
fi

if [ ! -x "$build/bench_eigs" ]; then
  cmake -S . -B "$build" -DCMAKE_BUILD_TYPE=Release >/dev/null
  cmake --build "$build" -j2 --target bench_eigs
fi
out=$(mktemp -d "${TMPDIR:-/tmp}/specseg_bench_eigs.XXXXXX")
trap 'rm -rf "$out"' EXIT
"$build/bench_eigs" --out "$out" --python "$py" --script scripts/bench_eigs_scipy.py "$@"

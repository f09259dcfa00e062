#!/usr/bin/env bash
# STD / DIFF (the paper's, unrefined) / the refined default of ss_match on every pair set of the
# held-out protocol (docs/tuning.md, issue 12): pairs among FAUST subjects 0-4 (tune) and 5-9 (held),
# BEST and GT landmarks. Prints each set's means, ratios to STD and CPU per pair.
#   scripts/bench_refined.sh [BUILD_DIR] [PAIRS] [SEED]     (defaults: build 20 1)
set -euo pipefail
cd "$(dirname "$0")/.."
build=${1:-build}
pairs=${2:-20}
seed=${3:-1}
for split in tune held; do
  for lm in best gt; do
    "$build/bench_match" --split "$split" --lm "$lm" --pairs "$pairs" --seed "$seed" \
      --cfg STD:paper=1,probes=std --cfg DIFF:paper=1,probes=diff --cfg default: | sed -n '/^split /,$p'
  done
done

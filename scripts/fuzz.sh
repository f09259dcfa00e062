#!/usr/bin/env bash
# libFuzzer harnesses of tests/fuzz (issue 13, item 8): every reader (OFF, OBJ, PLY, STL, glTF, content
# sniffing, text vectors, landmarks), read -> check -> geodesics / eigenpairs on small meshes, and the
# prepared-shape reader on mutated payloads whose checksum the harness recomputes (shape).
#   scripts/fuzz.sh SECONDS [--save] [HARNESS...]
# builds them with clang (ASan + UBSan + coverage, in build-fuzz/ or $SS_FUZZ_BUILD), then runs each for SECONDS (all
# harnesses by default, e.g. `scripts/fuzz.sh 60 geometry`). The seed corpus is
# tests/fuzz/corpus/HARNESS/ (regression inputs, run every time); new inputs go to a scratch corpus in
# build-fuzz/corpus/HARNESS/, and --save merges those that add coverage back into the repository's
# corpus (small files only: -max_len). Per-input time bound (-timeout): 10 s for the geometry
# harness, 2 s for the readers (ASan included); a slower input is a finding. Exit status 1 and the
# saved input (build-fuzz/findings/HARNESS-crash-*, -timeout-*, -leak-*) on any finding.
set -euo pipefail
cd "$(dirname "$0")/.."
secs=${1:?usage: scripts/fuzz.sh SECONDS [--save] [HARNESS...]}
shift
save=0
if [ "${1:-}" = --save ]; then save=1; shift; fi
all=(off obj ply stl gltf mesh vectors landmarks geometry shape)
harnesses=("$@")
[ ${#harnesses[@]} -gt 0 ] || harnesses=("${all[@]}")
command -v clang > /dev/null || { echo "fuzz: clang not found (apt-get install clang)" >&2; exit 77; }

B=${SS_FUZZ_BUILD:-build-fuzz}
mkdir -p "$B"
cmake -S . -B "$B" -DCMAKE_C_COMPILER=clang -DCMAKE_BUILD_TYPE=RelWithDebInfo -DSS_FUZZ=ON -DSS_BUILD_TESTS=OFF \
  -DSS_BUILD_BENCH=OFF > "$B/configure.log" 2>&1 || { cat "$B/configure.log" >&2; exit 1; }
targets=()
for h in "${harnesses[@]}"; do targets+=("fuzz_$h"); done
cmake --build "$B" -j2 --target "${targets[@]}" > "$B/build.log" 2>&1 || { tail -30 "$B/build.log" >&2; exit 1; }

export OMP_NUM_THREADS=1 OPENBLAS_NUM_THREADS=1
export ASAN_OPTIONS=detect_leaks=1:allocator_may_return_null=1 UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
mkdir -p "$B/findings"
rc=0
for h in "${harnesses[@]}"; do
  seed=tests/fuzz/corpus/$h
  work=$B/corpus/$h
  mkdir -p "$work" "$seed"
  maxlen=4096 timeout=2 rss=2048
  [ "$h" = geometry ] && maxlen=2048 timeout=10
  # prepared shapes: payloads of small meshes (the seeds ~26-45 KB), checksum recomputed by the harness
  [ "$h" = shape ] && maxlen=65536 timeout=10
  log=$B/fuzz_$h.log
  # the scratch corpus first: libFuzzer adds new inputs to the first folder only
  if "$B/fuzz_$h" "$work" "$seed" -max_total_time="$secs" -max_len="$maxlen" -timeout="$timeout" -rss_limit_mb="$rss" \
       -artifact_prefix="$B/findings/$h-" -print_final_stats=1 > "$log" 2>&1; then
    execs=$(sed -n 's/^stat::number_of_executed_units: *//p' "$log" | tail -1)
    echo "fuzz $h: ${execs:-?} executions in ${secs} s, no finding"
  else
    rc=1
    echo "fuzz $h: FINDING (see $log and $B/findings/$h-*)" >&2
    grep -E "^==[0-9]+==ERROR|^SUMMARY|fuzz property violated|ALARM|Test unit written" "$log" | head -5 >&2
  fi
  if [ "$save" = 1 ]; then
    "$B/fuzz_$h" -merge=1 -max_len="$maxlen" -timeout="$timeout" "$seed" "$work" > "$B/merge_$h.log" 2>&1 ||
      { echo "fuzz $h: merge failed (see $B/merge_$h.log)" >&2; rc=1; }
  fi
done
exit $rc

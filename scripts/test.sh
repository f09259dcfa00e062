#!/usr/bin/env bash
# Command (b): install what is missing, build (AddressSanitizer + UBSan), run the demo, run all tests;
# then a Release build with warnings as errors, installed into a scratch prefix and used from outside
# (C through pkg-config and find_package, Python through pip).
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build-asan -DSS_SANITIZE=ON
export ASAN_OPTIONS=detect_leaks=1 UBSAN_OPTIONS=print_stacktrace=1
./build-asan/specseg demo -o build-asan/demo-out
ctest --test-dir build-asan --output-on-failure -j2 --timeout 1500
# libFuzzer harnesses, 10 s each (their corpus also runs as CTest regression inputs above)
if command -v clang > /dev/null; then scripts/fuzz.sh 10; else echo "test: no clang, fuzzing skipped"; fi
scripts/setup.sh build-release -DSS_WERROR=ON
scripts/check_install.sh build-release "$PWD/build-release/install-check"

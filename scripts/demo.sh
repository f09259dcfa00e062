#!/usr/bin/env bash
# Command (a): install what is missing, build, run the main job on the built-in synthetic shapes.
set -euo pipefail
cd "$(dirname "$0")/.."
scripts/setup.sh build
./build/specseg demo -o specseg-demo

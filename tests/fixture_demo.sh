#!/usr/bin/env bash
# CTest fixture (not a test of its own): `specseg demo` once into DIR/out, its summary in DIR/demo.out,
# for the CLI scripts that start from the demo's meshes (lib_cli.sh: demo_outputs copies them). DIR/stamp
# names the binary (size, time, path), so that a script run with another binary runs the demo itself.
# Usage: fixture_demo.sh PATH/TO/specseg DIR
set -u
BIN=${1:?usage: $0 PATH/TO/specseg DIR}
DIR=${2:?usage: $0 PATH/TO/specseg DIR}
. "$(dirname "$0")/lib_cli.sh"
rm -rf "$DIR"
mkdir -p "$DIR" || exit 1
"$BIN" demo -o "$DIR/out" > "$DIR/demo.out" 2>&1 || { cat "$DIR/demo.out"; exit 1; }
bin_stamp > "$DIR/stamp"
echo "demo outputs in $DIR"

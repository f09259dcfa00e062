#!/usr/bin/env bash
# `specseg info` end to end: every file of the malformed corpus (tests/data/malformed) must exit 1
# with a "specseg: error: FILE..." line, within 10 s, without any sanitizer report; directories,
# missing files and usage errors too; valid oddities (pinched vertex, NaN literal, bow-tie) are
# reported, not refused; FAUST tr_reg_000 values when the shared data is there.
# Usage: cli_malformed.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
HERE=$(cd "$(dirname "$0")" && pwd)
TESTS=${SS_TEST_DIR:-$HERE}
CORPUS=$TESTS/data/malformed
. "$(dirname "$0")/lib_cli.sh"

sanitizer_clean() { ! grep -qE 'AddressSanitizer|LeakSanitizer|UndefinedBehaviorSanitizer|runtime error:' "$1"; }

# expect_fail CODE ARGS...: exit CODE, a "specseg: (error|usage):" line on stderr, nothing else wrong
expect_fail() {
  local want=$1
  shift
  timeout 10 "$BIN" "$@" >"$TMP/out" 2>"$TMP/err"
  local rc=$?
  local prefix='specseg: error:'
  [ "$want" = 2 ] && prefix='specseg: usage:'
  if [ $rc -eq 124 ]; then bad "timeout: $*"; return; fi
  if [ $rc -ne "$want" ]; then bad "exit $rc (want $want): $* -- $(head -c 300 "$TMP/err")"; return; fi
  if ! grep -q "^$prefix" "$TMP/err"; then bad "no '$prefix' line: $* -- $(head -c 300 "$TMP/err")"; return; fi
  if ! sanitizer_clean "$TMP/err"; then bad "sanitizer report: $*"; cat "$TMP/err" >&2; return; fi
  ok
}

n=0
for f in "$CORPUS"/*.off "$CORPUS"/*.obj "$CORPUS"/*.ply; do
  [ -e "$f" ] || continue
  n=$((n + 1))
  expect_fail 1 info "$f"
  # the message names the file and a position (":LINE:" or ": byte N:")
  if grep -qE "^specseg: error: .*$(basename "$f")(:[0-9]+:|: byte [0-9]+:)" "$TMP/err"; then ok; else bad "message lacks FILE:LINE: $(cat "$TMP/err")"; fi
done
if [ "$n" -ge 25 ]; then ok; else bad "corpus has only $n files"; fi

expect_fail 1 info "$CORPUS"                      # a directory
expect_fail 1 info "$TMP/does-not-exist.off"      # a missing file
expect_fail 1 info /dev/zero                       # a device that never ends
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' >"$TMP/noext"
chmod 000 "$TMP/noext"
if [ "$(id -u)" != 0 ]; then expect_fail 1 info "$TMP/noext"; fi  # unreadable (root reads anyway)
expect_fail 2 info                                 # no mesh
expect_fail 1 info a.off b.off                     # two meshes: a batch, both missing
expect_fail 2 info --bogus "$CORPUS/off_empty.off" # unknown option
expect_fail 2 nosuchcommand                        # unknown subcommand

# valid but unusual meshes: reported, exit 0
info_ok() { # FILE KEY VALUE...
  local f=$1
  shift
  timeout 10 "$BIN" info "$f" >"$TMP/out" 2>"$TMP/err"
  local rc=$?
  if [ $rc -ne 0 ] || ! sanitizer_clean "$TMP/err"; then bad "info $f: exit $rc $(head -c 300 "$TMP/err")"; return; fi
  while [ $# -ge 2 ]; do
    if grep -qx "$1: $2" "$TMP/out"; then ok; else bad "info $f: want '$1: $2', got '$(grep "^$1:" "$TMP/out")'"; fi
    shift 2
  done
}
info_ok "$TESTS/data/info/pinched_cones.off" vertices 15 faces 24 components 1 boundary_loops 0 manifold no nonmanifold_vertices 1 euler_characteristic 3
info_ok "$TESTS/data/info/nan_vertex.off" nonfinite_vertices 1 manifold yes boundary_loops 1
info_ok "$TESTS/data/info/bowtie.ply" faces 3 components 1 boundary_loops 2 manifold no nonmanifold_vertices 1
# content sniffing for a file without extension
chmod 644 "$TMP/noext"
info_ok "$TMP/noext" vertices 3 faces 1 boundary_loops 1 area 0.5

if [ -n "${SS_DATA_DIR:-}" ] && [ -f "$SS_DATA_DIR/faust/tr_reg_000.off" ]; then
  info_ok "$SS_DATA_DIR/faust/tr_reg_000.off" vertices 6890 faces 13776 components 1 boundary_loops 0 manifold yes \
    nonmanifold_vertices 0 euler_characteristic 2 genus 0
  for key in area bbox_diagonal; do
    if grep -qE "^$key: [0-9]+\.[0-9]+$" "$TMP/out"; then ok; else bad "FAUST $key line: $(grep "^$key" "$TMP/out")"; fi
  done
else
  skip "FAUST data not found (SS_DATA_DIR)"
fi

# an octahedron scaled by 1e300: the area overflows (inf, with a warning), never "-nan"; the
# diagonal and the degenerate-face count are those of the unit shape scaled
octa() { # SCALE
  awk -v s="$1" 'BEGIN { print "OFF"; print "6 8 0"
    split("1 0 0 -1 0 0 0 1 0 0 -1 0 0 0 1 0 0 -1", c, " ")
    for (i = 0; i < 6; i++) printf "%s %s %s\n", c[3*i+1] * s, c[3*i+2] * s, c[3*i+3] * s
    print "3 0 2 4"; print "3 2 1 4"; print "3 1 3 4"; print "3 3 0 4"
    print "3 2 0 5"; print "3 1 2 5"; print "3 3 1 5"; print "3 0 3 5" }'
}
octa 1e300 > "$TMP/octa_big.off"
info_ok "$TMP/octa_big.off" area inf degenerate_faces 0 bbox_diagonal 3.464101615e+300
grep -q "warning: .*octa_big.off: the area overflows a double" "$TMP/err" && ok || bad "no overflow warning: $(cat "$TMP/err")"

finish

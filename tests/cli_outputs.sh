#!/usr/bin/env bash
# Outputs (issue 32, items 1, 3, 4): every output is written whole or not at all (a temporary file
# beside it, renamed into place): after a write error (a file size limit) neither a partial file nor
# a temporary is left and a file there before keeps its contents; symlinks are written through to
# their target; a FIFO is written, not replaced; a folder is refused; an output naming an input (or
# another output) is refused before anything runs.
# Usage: cli_outputs.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
demo_outputs "$TMP/demo" || { bad "demo"; finish; }
A="$TMP/demo/humanoid_pose0.off"
B="$TMP/demo/humanoid_pose2.off"
S="$TMP/demo/sphere.off"
W="$TMP/w"
mkdir -p "$W"
no_temps() { ! ls -A "$W" | grep -q '\.tmp-'; }

# a write error part-way (8 KB file size limit, the outputs are larger): exit 1, the message, no
# file under the final name, no temporary; a file there before is left as it was
for out in dist.txt dist.npy; do
  (ulimit -f 8; "$BIN" geodesic "$A" -s 0 -o "$W/$out" > /dev/null 2> "$TMP/err"); rc=$?
  [ $rc -eq 1 ] && [ ! -e "$W/$out" ] && grep -q "write error" "$TMP/err" && no_temps && ok ||
    bad "$out past the size limit: rc $rc, $(ls -A "$W") $(cat "$TMP/err")"
done
echo old > "$W/keep.txt"
(ulimit -f 8; "$BIN" geodesic "$A" -s 0 -o "$W/keep.txt" > /dev/null 2>&1)
[ "$(cat "$W/keep.txt")" = old ] && no_temps && ok || bad "the file there before was changed"
(ulimit -f 8; "$BIN" prepare "$S" -k 20 -o "$W/s.sss" > /dev/null 2>&1); rc=$?
[ $rc -eq 1 ] && [ ! -e "$W/s.sss" ] && no_temps && ok || bad "prepare past the size limit: rc $rc $(ls -A "$W")"
(ulimit -f 8; "$BIN" smooth "$A" -o "$W/a.ply" > /dev/null 2>&1); rc=$?
[ $rc -eq 1 ] && [ ! -e "$W/a.ply" ] && no_temps && ok || bad "mesh past the size limit: rc $rc $(ls -A "$W")"
(ulimit -f 8; "$BIN" render "$A" --size 600x600 -o "$W/a.png" > /dev/null 2>&1); rc=$?
[ $rc -eq 1 ] && [ ! -e "$W/a.png" ] && no_temps && ok || bad "PNG past the size limit: rc $rc $(ls -A "$W")"
rm -f "$W/keep.txt"

# a symlink is written through: the link stays, its target gets the file (also a dangling one)
"$BIN" geodesic "$S" -s 0 -o "$W/ref.txt" > /dev/null 2>&1 || bad "geodesic"
for cmd in "geodesic $S -s 0" "prepare $S -k 20"; do
  rm -f "$W/link" "$W/target"
  ln -s target "$W/link"
  # shellcheck disable=SC2086
  "$BIN" $cmd -o "$W/link" > /dev/null 2> "$TMP/err" && [ -L "$W/link" ] && [ -s "$W/target" ] && no_temps && ok ||
    bad "$cmd -o a dangling symlink: $(ls -lA "$W") $(cat "$TMP/err")"
  # shellcheck disable=SC2086
  "$BIN" $cmd -o "$W/link" > /dev/null 2>&1 && [ -L "$W/link" ] && [ -s "$W/target" ] && ok || bad "$cmd -o a symlink"
done
rm -f "$W/link" "$W/target"

# a FIFO is written to, not replaced
mkfifo "$W/fifo"
cat "$W/fifo" > "$TMP/from_fifo" &
reader=$!
"$BIN" prepare "$S" -k 20 -o "$W/fifo" > /dev/null 2> "$TMP/err"; rc=$?
wait $reader
[ $rc -eq 0 ] && [ -p "$W/fifo" ] && head -c 14 "$TMP/from_fifo" | grep -q '^specseg-shape ' && ok ||
  bad "prepare -o FIFO: rc $rc $(cat "$TMP/err")"
cat "$W/fifo" > "$TMP/from_fifo" &
reader=$!
"$BIN" geodesic "$S" -s 0 -o "$W/fifo" > /dev/null 2>&1; rc=$?
wait $reader
[ $rc -eq 0 ] && [ -p "$W/fifo" ] && cmp -s "$TMP/from_fifo" "$W/ref.txt" && ok || bad "geodesic -o FIFO: rc $rc"
rm -f "$W/fifo"
mkdir "$W/dir"
"$BIN" prepare "$S" -k 20 -o "$W/dir" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && [ -d "$W/dir" ] && grep -Eq "is a folder|Is a directory" "$TMP/err" && ok || bad "prepare -o a folder: rc $rc $(cat "$TMP/err")"
rmdir "$W/dir"
# permissions of a replaced file are kept
"$BIN" geodesic "$S" -s 0 -o "$W/mode.txt" > /dev/null 2>&1 && chmod 640 "$W/mode.txt" &&
  "$BIN" geodesic "$S" -s 1 -o "$W/mode.txt" > /dev/null 2>&1 && [ "$(stat -c %a "$W/mode.txt")" = 640 ] && ok ||
  bad "mode not kept: $(stat -c %a "$W/mode.txt")"

# an output naming an input (or another output) is refused, the input untouched
cp "$A" "$W/a.off"
cp "$W/a.off" "$W/a0.off"
"$BIN" prepare "$S" -k 20 -o "$W/s.sss" > /dev/null 2>&1 || bad "prepare"
ln -s a.off "$W/alias.off"
for cmd in "segment $W/a.off -o $W/a.off" "segment $W/a.off -o $W/l.txt --ply $W/a.off" "prepare $W/a.off -o $W/a.off" \
           "prepare $W/a.off -o $W/alias.off" "match $W/s.sss $S -o $W/s.sss" "match $W/a.off $B -o $W/m.txt --pairs $W/a.off" \
           "smooth $W/a.off -o $W/alias.off" "geodesic $W/a.off -s 0 -o $W/a.off" "render $W/a.off -o $W/a.off" \
           "pair $W/a.off $B -o $W/a.off" "error $W/a.off $B -o $W/a.off" "eigs $W/a.off -k 3 -o $W/a.off" \
           "segment $W/a.off -o $W/l.txt --centers $W/l.txt"; do
  # shellcheck disable=SC2086
  "$BIN" $cmd > /dev/null 2> "$TMP/err"; rc=$?
  [ $rc -eq 2 ] && grep -Eq "would overwrite the input|two outputs would be" "$TMP/err" && cmp -s "$W/a.off" "$W/a0.off" &&
    [ -L "$W/alias.off" ] && ok || bad "$cmd: rc $rc $(cat "$TMP/err")"
done
head -c 14 "$W/s.sss" | grep -q '^specseg-shape ' && ok || bad "the prepared input was changed"
finish

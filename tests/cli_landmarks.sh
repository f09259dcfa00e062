#!/usr/bin/env bash
# Landmark files of `specseg match` (issue 32, item 6): a vertex given two partners ('962 1319' and
# '962 100', or two vertices of X the same partner) is an error naming both lines; more than
# SS_MAX_LANDMARKS (200) is refused before anything runs (1000 took > 60 s and 2.3 GB); an exact
# repeat is accepted with a warning.
# Usage: cli_landmarks.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
demo_outputs "$TMP/demo" || { bad "demo"; finish; }
S="$TMP/demo/sphere.off"
M="--no-refine --k 20 --descr-k 20 --probes std"
printf '# landmarks\n962 1319\n5 6\n\n962 100\n' > "$TMP/conflict.txt"
# shellcheck disable=SC2086
"$BIN" match "$S" "$S" --landmarks "$TMP/conflict.txt" $M -o "$TMP/m.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q "conflict.txt:2 and .*conflict.txt:5: vertex 962 of X has two partners on Y (1319 and 100)" "$TMP/err" &&
  [ ! -e "$TMP/m.txt" ] && ok || bad "conflicting partners on Y: rc $rc $(cat "$TMP/err")"
printf '1 7\n2 8\n3 7\n' > "$TMP/conflict_y.txt"
# shellcheck disable=SC2086
"$BIN" match "$S" "$S" --landmarks "$TMP/conflict_y.txt" $M -o "$TMP/m.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q "conflict_y.txt:1 and .*conflict_y.txt:3: vertex 7 of Y has two partners on X (1 and 3)" "$TMP/err" &&
  ok || bad "conflicting partners on X: rc $rc $(cat "$TMP/err")"
# too many: refused at once, saying the limit
awk 'BEGIN { for (i = 0; i < 201; i++) print i, i }' > "$TMP/many.txt"
# shellcheck disable=SC2086
"$BIN" match "$S" "$S" --landmarks "$TMP/many.txt" $M -o "$TMP/m.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q "201 landmarks: at most 200" "$TMP/err" && ok || bad "201 landmarks: rc $rc $(cat "$TMP/err")"
awk 'BEGIN { for (i = 0; i < 200; i++) print i * 3, i * 3 }' > "$TMP/max.txt"
# shellcheck disable=SC2086
"$BIN" match "$S" "$S" --landmarks "$TMP/max.txt" $M -o "$TMP/m.txt" > /dev/null 2> "$TMP/err" && ok ||
  bad "200 landmarks: $(cat "$TMP/err")"
# an exact repeat: accepted, with a warning naming both lines
printf '10 10\n20 20\n10 10\n30 30\n' > "$TMP/repeat.txt"
# shellcheck disable=SC2086
"$BIN" match "$S" "$S" --landmarks "$TMP/repeat.txt" $M -o "$TMP/m.txt" > /dev/null 2> "$TMP/err" &&
  grep -q "warning: .*repeat.txt:3 repeats .*repeat.txt:1" "$TMP/err" && ok || bad "exact repeat: $(cat "$TMP/err")"
finish

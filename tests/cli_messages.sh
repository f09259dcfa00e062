#!/usr/bin/env bash
# Messages and prepared shapes where a mesh is meant (issue 32, item 8): info, eigs, descriptors,
# geodesic, render and pair take a prepared shape (.sss) as its mesh, with the mesh's output;
# segment names both options when the prepared ones differ (--no-streamline asked of a streamlined
# file was reported as "--faces 15000").
# Usage: cli_messages.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
demo_outputs "$TMP/demo" || { bad "demo"; finish; }
S="$TMP/demo/sphere.off"
"$BIN" prepare "$S" -k 20 -o "$TMP/s.sss" > /dev/null 2>&1 || { bad "prepare"; finish; }
"$BIN" info "$S" | sed 's/^[^:]*\.off: //' > "$TMP/i_mesh" && "$BIN" info "$TMP/s.sss" > "$TMP/i_sss" 2> "$TMP/err" &&
  cmp -s "$TMP/i_mesh" "$TMP/i_sss" && ok || bad "info S.sss: $(cat "$TMP/err")"
for cmd in "eigs @ -k 5 -o #.txt" "descriptors @ --wks -n 20 -o #.npy" "geodesic @ -s 0 -o #.txt" "render @ --size 64x64 --no-titles -o #.png"; do
  m=${cmd//@/$S}; m=${m//\#/$TMP/from_mesh}
  p=${cmd//@/$TMP/s.sss}; p=${p//\#/$TMP/from_sss}
  ext=${cmd##*.}
  # shellcheck disable=SC2086
  "$BIN" $m > /dev/null 2>&1 && "$BIN" $p > /dev/null 2> "$TMP/err" && cmp -s "$TMP/from_mesh.$ext" "$TMP/from_sss.$ext" && ok ||
    bad "$p: $(cat "$TMP/err")"
done
"$BIN" pair "$S" "$S" > "$TMP/p_mesh" 2>&1 && "$BIN" pair "$TMP/s.sss" "$S" > "$TMP/p_sss" 2> "$TMP/err" &&
  [ "$(tail -n +2 "$TMP/p_mesh")" = "$(tail -n +2 "$TMP/p_sss")" ] && ok || bad "pair S.sss: $(cat "$TMP/err")"
"$BIN" segment "$TMP/s.sss" --no-streamline -o "$TMP/l.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q "was prepared with --faces 15000, not --no-streamline" "$TMP/err" && ok ||
  bad "segment --no-streamline on a streamlined file: rc $rc $(cat "$TMP/err")"
"$BIN" prepare "$S" -k 20 --no-streamline -o "$TMP/n.sss" > /dev/null 2>&1 &&
  "$BIN" segment "$TMP/n.sss" -o "$TMP/l.txt" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 1 ] && grep -q "was prepared with --no-streamline, not --faces 15000" "$TMP/err" && ok ||
  bad "segment on a --no-streamline file: rc $rc $(cat "$TMP/err")"
finish

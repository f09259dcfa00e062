#!/usr/bin/env bash
# Folders given to the per-mesh commands (issue 32, item 7): prepared shapes (.sss) in a folder are
# taken (a folder of only .sss was "no mesh files"); other files and subfolders are skipped with a
# warning and listed in --json's "skipped" (the count was computed and dropped).
# Usage: cli_folders.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
demo_outputs "$TMP/demo" || { bad "demo"; finish; }
S="$TMP/demo/sphere.off"
mkdir -p "$TMP/only_sss" "$TMP/mixed/sub"
"$BIN" prepare "$S" -k 20 -o "$TMP/only_sss/s.sss" > /dev/null 2>&1 || bad "prepare"
"$BIN" info "$TMP/only_sss" -o "$TMP/out1/" > /dev/null 2> "$TMP/err" && [ -s "$TMP/out1/s.info.txt" ] && ok ||
  bad "a folder of .sss: $(cat "$TMP/err")"
"$BIN" info "$S" -o "$TMP/i_mesh.txt" > /dev/null 2>&1 && cmp -s "$TMP/i_mesh.txt" "$TMP/out1/s.info.txt" && ok ||
  bad "info of the .sss differs from the mesh's"
cp "$TMP/only_sss/s.sss" "$TMP/mixed/a.sss"
cp "$TMP/demo/torus.off" "$TMP/mixed/b.off"
echo notes > "$TMP/mixed/README.txt"
"$BIN" info "$TMP/mixed" -o "$TMP/out2/" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc -eq 0 ] && [ -s "$TMP/out2/a.info.txt" ] && [ -s "$TMP/out2/b.info.txt" ] &&
  grep -q "warning: .*mixed: 2 entries skipped" "$TMP/err" && ok || bad "mixed folder: rc $rc $(cat "$TMP/err")"
if [ -n "$PY" ]; then
  "$BIN" info "$TMP/mixed" -o "$TMP/out3/" --json 2> /dev/null > "$TMP/j" &&
    "$PY" -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert sorted(p.rsplit("/", 1)[1] for p in d["skipped"]) == ["README.txt", "sub"], d.get("skipped")
assert d["ok"] == 2 and len(d["results"]) == 2
' "$TMP/j" && ok || bad "--json skipped: $(cat "$TMP/j")"
fi
finish

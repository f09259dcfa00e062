#!/usr/bin/env bash
# `specseg geodesic` end to end: a hand-made square (exact diagonal), multi-source, max distance
# (inf), methods, usage and input errors; FAUST tr_reg_000 against the reference when data is there.
# Usage: cli_geodesic.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"

# unit square split along 0-2, plus a far vertex 4 in a second component
cat > "$TMP/sq.off" <<'EOM'
OFF
5 3 0
0 0 0
1 0 0
1 1 0
0 1 0
5 5 5
3 0 1 2
3 0 2 3
3 4 4 4
EOM

# exact: d(1,3) = sqrt(2) through the shared edge; unreached vertex is inf
if "$BIN" geodesic "$TMP/sq.off" --source 1 -o "$TMP/d.txt" 2> "$TMP/err"; then
  if awk 'NR==1{ok=($1=="1")} NR==2{ok=ok&&($1=="0")} NR==4{ok=ok&&(($1-sqrt(2))^2<1e-30)} NR==5{ok=ok&&($1=="inf")} END{exit !(ok&&NR==5)}' "$TMP/d.txt"; then ok; else bad "exact square values: $(tr '\n' ' ' < "$TMP/d.txt")"; fi
else bad "exact square exit: $(cat "$TMP/err")"; fi

# edge method: d(1,3) = 2; graph (NPP22) adds the unfolded diagonal: sqrt(2)
"$BIN" geodesic "$TMP/sq.off" --source 1 --method edge -o "$TMP/e.txt" && [ "$(sed -n 4p "$TMP/e.txt")" = "2" ] && ok || bad "edge method"
"$BIN" geodesic "$TMP/sq.off" --source 1 --method graph -o "$TMP/g.txt" && awk 'NR==4{exit !(($1-sqrt(2))^2<1e-30)}' "$TMP/g.txt" && ok || bad "graph method"

# two sources and max distance
"$BIN" geodesic "$TMP/sq.off" --source 0 --source 2 -o "$TMP/m.txt" && [ "$(sed -n 2p "$TMP/m.txt")" = "1" ] && [ "$(sed -n 3p "$TMP/m.txt")" = "0" ] && ok || bad "two sources"
"$BIN" geodesic "$TMP/sq.off" --source 0 --max-dist 1.2 -o "$TMP/r.txt" && [ "$(sed -n 3p "$TMP/r.txt")" = "inf" ] && [ "$(sed -n 2p "$TMP/r.txt")" = "1" ] && ok || bad "max-dist"

# usage errors exit 2, input errors exit 1, both with a specseg: prefix
"$BIN" geodesic "$TMP/sq.off" -o "$TMP/x.txt" 2> "$TMP/err"; [ $? -eq 2 ] && grep -q '^specseg: usage:' "$TMP/err" && ok || bad "missing --source"
"$BIN" geodesic "$TMP/sq.off" --source 0 --method fast -o "$TMP/x.txt" 2> /dev/null; [ $? -eq 2 ] && ok || bad "bad method"
"$BIN" geodesic "$TMP/sq.off" --source -1 -o "$TMP/x.txt" 2> /dev/null; [ $? -eq 2 ] && ok || bad "negative source"
"$BIN" geodesic "$TMP/sq.off" --source 0 --max-dist abc -o "$TMP/x.txt" 2> /dev/null; [ $? -eq 2 ] && ok || bad "bad max-dist"
"$BIN" geodesic "$TMP/sq.off" --source 9 -o "$TMP/x.txt" 2> "$TMP/err"; [ $? -eq 1 ] && grep -q '^specseg: error:' "$TMP/err" && ok || bad "source out of range"
"$BIN" geodesic "$TMP/missing.off" --source 0 -o "$TMP/x.txt" 2> "$TMP/err"; [ $? -eq 1 ] && grep -q '^specseg: error:' "$TMP/err" && ok || bad "missing mesh"
"$BIN" geodesic "$TMP/sq.off" --source 0 -o "$TMP/nodir/x.txt" 2> "$TMP/err"; [ $? -eq 1 ] &&
  grep -q "nodir/x.txt: cannot open for writing: No such file or directory" "$TMP/err" && ok || bad "unwritable output: $(cat "$TMP/err")"
# the reason of a failed write (was "cannot write 'P'"), to a file and to standard output
if [ -w /dev/full ]; then
  "$BIN" geodesic "$TMP/sq.off" --source 0 -o /dev/full 2> "$TMP/err"; [ $? -eq 1 ] &&
    grep -q "/dev/full: write error: No space left on device" "$TMP/err" && ok || bad "full device: $(cat "$TMP/err")"
  "$BIN" geodesic "$TMP/sq.off" --source 0 -o - > /dev/full 2> "$TMP/err"; [ $? -eq 1 ] &&
    grep -q "<stdout>: write error: No space left on device" "$TMP/err" && ok || bad "full stdout: $(cat "$TMP/err")"
fi

# FAUST reference (relative error <= 1e-9)
D=${SS_DATA_DIR:-}
if [ -n "$D" ] && [ -f "$D/faust/tr_reg_000.off" ] && [ -f "$D/geodesic_ref/tr_reg_000_src412.txt" ]; then
  if "$BIN" geodesic "$D/faust/tr_reg_000.off" --source 412 -o "$TMP/f.txt"; then
    paste "$TMP/f.txt" "$D/geodesic_ref/tr_reg_000_src412.txt" |
      awk '{r=($2>0)?($1-$2)/$2:$1; if(r<0)r=-r; if(r>m)m=r} END{exit !(NR==6890 && m<=1e-9)}' && ok || bad "FAUST reference"
  else bad "FAUST run"; fi
else
  skip "FAUST data not found"
fi

finish

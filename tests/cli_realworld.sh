#!/usr/bin/env bash
# Real-world meshes through `specseg match` (issue 13): meshes of several components (the components
# holding landmarks are matched, with a warning saying what was dropped), a mesh too small to match.
# Usage: cli_realworld.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"

# a closed surface of ~640 vertices: an icosahedron remeshed
t=1.618033988749895
{ echo OFF; echo "12 20 0"
  for v in "-1 $t 0" "1 $t 0" "-1 -$t 0" "1 -$t 0" "0 -1 $t" "0 1 $t" "0 -1 -$t" "0 1 -$t" \
           "$t 0 -1" "$t 0 1" "-$t 0 -1" "-$t 0 1"; do echo "$v"; done
  for f in "0 11 5" "0 5 1" "0 1 7" "0 7 10" "0 10 11" "1 5 9" "5 11 4" "11 10 2" "10 7 6" "7 1 8" \
           "3 9 4" "3 4 2" "3 2 6" "3 6 8" "3 8 9" "4 9 5" "2 4 11" "6 2 10" "8 6 7" "9 8 1"; do echo "3 $f"; done
} > "$TMP/ico.off"
"$BIN" remesh "$TMP/ico.off" --faces 1280 -o "$TMP/sphere.off" > /dev/null 2>&1 || { bad "remesh failed"; finish; }
S="$TMP/sphere.off"
nv=$(sed -n 2p "$S" | awk '{print $1}')
nf=$(sed -n 2p "$S" | awk '{print $2}')
# two copies, the second shifted by 3 in x
awk -v nv="$nv" -v nf="$nf" 'NR == 1 { print; next } NR == 2 { print 2 * nv, 2 * nf, 0; next }
  NR <= 2 + nv { v[NR] = $0; print; next }
  NR == 3 + nv { for (i = 3; i <= 2 + nv; i++) { split(v[i], c, " "); print c[1] + 3, c[2], c[3] } }
  NR > 2 + nv { f[NR] = $0; print }
  END { for (i = 3 + nv; i <= 2 + nv + nf; i++) { split(f[i], c, " "); print 3, c[2] + nv, c[3] + nv, c[4] + nv } }' \
  "$S" > "$TMP/two.off"
[ "$(sed -n 2p "$TMP/two.off")" = "$((2 * nv)) $((2 * nf)) 0" ] && ok || bad "two spheres header"
printf '0\n100\n300\n' > "$TMP/lm.txt"
# landmarks on the first sphere of each: that sphere is matched, the second dropped with a warning
# (was "fmap: normal equations not positive definite (dsposv info 258)")
"$BIN" match "$TMP/two.off" "$TMP/two.off" --landmarks "$TMP/lm.txt" --k 20 -o "$TMP/map.txt" > /dev/null 2> "$TMP/err" &&
  ok || bad "two spheres: $(cat "$TMP/err")"
grep -q "warning: .*two.off: X (the first mesh): matched the 1 of its 2 components that hold a landmark" "$TMP/err" &&
  grep -q "Y (the second mesh): matched the 1 of its 2 components" "$TMP/err" && ok || bad "no warning: $(cat "$TMP/err")"
[ "$(grep -c . "$TMP/map.txt")" = $((2 * nv)) ] && ok || bad "map has $(grep -c . "$TMP/map.txt") lines"
awk -v n="$nv" 'NR <= n && $1 != NR - 1 { bad++ } $1 >= n { bad++ } END { exit bad > 0 }' "$TMP/map.txt" && ok ||
  bad "the first sphere does not map onto itself / an image on the dropped sphere"
# landmarks on both spheres: both matched, no warning
printf '0\n100\n300\n%d\n%d\n%d\n' "$nv" $((nv + 100)) $((nv + 300)) > "$TMP/lm6.txt"
"$BIN" match "$TMP/two.off" "$TMP/two.off" --landmarks "$TMP/lm6.txt" --k 20 -o "$TMP/map6.txt" > /dev/null 2> "$TMP/err" &&
  ! grep -q warning "$TMP/err" && ok || bad "landmarks on both spheres: $(cat "$TMP/err")"

# one triangle: says its size and what is needed (was "match: empty mesh")
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n' > "$TMP/tri.off"
echo 0 > "$TMP/lm0.txt"
"$BIN" match "$TMP/tri.off" "$S" --landmarks "$TMP/lm0.txt" -o "$TMP/m.txt" > /dev/null 2> "$TMP/err"; [ $? = 1 ] &&
  grep -q "error: match: X (the first mesh): the mesh has 3 vertices and 1 face: too small to match" "$TMP/err" && ok ||
  bad "one triangle: $(cat "$TMP/err")"

finish

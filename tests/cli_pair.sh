#!/usr/bin/env bash
# `specseg pair` and `specseg match` without --landmarks on the built-in humanoid (two poses of one
# vertex order, so the ground truth is the identity): the report, the -o landmark file (usable by
# `match --landmarks`), the confidence line, the landmark-free match's summary, usage errors.
# Usage: cli_pair.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
demo_outputs "$TMP/demo" || { bad "demo"; finish; }
A="$TMP/demo/humanoid_pose0.off"
B=$(ls "$TMP"/demo/humanoid_pose*.off | grep -v pose0 | head -1)
"$BIN" pair "$A" "$B" -o "$TMP/pairs.txt" > "$TMP/out" 2>&1 && ok || bad "pair: $(cat "$TMP/out")"
grep -q 'paired (exact search)' "$TMP/out" && ok || bad "pair report: $(cat "$TMP/out")"
grep -Eq '^(confident|NOT confident)' "$TMP/out" && ok || bad "confidence line: $(cat "$TMP/out")"
np=$(sed -n 's/.* \([0-9]*\) paired (exact.*/\1/p' "$TMP/out")
[ -n "$np" ] && [ "$(wc -l < "$TMP/pairs.txt")" -eq "$np" ] && ok || bad "-o: $np pairs, $(wc -l < "$TMP/pairs.txt") lines"
# every pair's centres: two vertex indices
awk 'NF != 2 || $1 !~ /^[0-9]+$/ || $2 !~ /^[0-9]+$/ { exit 1 }' "$TMP/pairs.txt" && ok || bad "pairs file format"
# the pairs file is a landmark file for match
"$BIN" match "$A" "$B" --landmarks "$TMP/pairs.txt" --no-refine -o "$TMP/m1.txt" > "$TMP/out" 2>&1 && ok ||
  bad "match --landmarks PAIRS: $(cat "$TMP/out")"
# landmark-free match: its pairing line and a map of the right length
"$BIN" match "$A" "$B" --no-refine -o "$TMP/m0.txt" > "$TMP/out" 2>&1 && ok || bad "match without landmarks: $(cat "$TMP/out")"
grep -q '^landmark-free pairing' "$TMP/out" && grep -q '(paired protrusion centres)' "$TMP/out" && ok || bad "match summary: $(cat "$TMP/out")"
grep -Eq '^hypotheses: ([2-9]|1[0-6]) mapped( \([0-9]+ more skipped\))?, #([0-9]|1[0-5])( \(the descriptors. own\)| \(the flip of #[0-9]+ by [XY].s symmetry\)| \(from Y.s side\))? kept \(energy [^)]*orientation -?[0-9.]+; margin' "$TMP/out" && ok || bad "hypotheses line: $(cat "$TMP/out")"
[ "$(wc -l < "$TMP/m0.txt")" -eq "$(sed -n 2p "$A" | awk '{print $1}')" ] && ok || bad "map length"
if grep -q '^hypotheses: .*NOT confident' "$TMP/out"; then grep -q '^note: landmark-free map NOT confident' "$TMP/out" && ok || bad "no note for a map that is not confident"; fi
# --json: the hypotheses, the one kept, the margin behind the confidence
"$BIN" match "$A" "$B" --no-refine -o "$TMP/m0j.txt" --json > "$TMP/j.json" 2> "$TMP/err" && ok || bad "match --json: $(cat "$TMP/err")"
cmp -s "$TMP/m0.txt" "$TMP/m0j.txt" && ok || bad "--json changed the map"
python3 - "$TMP/j.json" <<'PY' && ok || bad "hypotheses in --json: $(cat "$TMP/j.json")"
import json, sys
r = json.load(open(sys.argv[1]))["results"][0]
H, b = r["hypotheses"], r["hypothesis"]
assert 2 <= len(H) <= 16 and 0 <= b < len(H), (len(H), b)
assert all(h.get("from", "Y") == "Y" for h in H)
assert all("from" not in h for h in H[:r["descriptor_candidate"] + 1])  # X's own first
E = [h["energy"] for h in H]
assert E[b] == min(E), E
# the margin: against the candidates whose maps differ from the kept one, in its orientation class
up = lambda h: h["orientation"] >= 0
M = [e - E[b] for i, e in enumerate(E) if i != b and H[i]["differ"] >= 0.05 and up(H[i]) == up(H[b])]
assert (not M and r["hypothesis_margin"] is None) or abs(r["hypothesis_margin"] - min(M)) < 1e-12, (M, r)
assert 0 <= r["descriptor_candidate"] < len(H)
for h in H:
    assert 0 <= h["reversed"] <= 1 and h["distortion"] >= 0 and -1 <= h["orientation"] <= 1
    assert abs(h["energy"] - (h["distortion"] + 0.05 * h["reversed"])) < 1e-12
assert r["confident"] == ((r["hypothesis_margin"] is None or r["hypothesis_margin"] >= 0.003) and H[b]["orientation"] >= 0.45)
PY
# landmark-free match of meshes with a crumb (a small sphere beside the body): the largest component
# of each is matched, the crumb dropped with a warning (was: no landmark on any component)
S="$TMP/demo/sphere.off"
crumb() {
  awk 'FNR == 1 { k++; next } FNR == 2 { n[k] = $1; m[k] = $2; next } { L[k, ++c[k]] = $0 }
    END { print "OFF"; print n[1] + n[2], m[1] + m[2], 0
          for (i = 1; i <= n[1]; i++) print L[1, i]
          for (i = 1; i <= n[2]; i++) { split(L[2, i], a, " "); print a[1] * 0.05 + 3, a[2] * 0.05, a[3] * 0.05 }
          for (i = n[1] + 1; i <= n[1] + m[1]; i++) print L[1, i]
          for (i = n[2] + 1; i <= n[2] + m[2]; i++) { split(L[2, i], a, " "); print 3, a[2] + n[1], a[3] + n[1], a[4] + n[1] } }' "$1" "$S"
}
crumb "$A" > "$TMP/ac.off"; crumb "$B" > "$TMP/bc.off"
nva=$(sed -n 2p "$A" | awk '{print $1}')
"$BIN" match "$TMP/ac.off" "$TMP/bc.off" --no-refine -o "$TMP/mc.txt" > "$TMP/out" 2>&1 && ok || bad "crumbs, no landmarks: $(cat "$TMP/out")"
grep -q 'X (the first mesh): matched the 1 of its 2 components that is the largest' "$TMP/out" &&
  grep -q 'Y (the second mesh): matched the 1 of its 2 components that is the largest' "$TMP/out" && ok ||
  bad "crumb warning: $(cat "$TMP/out")"
awk -v n="$nva" 'NR <= n && $1 >= n { b++ } END { exit b > 0 }' "$TMP/mc.txt" && ok || bad "body vertices mapped onto the crumb"
# report to stderr when the pairs go to stdout
"$BIN" pair "$A" "$B" -o - > "$TMP/so" 2> "$TMP/se" && [ "$(wc -l < "$TMP/so")" -eq "$np" ] && grep -q 'energy' "$TMP/se" && ok ||
  bad "pair -o -"
# usage errors
"$BIN" pair "$A" > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "one mesh: exit 2"
"$BIN" pair "$A" "$B" --bogus > /dev/null 2>&1; [ $? -eq 2 ] && ok || bad "unknown option: exit 2"
"$BIN" match "$A" "$B" --skip-tol -1 -o "$TMP/ms.txt" > /dev/null 2> "$TMP/err"; [ $? -eq 2 ] &&
  grep -q "^specseg: usage: match: --skip-tol needs a value between 0 and 1e6, not '-1'" "$TMP/err" && ok ||
  bad "--skip-tol -1: $(cat "$TMP/err")"
"$BIN" pair "$A" "$TMP/missing.off" > /dev/null 2>&1; [ $? -eq 1 ] && ok || bad "missing file: exit 1"
"$BIN" pair --help | grep -q 'usage: specseg pair' && ok || bad "--help"
finish

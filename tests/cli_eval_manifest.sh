#!/usr/bin/env bash
# `specseg eval --table1 --manifest` end to end on three small synthetic ellipsoids (written here by
# tests/data/eval/ellipsoid.awk, same connectivity): a group with identity ground truth and one with a
# ground-truth map file (the identity written out, so its rows must equal the identity group's for the
# same meshes), the expected rows, resume (nothing new; a cut file completed to the same rows), the
# per-group table, malformed manifests (exit 1, "specseg: error: FILE:LINE: ..."), usage errors (2);
# with FAUST data, the built-in FAUST default gives the rows of tests/data/eval/faust_tiny_rows.csv.
# Usage: cli_eval_manifest.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
HERE=$(cd "$(dirname "$0")" && pwd)
. "$HERE/lib_cli.sh"

# usage errors
"$BIN" eval --table1 --manifest "$TMP/m" --data /x > /dev/null 2>&1; [ $? = 2 ] && ok || bad "--manifest with --data: exit != 2"
"$BIN" eval --coherency --manifest "$TMP/m" > /dev/null 2>&1; [ $? = 2 ] && ok || bad "--manifest without --table1: exit != 2"
"$BIN" eval --table1 --manifest "$TMP/m" --pairing sometimes > /dev/null 2>&1; [ $? = 2 ] && ok || bad "bad --pairing: exit != 2"

# three ellipsoids; P bends them (same connectivity: ground truth = identity)
M=$TMP/data
mkdir -p "$M/meshes" "$M/maps"
for p in 0 1 2; do awk -v P=$p -f "$HERE/data/eval/ellipsoid.awk" > "$M/meshes/e$p.off"; done
NV=$(sed -n 2p "$M/meshes/e0.off" | cut -d' ' -f1)
seq 0 $((NV - 1)) > "$M/maps/identity.txt"
cat > "$M/set.manifest" << 'MAN'
specseg-manifest 1
# identity ground truth, the paper's FPS procedure on e0 for the GT landmarks
group ell
gt identity
landmarks fps e0
mesh meshes/e0.off
mesh meshes/e2.off
pairs all
# the same two meshes with a ground-truth map file
group mapped
gt maps
mesh meshes/e0.off name m0
mesh meshes/e2.off name m2
mesh meshes/e1.off name m1
pair m0 m2
map m0 m2 maps/identity.txt
MAN
ARGS=(eval --table1 --manifest "$M/set.manifest" --landmarks gt,fps --methods std,diff --k 20 --cache "$TMP/cache" --quiet)
"$BIN" "${ARGS[@]}" --out "$TMP/r.csv" > "$TMP/r.out" 2> "$TMP/err" && ok || bad "manifest run: $(cat "$TMP/err")"
N=$(($(wc -l < "$TMP/r.csv") - 1))
[ "$N" = 12 ] && ok || bad "manifest run wrote $N rows, want 12 (3 pairs x 2 landmark sets x 2 methods)"
# pair (m0 -> m2) = (2, 3) through the identity map file equals (e0 -> e2) = (0, 1)
for lm in gt fps; do for m in std diff; do
  a=$(grep "^random,$lm,$m,0,1," "$TMP/r.csv" | cut -d, -f6-10)
  b=$(grep "^random,$lm,$m,2,3," "$TMP/r.csv" | cut -d, -f6-10)
  [ -n "$a" ] && [ "$a" = "$b" ] && ok || bad "$lm $m: map-file rows differ from identity rows: '$a' vs '$b'"
done; done
grep -Eq '^ell +gt ' "$TMP/r.out" && grep -Eq '^mapped +fps ' "$TMP/r.out" && grep -q 'DIFF/STD' "$TMP/r.out" && ok ||
  bad "per-group table missing: $(cat "$TMP/r.out")"
# the cache names entries by mesh name; m0 is e0 (same content): one entry serves both
ls "$TMP"/cache/e0_*.bin > /dev/null 2>&1 && ok || bad "no cache entry named after e0"

# resume: nothing new; a cut file is completed to the same rows (timings aside)
"$BIN" "${ARGS[@]}" --out "$TMP/r.csv" > /dev/null 2> "$TMP/err" && ok || bad "re-run: $(cat "$TMP/err")"
[ $(($(wc -l < "$TMP/r.csv") - 1)) = 12 ] && ok || bad "re-run added rows"
head -n 6 "$TMP/r.csv" > "$TMP/cut.csv"; head -c 25 <(sed -n 7p "$TMP/r.csv") >> "$TMP/cut.csv"
"$BIN" "${ARGS[@]}" --out "$TMP/cut.csv" > /dev/null 2> "$TMP/err" && ok || bad "resume: $(cat "$TMP/err")"
cut -d, -f1-10,12 "$TMP/r.csv" | sort > "$TMP/a"; cut -d, -f1-10,12 "$TMP/cut.csv" | sort > "$TMP/b"
cmp -s "$TMP/a" "$TMP/b" && ok || bad "resumed rows differ: $(diff "$TMP/a" "$TMP/b" | head -4)"
# merge with the manifest prints the same per-group table
"$BIN" eval merge "$TMP/cut.csv" --manifest "$M/set.manifest" > "$TMP/merge.out" 2> "$TMP/err" && ok || bad "merge: $(cat "$TMP/err")"
diff <(grep -E '^(ell|mapped) ' "$TMP/merge.out") <(grep -E '^(ell|mapped) ' "$TMP/r.out") > /dev/null && ok ||
  bad "merge table differs from the run's"

# malformed manifests and files: exit 1, one clear message
expect_error() { # manifest-text expected-message-part
  printf '%b' "$1" > "$M/bad.manifest"
  "$BIN" eval --table1 --manifest "$M/bad.manifest" --out "$TMP/bad.csv" --quiet > /dev/null 2> "$TMP/err"
  local rc=$?
  [ $rc = 1 ] && grep -q "^specseg: error: .*$2" "$TMP/err" && ok || bad "'$2': exit $rc, $(cat "$TMP/err")"
}
expect_error 'mesh meshes/e0.off\n' "bad.manifest:1: not a specseg manifest"
expect_error 'specseg-manifest 1\nmesh meshes/e0.off\nmesh meshes/e1.off\npiar e0 e1\n' "bad.manifest:4: unknown directive 'piar'"
expect_error 'specseg-manifest 1\nmesh meshes/e0.off\nmesh meshes/e1.off\npair e0 e9\n' "bad.manifest:4: no mesh named 'e9'"
expect_error 'specseg-manifest 1\nmesh meshes/none.off\nmesh meshes/e1.off\n' "none.off"
expect_error 'specseg-manifest 1\ngt maps\nmesh meshes/e0.off\nmesh meshes/e1.off\npair e0 e1\nmap e0 e1 maps/none.txt\n' "none.txt"
head -n 5 "$M/maps/identity.txt" > "$M/maps/short.txt"
expect_error 'specseg-manifest 1\ngt maps\nmesh meshes/e0.off\nmesh meshes/e1.off\npair e0 e1\nmap e0 e1 maps/short.txt\n' "short.txt: 5 lines"
printf '0\n1\n2\n' > "$M/three.lm"
expect_error "specseg-manifest 1\nlandmarks file three.lm\nmesh meshes/e0.off\nmesh meshes/e1.off\n" "three.lm: 3 landmarks, 5 expected"
"$BIN" eval --table1 --manifest "$M/set.manifest" --landmarks best --out "$TMP/b.csv" --quiet > /dev/null 2> "$TMP/err"
[ $? = 1 ] && grep -q "no landmarks for the set 'best'" "$TMP/err" && ok || bad "best without landmark files: $(cat "$TMP/err")"

# the FAUST default is unchanged: the tiny run of cli_eval.sh gives the stored rows
D=${SS_DATA_DIR:-}
if [ -z "$D" ] || [ ! -f "$D/faust/tr_reg_000.off" ]; then
  skip "no FAUST data (set SS_DATA_DIR); FAUST default rows not checked"
  finish
fi
"$BIN" eval --table1 --data "$D" --pairs 1 --seed 7 --policies random,pose --landmarks best,fps --methods std,asa --k 20 \
  --error-samples 8 --out "$TMP/faust.csv" --quiet > /dev/null 2> "$TMP/err" && ok || bad "FAUST run: $(cat "$TMP/err")"
cut -d, -f1-10,12 "$TMP/faust.csv" | sort > "$TMP/f"
# integers exactly, errors to 1e-12 relative (another BLAS may round the last bits differently)
awk -F, 'NR==FNR { ref[FNR] = $0; n = FNR; next }
         { split(ref[FNR], r, ","); if (NF != 11) bad++
           for (i = 1; i <= 11; i++) if (i == 6 || i == 7) { d = $i - r[i]; if (d < 0) d = -d; if (FNR > 1 && d > 1e-12 * (r[i] < 0 ? -r[i] : r[i])) bad++ }
                                     else if ($i != r[i]) bad++ }
         END { exit (bad || FNR != n) ? 1 : 0 }' "$HERE/data/eval/faust_tiny_rows.csv" "$TMP/f" && ok ||
  bad "FAUST default rows changed: $(diff "$HERE/data/eval/faust_tiny_rows.csv" "$TMP/f" | head -4)"
finish

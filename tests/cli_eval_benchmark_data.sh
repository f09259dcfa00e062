#!/usr/bin/env bash
# `specseg eval --benchmark` on the tuning split of the remeshed benchmarks (SS_DATA_DIR/bcicp_tune,
# the BCICP layout): TOSCA_r with the truncated horse7.off (a real broken file: its pair is skipped
# with a warning, the run goes on), our landmark-free map equal to `specseg match X Y`'s, every scored
# number equal to `specseg error` on the K-point files (tests/python/bench_check.py); --landmarks gt:5
# from the same cache: the five points are the Euclidean farthest-point sample of cat0's points (the data set's first shape) from
# point 0 (recomputed here) and the map is `specseg match --landmarks` with those points.
# SKIPs when the folder is absent.
# Usage: cli_eval_benchmark_data.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
HERE=$(cd "$(dirname "$0")" && pwd)
. "$HERE/lib_cli.sh"
. "$HERE/lib_bench.sh"
D=${SS_DATA_DIR:-$HERE/../../shared/data}/bcicp_tune
[ -d "$D/TOSCA_Isometric/vtx_5k" ] || { skip "no $D (the remeshed benchmarks' tuning split)"; finish; }
[ -n "$PY" ] || { skip "no python3 for the checks"; finish; }
check() { PYTHONDONTWRITEBYTECODE=1 "$PY" "$HERE/python/bench_check.py" "$@"; }
REC=$TMP/rec.txt

# TOSCA_r: a pair with the broken horse7 and a cat pair
T=$D/TOSCA_Isometric
printf 'horse0\thorse7\ncat3\tcat5\n' > "$TMP/pairs.txt"
"$BIN" eval --benchmark "$T" --pairs "$TMP/pairs.txt" --out "$TMP/t" --cache "$TMP/cache" --jobs 2 --quiet > "$TMP/o1" 2> "$TMP/e1"; rc=$?
[ $rc = 0 ] && ok || bad "TOSCA_r run: rc $rc: $(cat "$TMP/e1")"
grep -q "warning: .*horse7.off:.*: its 1 pair skipped" "$TMP/e1" && ok || bad "no warning for horse7.off: $(cat "$TMP/e1")"
grep -q '^specseg,horse0,horse7,.*,skipped,' "$TMP/t/pairs.csv" && ok || bad "horse0 -> horse7 not a skipped row"
# (specseg match on the cache's prepared shapes, specseg prepare's files: the map it gives from the meshes)
"$BIN" match "$TMP"/cache/cat3_*.sss "$TMP"/cache/cat5_*.sss -o "$TMP/m.txt" > /dev/null 2>&1 &&
  cmp -s "$TMP/m.txt" "$TMP/t/maps/cat3__cat5.txt" && ok || bad "maps/cat3__cat5.txt differs from specseg match"
# the hypotheses mapped are distinct: on cat3 -> cat5 the search's first four pairings keep the same
# protrusion pairs twice over (energies 0.08497, 0.08497, 0.08813, 0.08813 before duplicates were skipped)
"$BIN" match "$TMP"/cache/cat3_*.sss "$TMP"/cache/cat5_*.sss -o "$TMP/m3.txt" --json > "$TMP/j3" 2> /dev/null &&
  "$PY" -c 'import json, sys
h = [c["energy"] for c in json.load(open(sys.argv[1]))["results"][0]["hypotheses"]]
sys.exit(0 if len(h) >= 3 and len(set(h)) == len(h) else "energies %s" % h)' "$TMP/j3" && ok ||
  bad "cat3 -> cat5: distinct hypotheses wanted: $(head -c 600 "$TMP/j3")"
# ... and the one of least distortion there is a mirror image (whole-map orientation below 0): the map
# kept preserves orientation, has the least energy of those that do, and when its score is below
# hyp_confident_orientation (0.45) it is not confident
"$PY" -c 'import json, sys
r = json.load(open(sys.argv[1]))["results"][0]; H = r["hypotheses"]; k = H[r["hypothesis"]]
low = min(H, key=lambda c: c["distortion"])
ok = low["orientation"] < 0 and k["orientation"] >= 0 and k["distortion"] > low["distortion"]
ok = ok and all(k["energy"] <= c["energy"] for c in H if c["orientation"] >= 0)
ok = ok and (k["orientation"] >= 0.45 or (not r["confident"] and "orientation score" in r["notes"]))
sys.exit(0 if ok else "kept %s of %s" % (r["hypothesis"], H))' "$TMP/j3" && ok ||
  bad "cat3 -> cat5: the orientation-preserving hypothesis wanted: $(head -c 900 "$TMP/j3")"
: > "$REC"
recompute specseg cat3 cat5 "$TMP/t/maps/cat3__cat5.txt" "$T/vtx_5k"
check "$TMP/t" "$REC" specseg:2:1:1 > "$TMP/c1" && ok || bad "TOSCA_r summary: $(cat "$TMP/c1")"

# --landmarks gt:5 on the same shapes: the cache's entries serve it too; the five points are the FPS of
# cat0's points (the data set's first shape by name)
printf 'cat3\tcat5\n' > "$TMP/p1.txt"
"$BIN" eval --benchmark "$T" --pairs "$TMP/p1.txt" --landmarks gt:5 --out "$TMP/g" --cache "$TMP/cache" --jobs 2 > "$TMP/o2" 2> "$TMP/e2"; rc=$?
[ $rc = 0 ] && ok || bad "gt:5 run: rc $rc: $(cat "$TMP/e2")"
grep -q "(0 prepared, 2 from the cache)" "$TMP/e2" && ok || bad "gt:5 did not use the landmark-free run's cache: $(grep prepared "$TMP/e2")"
V=$T/vtx_5k
want=$(awk 'FNR == 1 { f++ } f == 1 && FNR == 2 { nv = $1 } f == 1 && FNR >= 3 && FNR < 3 + nv { X[FNR - 3] = $1; Y[FNR - 3] = $2; Z[FNR - 3] = $3 }
  f == 2 { p[n++] = $1 - 1 }
  END { for (k = 0; k < n; k++) d[k] = -1; c = 0
    for (j = 0; j < 5; j++) { printf " %d", c; bd = -1
      for (k = 0; k < n; k++) { q = sqrt((X[p[k]] - X[p[c]])^2 + (Y[p[k]] - Y[p[c]])^2 + (Z[p[k]] - Z[p[c]])^2)
        if (d[k] < 0 || q < d[k]) d[k] = q
        if (d[k] > bd) { bd = d[k]; b = k } }
      c = b } }' "$V/cat0.off" "$V/corres/cat0.vts")
grep -q "landmarks: 5 ground-truth points by farthest-point sampling on cat0 from its point 0:$want\$" "$TMP/e2" && ok ||
  bad "landmarks: want$want; $(grep landmarks: "$TMP/e2")"
# the map of specseg match with those points as landmarks (vts_X[k] - 1, vts_Y[k] - 1)
for k in $want; do
  echo "$(($(sed -n "$((k + 1))p" "$V/corres/cat3.vts") - 1)) $(($(sed -n "$((k + 1))p" "$V/corres/cat5.vts") - 1))"
done > "$TMP/lm.txt"
"$BIN" match "$TMP"/cache/cat3_*.sss "$TMP"/cache/cat5_*.sss --landmarks "$TMP/lm.txt" -o "$TMP/m2.txt" > /dev/null 2>&1 &&
  cmp -s "$TMP/m2.txt" "$TMP/g/maps/cat3__cat5.txt" && ok || bad "the gt:5 map differs from specseg match --landmarks"
: > "$REC"
recompute specseg_gt5 cat3 cat5 "$TMP/g/maps/cat3__cat5.txt" "$V"
check "$TMP/g" "$REC" specseg_gt5:1:1:0 > "$TMP/c2" && ok || bad "gt:5 summary: $(cat "$TMP/c2")"
finish

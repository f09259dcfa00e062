#!/usr/bin/env bash
# `specseg eval --figures`: usage errors (2) without data; with FAUST, a small run (2-shape gallery,
# Figure 9 of a given pair, 100x200 panels, k = 20) writes PNGs of the expected layout: the gallery
# 2 panels wide with segment colours, the map figure 5 panels + colour bar wide, 2 rows + heading
# high, with heat-map red in its error row; --gallery-only writes no map figure; the showcase rule
# (--candidates 3: the median of the candidates' mean errors, the candidates the first pairs drawn,
# the figure's errors those the pair was scored with) through --json.
# Usage: cli_eval_figures.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"

expect2() { "$BIN" eval "$@" > /dev/null 2>&1; [ $? = 2 ] && ok || bad "eval $* -> exit != 2"; }
expect2 --figures "$TMP/f"                                  # no --data
expect2 --figures "$TMP/f" --data /nonexistent --pair 3,3
expect2 --figures "$TMP/f" --data /nonexistent --pair 3
expect2 --figures "$TMP/f" --data /nonexistent --pair 3,100
expect2 --figures "$TMP/f" --data /nonexistent --size 5x5
expect2 --figures "$TMP/f" --data /nonexistent --landmarks worst
expect2 --figures "$TMP/f" --data /nonexistent --gallery-count 101
expect2 --figures "$TMP/f" --table1 --data /nonexistent
"$BIN" eval --figures "$TMP/f" --data "$TMP" --gallery-count 1 > /dev/null 2> "$TMP/err"
[ $? = 1 ] && grep -q "^specseg: error: " "$TMP/err" && ok || bad "missing data: not exit 1 with an error line"

D=${SS_DATA_DIR:-}
if [ -z "$D" ] || [ ! -f "$D/faust/tr_reg_001.off" ]; then
  skip "no FAUST data (set SS_DATA_DIR); figures not rendered"
  finish
fi

OUT="$TMP/figs"
"$BIN" eval --figures "$OUT" --data "$D" --gallery-count 2 --pair 1,0 --size 100x200 --k 20 > "$TMP/out" 2> "$TMP/err" &&
  ok || bad "eval --figures: $(tail -3 "$TMP/err")"
G="$OUT/faust_gallery.png" F="$OUT/figure9_001_000.png"
[ -s "$G" ] && ok || bad "no $G"
[ -s "$F" ] && ok || bad "no $F"
grep -q "faust_gallery.png: Figure 3" "$TMP/out" && grep -q "figure9_001_000.png: Figure 9, FAUST best" "$TMP/out" && ok ||
  bad "summary lines missing: $(cat "$TMP/out")"
grep -Eq "mean error STD 0\.[0-9]+ ASA 0\.[0-9]+ DIFF 0\.[0-9]+" "$TMP/out" && ok || bad "no mean errors printed"
if [ -z "$PY" ]; then
  skip "PNG checks (no python3)"
elif [ -s "$G" ] && [ -s "$F" ]; then
  # gallery: 2 panels of 100x200 in a row, a 13-pixel title line under them (text scale 1)
  [ "$(png "$G" size)" = "200 213" ] && ok || bad "gallery size $(png "$G" size), want 200 213"
  # corresponding segments share colours (aligned to tr_reg_000): the first label colours show in both panels
  for col in "230 25 75" "60 180 75" "255 200 25"; do
    a=$(png "$G" chroma $col 100); b=$(png "$G" chroma $col)
    [ "$a" -ge 10 ] && [ $((b - a)) -ge 10 ] && ok || bad "segment colour $col: $a pixels left, $((b - a)) right"
  done
  # map figure: 5 columns of 100 + the colour bar's column; heading 15 + 2 rows of (200 + 13)
  read -r W H <<< "$(png "$F" size)"
  [ "$H" = 441 ] && [ "$W" -gt 520 ] && [ "$W" -lt 620 ] && ok || bad "figure size $W x $H, want 5x100 + bar by 441"
  # the error row (x < 400: the three heat maps and the ground-truth panel) shows red somewhere
  [ "$(png "$F" red 400)" -gt 0 ] && ok || bad "no heat-map red in the figure"
  [ "$(png "$F" pixel 0 0)" = "255 255 255" ] && ok || bad "background corner"
fi
# --gallery-only: the gallery, no map figure
"$BIN" eval --figures "$TMP/g" --data "$D" --gallery-only --gallery-count 1 --size 64x128 > "$TMP/out2" 2> "$TMP/err" &&
  ok || bad "--gallery-only: $(tail -3 "$TMP/err")"
[ -s "$TMP/g/faust_gallery.png" ] && [ -z "$(ls "$TMP/g" | grep figure)" ] && ok || bad "--gallery-only wrote $(ls "$TMP/g")"

# the showcase pair: the median of 3 candidates, checked through --json (no --pair)
if [ -z "$PY" ]; then
  skip "showcase rule (no python3)"
else
  SA=(eval --data "$D" --gallery-count 0 --size 40x80 --k 20 --cache "$TMP/cache" --json)
  "$BIN" "${SA[@]}" --figures "$TMP/s3" --candidates 3 > "$TMP/s3.json" 2> "$TMP/err" && ok || bad "--candidates 3: $(tail -3 "$TMP/err")"
  "$BIN" "${SA[@]}" --figures "$TMP/s1" --candidates 1 > "$TMP/s1.json" 2> "$TMP/err" && ok || bad "--candidates 1: $(tail -3 "$TMP/err")"
  "$PY" - "$TMP" <<'PYEOF' && ok || bad "the showcase pair is not the median of the candidates"
import json, os, sys
t = sys.argv[1]
d3, d1 = (json.load(open(t + "/s%d.json" % n)) for n in (3, 1))
f3, = d3["results"][0]["figures"]
f1, = d1["results"][0]["figures"]
c = f3["candidates"]
assert len(c) == 3 and "median" in f3["rule"] and f3["figure"] == 9 and f3["landmarks"] == "best", f3
med = sorted(c, key=lambda p: p["score"])[1]
assert (f3["x"], f3["y"]) == (med["x"], med["y"]), (f3, med)
# the figure's errors are those the pair was scored with
e = f3["mean_error"]
assert abs((e["std"] + e["asa"] + e["diff"]) / 3 - med["score"]) < 1e-12, (e, med)
# --candidates 1: the first pair drawn, the first candidate of the three
assert (f1["x"], f1["y"]) == (c[0]["x"], c[0]["y"]) and "first" in f1["rule"] and "candidates" not in f1, f1
assert os.path.exists(f3["path"]) and d3["results"][0]["outputs"] == [f3["path"]], d3
PYEOF
fi

finish

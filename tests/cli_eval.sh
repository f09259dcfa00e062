#!/usr/bin/env bash
# `specseg eval` end to end on a tiny Table 1 run over FAUST: a single run and two shards merged give
# the same rows (bit for bit, timings aside) and the same table; a re-run resumes (nothing new); an
# interrupted file (partial last line) is completed; usage (2) and input (1) errors.
# Usage: cli_eval.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"

# usage errors need no data
"$BIN" eval > /dev/null 2>&1; [ $? = 2 ] && ok || bad "no mode: exit != 2"
"$BIN" eval --table1 --data /nonexistent --shard 3/2 > /dev/null 2>&1; [ $? = 2 ] && ok || bad "bad shard: exit != 2"
"$BIN" eval --table1 --data /nonexistent --methods foo > /dev/null 2>&1; [ $? = 2 ] && ok || bad "bad method: exit != 2"
"$BIN" eval merge > /dev/null 2>&1; [ $? = 2 ] && ok || bad "merge without files: exit != 2"
"$BIN" eval merge "$TMP/none.csv" > /dev/null 2>&1; [ $? = 1 ] && ok || bad "merge of a missing file: exit != 1"
"$BIN" eval --table1 --data "$TMP" --out "$TMP/x.csv" --quiet > /dev/null 2>&1; [ $? = 1 ] && ok || bad "missing data: exit != 1"

D=${SS_DATA_DIR:-}
if [ -z "$D" ] || [ ! -f "$D/faust/tr_reg_000.off" ]; then
  skip "no FAUST data (set SS_DATA_DIR); shard/merge identity not checked"
  finish
fi

# tiny: 1 pair per policy, BEST and FPS landmarks, STD and ASA, small basis and error sample
ARGS=(eval --table1 --data "$D" --pairs 1 --seed 7 --policies random,pose --landmarks best,fps --methods std,asa
      --k 20 --error-samples 8 --cache "$TMP/cache" --quiet)
"$BIN" "${ARGS[@]}" --out "$TMP/single.csv" > "$TMP/single.out" 2> "$TMP/err" && ok || bad "single run: $(cat "$TMP/err")"
N=$(($(wc -l < "$TMP/single.csv") - 1))
[ "$N" = 8 ] && ok || bad "single run wrote $N rows, want 8"
"$BIN" "${ARGS[@]}" --shard 1/2 --out "$TMP/s1.csv" > /dev/null 2> "$TMP/err" && ok || bad "shard 1: $(cat "$TMP/err")"
"$BIN" "${ARGS[@]}" --shard 2/2 --out "$TMP/s2.csv" > /dev/null 2> "$TMP/err" && ok || bad "shard 2: $(cat "$TMP/err")"
N1=$(($(wc -l < "$TMP/s1.csv") - 1)); N2=$(($(wc -l < "$TMP/s2.csv") - 1))
[ $((N1 + N2)) = 8 ] && [ "$N1" -gt 0 ] && [ "$N2" -gt 0 ] && ok || bad "shards wrote $N1 + $N2 rows"
"$BIN" eval merge "$TMP/s1.csv" "$TMP/s2.csv" --out "$TMP/merged.csv" > "$TMP/merged.out" 2> "$TMP/err" && ok ||
  bad "merge: $(cat "$TMP/err")"
"$BIN" eval merge "$TMP/single.csv" --out "$TMP/single_sorted.csv" > "$TMP/sorted.out" 2> "$TMP/err" && ok ||
  bad "merge single: $(cat "$TMP/err")"
# identical rows except the timing column (11th)
cut -d, -f1-10,12 "$TMP/merged.csv" > "$TMP/a"; cut -d, -f1-10,12 "$TMP/single_sorted.csv" > "$TMP/b"
cmp -s "$TMP/a" "$TMP/b" && ok || bad "sharded rows differ from the single run: $(diff "$TMP/a" "$TMP/b" | head -4)"
# and the same table
grep -A20 '^Table 1' "$TMP/merged.out" > "$TMP/ta"; grep -A20 '^Table 1' "$TMP/single.out" > "$TMP/tb"
[ -s "$TMP/ta" ] && cmp -s "$TMP/ta" "$TMP/tb" && ok || bad "merged table differs from the single run's"
grep -q 'FAUST BEST' "$TMP/single.out" && grep -q 'FAUST pose FPS' "$TMP/single.out" && grep -q 'FAUST sym BEST' "$TMP/single.out" &&
  ok || bad "table rows missing"

# resume: a second run computes nothing; an interrupted file is completed to the same rows
"$BIN" "${ARGS[@]}" --out "$TMP/single.csv" > /dev/null 2> "$TMP/err" && ok || bad "re-run: $(cat "$TMP/err")"
[ $(($(wc -l < "$TMP/single.csv") - 1)) = 8 ] && ok || bad "re-run added rows"
head -c -40 "$TMP/merged.csv" | head -n 6 > "$TMP/cut.csv"      # 5 rows + a partial line
head -c 30 <(sed -n 7p "$TMP/merged.csv") >> "$TMP/cut.csv"
"$BIN" "${ARGS[@]}" --out "$TMP/cut.csv" > /dev/null 2> "$TMP/err" && ok || bad "resume: $(cat "$TMP/err")"
"$BIN" eval merge "$TMP/cut.csv" --out "$TMP/cut_sorted.csv" > /dev/null 2>&1
cut -d, -f1-10,12 "$TMP/cut_sorted.csv" > "$TMP/c"
cmp -s "$TMP/c" "$TMP/b" && ok || bad "resumed rows differ: $(diff "$TMP/c" "$TMP/b" | head -4)"

# --json: the same table as the CSV's rows (a re-run: nothing new), the CSV among the outputs
"$BIN" "${ARGS[@]}" --out "$TMP/single.csv" --json > "$TMP/t.json" 2> "$TMP/err" && ok || bad "--json: $(cat "$TMP/err")"
if [ -n "$PY" ]; then
  "$PY" - "$TMP" <<'PYEOF' && ok || bad "eval --table1 --json"
import csv, json, sys
t = sys.argv[1]
d = json.load(open(t + "/t.json"))
r, = d["results"]
assert d["command"] == "eval" and r["ok"] and r["outputs"] == [t + "/single.csv"] and r["new_rows"] == 0 and r["rows"] == 8, r
rows = list(csv.DictReader(open(t + "/single.csv")))
best = [x for x in r["table"] if x["scenario"] == "FAUST BEST"][0]
want = [float(x["error"]) for x in rows if x["policy"] == "random" and x["landmarks"] == "best" and x["method"] == "std"]
assert best["std_pairs"] == len(want) == 1 and abs(best["std"] - want[0]) < 1e-15 and best["diff"] is None, best
assert best["refined"] is None and best["refined_pairs"] == 0 and "refined_paper" not in best, best
assert abs(best["std_paper"] - 0.027) < 1e-12, best
PYEOF
fi
"$BIN" eval --coherency --data "$D" --json > /dev/null 2> "$TMP/err"
[ $? = 2 ] && grep -q -- "--json is for --table1 and --figures" "$TMP/err" && ok || bad "--json with --coherency: $(cat "$TMP/err")"

# damaged cache entries (D8): two eigenvector columns swapped, bytes flipped, a file cut short, a key
# line of another version under the same name: each is reported through the log, recomputed (never
# used) and rewritten; the rows stay those of the intact run, and the next run uses the cache silently
C=("$TMP"/cache/faust_*.bin)
if [ ${#C[@]} = 4 ]; then
  for f in "${C[@]}"; do cp "$f" "$f.orig"; done
  LOUD=(); for a in "${ARGS[@]}"; do [ "$a" = --quiet ] || LOUD+=("$a"); done   # the log on stderr
  off=$(head -n 2 "${C[0]}" | wc -c)
  col=$((8 * 6890)); c3=$((off + 16 + 8 * 20 + 3 * col)); c4=$((c3 + col))   # nv 6890, k 20: columns 3 and 4
  dd if="${C[0]}" of="$TMP/c3" bs=1 skip=$c3 count=$col status=none
  dd if="${C[0]}" of="$TMP/c4" bs=1 skip=$c4 count=$col status=none
  dd if="$TMP/c4" of="${C[0]}" bs=1 seek=$c3 conv=notrunc status=none
  dd if="$TMP/c3" of="${C[0]}" bs=1 seek=$c4 conv=notrunc status=none
  cmp -s "${C[0]}" "${C[0]}.orig" && bad "column swap changed nothing"
  printf '\x5a\xa5\x5a' | dd of="${C[1]}" bs=1 seek=$((off + 500000)) conv=notrunc status=none
  truncate -s -1000 "${C[2]}"
  sed -i '1s/ lib [0-9]*\.[0-9]*\.[0-9]* / lib 9.9.9 /' "${C[3]}"
  "$BIN" "${LOUD[@]}" --out "$TMP/damaged.csv" > /dev/null 2> "$TMP/log" && ok || bad "damaged cache run: $(cat "$TMP/log")"
  for i in 0 1 2 3; do
    grep -q "eval cache: ${C[$i]}: .*not used, recomputing" "$TMP/log" && ok || bad "damaged entry ${C[$i]##*/} not reported"
  done
  grep -q 'checksum mismatch' "$TMP/log" && grep -q 'truncated' "$TMP/log" && grep -q 'another version' "$TMP/log" && ok ||
    bad "damage reports do not say what is wrong: $(grep 'eval cache' "$TMP/log")"
  [ "$(grep -c 'checksum mismatch' "$TMP/log")" = 2 ] && ok || bad "swapped columns and flipped bytes: want 2 checksum reports"
  "$BIN" eval merge "$TMP/damaged.csv" --out "$TMP/damaged_sorted.csv" > /dev/null 2>&1
  cut -d, -f1-10,12 "$TMP/damaged_sorted.csv" > "$TMP/d"
  cmp -s "$TMP/d" "$TMP/b" && ok || bad "rows after recomputing damaged entries differ: $(diff "$TMP/d" "$TMP/b" | head -4)"
  # rewritten with the same key and contents (the last 28 bytes are the timings, which differ, and the refined eigenpairs' count, 0)
  for f in "${C[@]}"; do
    cmp -s <(head -n 1 "$f"; tail -n +3 "$f" | head -c -28) <(head -n 1 "$f.orig"; tail -n +3 "$f.orig" | head -c -28) &&
      ok || bad "${f##*/} not rewritten as it was"
  done
  "$BIN" "${LOUD[@]}" --out "$TMP/again.csv" > /dev/null 2> "$TMP/log" && ok || bad "warm run: $(cat "$TMP/log")"
  grep -q 'eval cache' "$TMP/log" && bad "rewritten entries reported again: $(grep 'eval cache' "$TMP/log")" || ok
else
  bad "want 4 cache files, found ${#C[@]}"
fi

# the refined default as a 4th method, through the same cache (its entries gain the refined
# eigenpairs): the paper methods' rows stay bit for bit, a refined row per unit, and a later run
# without it reads the completed entries to the same rows
"$BIN" "${ARGS[@]}" --methods std,asa,refined --out "$TMP/ref.csv" > "$TMP/ref.out" 2> "$TMP/err" && ok ||
  bad "refined run: $(cat "$TMP/err")"
[ "$(grep -c ',refined,' "$TMP/ref.csv")" = 4 ] && ok || bad "refined rows: $(grep -c ',refined,' "$TMP/ref.csv"), want 4"
"$BIN" eval merge "$TMP/ref.csv" --out "$TMP/ref_sorted.csv" > /dev/null 2>&1
grep -v ',refined,' "$TMP/ref_sorted.csv" | cut -d, -f1-10,12 > "$TMP/r"
cmp -s "$TMP/r" "$TMP/b" && ok || bad "paper rows differ with the refined method: $(diff "$TMP/r" "$TMP/b" | head -4)"
grep -q 'REFINED' "$TMP/ref.out" && ok || bad "no REFINED column in the table"
"$BIN" "${ARGS[@]}" --out "$TMP/again.csv" > /dev/null 2> "$TMP/err" && ok || bad "run after refined: $(cat "$TMP/err")"
"$BIN" eval merge "$TMP/again.csv" --out "$TMP/again_sorted.csv" > /dev/null 2>&1
cut -d, -f1-10,12 "$TMP/again_sorted.csv" > "$TMP/g"
cmp -s "$TMP/g" "$TMP/b" && ok || bad "rows from completed cache entries differ: $(diff "$TMP/g" "$TMP/b" | head -4)"

finish

#!/usr/bin/env bash
# Batches of the per-mesh commands (one shared helper): a folder (its mesh files, sorted by name; other
# files skipped) or several meshes, -o OUTDIR with NAME<suffix> per mesh and suffix-valued extra
# outputs; every output equals the one-mesh run's, with --jobs 1 and 2; reports prefixed by the mesh in
# the order given; a broken mesh fails alone (exit 1, the others written); --json (valid JSON: counts,
# outputs, errors) for batches, single runs, match and error; the progress bar on a terminal only
# (through script(1), SKIP without it); and the refusals (name clashes, overwriting an input, '-',
# non-suffix extras, --suffix without a batch, --json with '-').
# Usage: cli_batch.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"

demo_outputs "$TMP/demo" "$TMP/demo.out" || bad "demo failed: $(tail -3 "$TMP/demo.out")"
mkdir -p "$TMP/in"
cp "$TMP/demo/torus.off" "$TMP/in/b_torus.off"
cp "$TMP/demo/sphere.ply" "$TMP/in/a_sphere.ply"
cp "$TMP/demo/humanoid_pose0.off" "$TMP/in/c_human.off"
echo "not a mesh" > "$TMP/in/notes.txt"
cp "$TMP/demo/torus.off" "$TMP/in/.hidden.off"
NAMES="a_sphere b_torus c_human"
IN="$TMP/in"
JSONPY=""
[ -n "$PY" ] && JSONPY=$PY

# ---- info: a folder, reports in name order, prefixed; -o OUTDIR; the same as one mesh at a time ----
"$BIN" info "$IN" > "$TMP/info.out" 2> "$TMP/info.err" && ok || bad "info FOLDER: $(cat "$TMP/info.err")"
: > "$TMP/info.want"
for f in a_sphere.ply b_torus.off c_human.off; do
  "$BIN" info "$IN/$f" | sed "s|^|$IN/$f: |" >> "$TMP/info.want"
done
cmp -s "$TMP/info.out" "$TMP/info.want" && ok || bad "info FOLDER: $(diff "$TMP/info.out" "$TMP/info.want" | head -5)"
grep -q "notes.txt\|hidden" "$TMP/info.out" && bad "info FOLDER read a non-mesh or hidden file" || ok
grep -q "^specseg info: 3 meshes, 3 done, 0 failed" "$TMP/info.err" && ok || bad "batch summary: $(cat "$TMP/info.err")"
"$BIN" info "$IN" -o "$TMP/infos/" > /dev/null 2>&1 && ok || bad "info -o OUTDIR/"
for n in $NAMES; do
  f=$(ls "$IN"/$n.*)
  "$BIN" info "$f" | cmp -s - "$TMP/infos/$n.info.txt" && ok || bad "info -o OUTDIR: $n.info.txt"
done
# one mesh with -o naming a folder is a batch too
"$BIN" info "$IN/b_torus.off" -o "$TMP/infos" > /dev/null 2>&1 && cmp -s "$TMP/infos/b_torus.info.txt" <("$BIN" info "$IN/b_torus.off") &&
  ok || bad "one mesh, -o an existing folder"

# ---- segment: the same labels / centres / PLY as one mesh at a time, --jobs 1 and 2 ----
for n in $NAMES; do
  f=$(ls "$IN"/$n.*)
  "$BIN" segment "$f" -o "$TMP/$n.l1" --centers "$TMP/$n.c1" --ply "$TMP/$n.p1.ply" --faces 3000 > /dev/null 2>&1 ||
    bad "segment $n alone"
done
for j in 1 2; do
  "$BIN" segment "$IN" -o "$TMP/seg$j" --centers .centers.txt --ply .ply --faces 3000 --jobs $j > "$TMP/seg$j.out" 2> "$TMP/seg$j.err" &&
    ok || bad "segment FOLDER --jobs $j: $(cat "$TMP/seg$j.err")"
  for n in $NAMES; do
    cmp -s "$TMP/seg$j/$n.labels.txt" "$TMP/$n.l1" && cmp -s "$TMP/seg$j/$n.centers.txt" "$TMP/$n.c1" &&
      cmp -s "$TMP/seg$j/$n.ply" "$TMP/$n.p1.ply" && ok || bad "segment --jobs $j: $n differs from the one-mesh run"
  done
  [ "$(wc -l < "$TMP/seg$j.out")" = 3 ] && grep -q "^$IN/a_sphere.ply: [0-9]* segments" "$TMP/seg$j.out" && ok ||
    bad "segment --jobs $j reports: $(cat "$TMP/seg$j.out")"
done
# several meshes given one by one, --suffix for the labels, .npy by extension
"$BIN" segment "$IN/c_human.off" "$IN/b_torus.off" -o "$TMP/segn" --suffix .npy --faces 3000 > "$TMP/o" 2>&1 && ok || bad "segment A B --suffix .npy"
[ -s "$TMP/segn/c_human.npy" ] && [ -s "$TMP/segn/b_torus.npy" ] && head -c 6 "$TMP/segn/b_torus.npy" | grep -q NUMPY && ok ||
  bad "--suffix .npy outputs"
sed -n 1p "$TMP/o" | grep -q "^$IN/c_human.off:" && ok || bad "reports not in the order given: $(head -2 "$TMP/o")"

# ---- smooth / remesh / eigs / descriptors: each equals its one-mesh run ----
"$BIN" smooth "$IN" -o "$TMP/sm" --steps 2 > /dev/null 2>&1 && ok || bad "smooth FOLDER"
"$BIN" remesh "$IN/b_torus.off" "$IN/a_sphere.ply" -o "$TMP/rm/" --faces 800 --suffix .ply > "$TMP/rm.out" 2>&1 && ok || bad "remesh A B"
grep -q "^$IN/b_torus.off: remesh: faces" "$TMP/rm.out" && ok || bad "remesh report in a batch: $(head -3 "$TMP/rm.out")"
"$BIN" eigs "$IN" -k 6 -o "$TMP/ev" --evecs .evecs.npy > /dev/null 2>&1 && ok || bad "eigs FOLDER"
"$BIN" descriptors "$IN" --hks -k 10 -n 4 -o "$TMP/ds" > /dev/null 2>&1 && ok || bad "descriptors FOLDER"
for n in $NAMES; do
  f=$(ls "$IN"/$n.*)
  "$BIN" smooth "$f" -o "$TMP/one.off" --steps 2 2> /dev/null && cmp -s "$TMP/one.off" "$TMP/sm/$n.off" && ok || bad "smooth: $n"
  "$BIN" eigs "$f" -k 6 --evecs "$TMP/one.npy" > "$TMP/one.ev" 2> /dev/null && cmp -s "$TMP/one.ev" "$TMP/ev/$n.evals.txt" &&
    cmp -s "$TMP/one.npy" "$TMP/ev/$n.evecs.npy" && ok || bad "eigs: $n"
  "$BIN" descriptors "$f" --hks -k 10 -n 4 -o "$TMP/one.npy" > /dev/null 2>&1 && cmp -s "$TMP/one.npy" "$TMP/ds/$n.hks.npy" &&
    ok || bad "descriptors: $n"
done
for n in b_torus a_sphere; do
  f=$(ls "$IN"/$n.*)
  "$BIN" remesh "$f" -o "$TMP/one.ply" --faces 800 2> /dev/null && cmp -s "$TMP/one.ply" "$TMP/rm/$n.ply" && ok || bad "remesh: $n"
done

# ---- a broken mesh fails alone ----
cp -r "$IN" "$TMP/in2"
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 7\n' > "$TMP/in2/z_broken.off"
"$BIN" segment "$TMP/in2" -o "$TMP/seg3" --faces 3000 --json > "$TMP/seg3.json" 2> "$TMP/seg3.err"
[ $? = 1 ] && ok || bad "a broken mesh: exit not 1"
grep -q "^specseg: error: .*z_broken.off:6: " "$TMP/seg3.err" && ok || bad "the broken mesh's error: $(cat "$TMP/seg3.err")"
for n in $NAMES; do cmp -s "$TMP/seg3/$n.labels.txt" "$TMP/$n.l1" && ok || bad "the others still written: $n"; done
if [ -n "$JSONPY" ]; then
  "$JSONPY" - "$TMP/seg3.json" "$TMP" <<'PYEOF' && ok || bad "segment --json of a batch with a failure"
import json, os, sys
d = json.load(open(sys.argv[1]))
assert d["command"] == "segment" and d["ok"] == 3 and d["failed"] == 1 and d["jobs"] >= 1, d
r = d["results"]
assert [os.path.basename(x["input"]) for x in r] == ["a_sphere.ply", "b_torus.off", "c_human.off", "z_broken.off"]
for x in r[:3]:
    assert x["ok"] and x["segments"] >= 1 and x["vertices"] > 0 and x["seconds"] > 0, x
    assert x["outputs"] == [sys.argv[2] + "/seg3/" + os.path.basename(x["input"]).rsplit(".", 1)[0] + ".labels.txt"], x
    assert x["segments"] == len(set(open(x["outputs"][0]).read().split())), x
    assert all(k in x for k in ("t_smooth", "t_remesh", "t_spectrum", "t_critical", "t_ivd", "t_total"))
assert not r[3]["ok"] and "z_broken.off:6" in r[3]["error"] and r[3]["outputs"] == [sys.argv[2] + "/seg3/z_broken.labels.txt"]
PYEOF
  # one mesh: the same format with one result; warnings recorded
  "$BIN" info "$IN/b_torus.off" --json > "$TMP/i.json" 2> /dev/null && "$JSONPY" - "$TMP/i.json" <<'PYEOF' && ok || bad "info --json"
import json, sys
d = json.load(open(sys.argv[1]))
x, = d["results"]
assert d["ok"] == 1 and d["failed"] == 0 and x["ok"] and x["vertices"] == 2048 and x["genus"] == 1 and x["manifold"] == 1, d
PYEOF
  printf 'OFF\n5 2 0\n0 0 0\n1 0 0\n0 1 0\n1 1 0\n7 7 7\n3 0 1 2\n3 1 3 2\n' > "$TMP/unref.off"
  "$BIN" eigs "$TMP/unref.off" -k 2 -o "$TMP/u.ev" --json > "$TMP/u.json" 2> /dev/null
  "$JSONPY" - "$TMP/u.json" <<'PYEOF' && ok || bad "eigs --json: the warning recorded"
import json, sys
x, = json.load(open(sys.argv[1]))["results"]
assert x["ok"] and len(x["warnings"]) == 1 and "zero area" in x["warnings"][0] and x["k"] == 2, x
PYEOF
  # match and error
  seq 0 1000 6000 > "$TMP/lm.txt"
  "$BIN" match "$TMP/demo/humanoid_pose0.off" "$TMP/demo/humanoid_pose2.off" --landmarks "$TMP/lm.txt" --probes std --k 20 \
    -o "$TMP/m.txt" --fmap "$TMP/C.npy" --json > "$TMP/m.json" 2> "$TMP/m.err" && ok || bad "match --json: $(cat "$TMP/m.err")"
  "$BIN" error "$TMP/m.txt" "$TMP/demo/humanoid_pose2.off" -o "$TMP/e.txt" --json > "$TMP/e.json" 2> /dev/null && ok || bad "error --json"
  "$BIN" error "$TMP/nonexistent.txt" "$TMP/demo/humanoid_pose2.off" --json > "$TMP/e2.json" 2> /dev/null
  [ $? = 1 ] && ok || bad "error --json of a missing map: exit not 1"
  "$JSONPY" - "$TMP" <<'PYEOF' && ok || bad "match / error --json"
import json, sys
t = sys.argv[1]
m, = json.load(open(t + "/m.json"))["results"]
assert m["ok"] and m["outputs"] == [t + "/m.txt", t + "/C.npy"] and m["vertices_x"] == 6864 and m["landmarks"] == 7, m
assert m["probes"] == "std" and m["k"] == 20 and m["paired"] <= min(m["segments_x"], m["segments_y"]) and m["t_fmap"] > 0
e, = json.load(open(t + "/e.json"))["results"]
errs = [float(v) for v in open(t + "/e.txt").read().split()]
assert e["ok"] and abs(e["mean_error"] - sum(errs) / len(errs)) < 1e-12 and e["max_error"] == max(errs), e
assert e["median_error"] <= e["max_error"] and e["vertices"] == len(errs)
d = json.load(open(t + "/e2.json"))
assert d["failed"] == 1 and "cannot open" in d["results"][0]["error"], d
PYEOF
else
  skip "JSON checks (no python3)"
fi

# ---- the progress bar: on a terminal only ----
grep -q $'\r' "$TMP/seg1.err" && bad "a progress bar without a terminal" || ok
if command -v script > /dev/null 2>&1 && script -qec true /dev/null > /dev/null 2>&1; then
  script -qec "'$BIN' info '$IN' --jobs 1" /dev/null > "$TMP/tty.out" 2>&1
  grep -q "info \[#*\.*\] 3/3 meshes" "$TMP/tty.out" && ok || bad "no progress bar on a terminal: $(head -c 300 "$TMP/tty.out" | od -c | head -5)"
else
  skip "progress bar on a terminal (no script(1))"
fi

# ---- refusals ----
expect2() { # expect2 WHAT ARGS...: exit 2 and a usage line containing WHAT
  local what=$1
  shift
  "$BIN" "$@" > /dev/null 2> "$TMP/err"
  local rc=$?
  [ $rc = 2 ] && grep -q "^specseg: usage: .*$what" "$TMP/err" && ok || bad "$* -> exit $rc: $(head -2 "$TMP/err")"
}
mkdir -p "$TMP/clash"
cp "$TMP/demo/torus.off" "$TMP/demo/torus.ply" "$TMP/clash/"
expect2 "two outputs would be" info "$TMP/clash" -o "$TMP/cl"
expect2 "would overwrite the input" smooth "$IN" -o "$IN" --steps 1
expect2 "needs -o OUTDIR" segment "$IN"
expect2 "not standard input" info "$IN/b_torus.off" - < "$IN/b_torus.off"
expect2 "take a suffix" segment "$IN" -o "$TMP/x" --ply out.ply
expect2 "--suffix is for batches" segment "$IN/b_torus.off" -o "$TMP/x.txt" --suffix .npy
expect2 "--suffix takes a suffix" segment "$IN" -o "$TMP/x" --suffix npy
expect2 "--jobs needs an integer" info "$IN" --jobs 0
expect2 "both want standard output" segment "$IN/b_torus.off" -o - --json
expect2 "no mesh files" info "$TMP/infos"
[ ! -e "$TMP/cl" ] && ok || bad "a refused batch created its folder"
finish

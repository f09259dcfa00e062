#!/usr/bin/env bash
# The conventions every subcommand shares: --opt=value is --opt value, --version / version, help and
# --help / -h for every subcommand (exit 0, "usage:" first), "=value" on a flag and a missing value are
# usage errors (2), "-" reads standard input (meshes sniffed by content, messages name <stdin>) and
# writes standard output, named pipes read once like standard input. Meshes are written by the test (a
# UV sphere from awk, ~10k vertices, so standard input is read in several chunks). A last section
# matches FAUST shapes through stdin / stdout; it prints SKIP: and exits 77 when the data is absent.
# Usage: cli_conventions.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
BIN=$(cd "$(dirname "$BIN")" && pwd)/$(basename "$BIN") # one check runs in another folder
. "$(dirname "$0")/lib_cli.sh"
HERE=$(cd "$(dirname "$0")" && pwd)
TESTS=${SS_TEST_DIR:-$HERE}

# uv_sphere NU NV: closed UV sphere, NU segments around, NV rings (2 + NU*(NV-1) vertices)
uv_sphere() {
  awk -v nu="$1" -v nv="$2" 'BEGIN {
    pi = atan2(0, -1); n = 2 + nu * (nv - 1); f = 2 * nu * (nv - 1)
    print "OFF"; print n, f, 0
    print 0, 0, 1
    for (r = 1; r < nv; r++) for (k = 0; k < nu; k++) {
      t = pi * r / nv; p = 2 * pi * k / nu
      printf "%.12f %.12f %.12f\n", sin(t) * cos(p), sin(t) * sin(p), cos(t)
    }
    print 0, 0, -1
    for (k = 0; k < nu; k++) print 3, 0, 1 + k, 1 + (k + 1) % nu
    for (r = 1; r < nv - 1; r++) for (k = 0; k < nu; k++) {
      a = 1 + (r - 1) * nu + k; b = 1 + (r - 1) * nu + (k + 1) % nu; c = a + nu; d = b + nu
      print 3, a, c, d; print 3, a, d, b
    }
    s = n - 1
    for (k = 0; k < nu; k++) { a = 1 + (nv - 2) * nu + k; b = 1 + (nv - 2) * nu + (k + 1) % nu; print 3, a, s, b }
  }'
}
uv_sphere 16 10 > "$TMP/s.off"      # 146 vertices
uv_sphere 100 100 > "$TMP/big.off"  # 9902 vertices, ~0.4 MB of text
S=$TMP/s.off
NV=$(sed -n 2p "$S" | awk '{print $1}')
# the same small sphere as OBJ (no extension needed on stdin)
awk 'NR > 2 && NF == 3 { print "v", $0 } NR > 2 && NF == 4 { print "f", $2 + 1, $3 + 1, $4 + 1 }' "$S" > "$TMP/s.obj"

# run ARGS...: the program with stdout / stderr in $TMP/run.out / $TMP/run.err
run() { "$BIN" "$@" > "$TMP/run.out" 2> "$TMP/run.err"; }

# ---- --version / version -----------------------------------------------------------------------
V=$("$BIN" --version 2> "$TMP/err"); rc=$?
[ $rc = 0 ] && [ ! -s "$TMP/err" ] && ok || bad "--version: exit $rc $(cat "$TMP/err")"
[[ "$V" =~ ^specseg\ [0-9]+\.[0-9]+\.[0-9]+$ ]] && ok || bad "--version printed '$V'"
[ "$("$BIN" version)" = "$V" ] && ok || bad "'version' differs from --version"
H="$TESTS/../include/specseg/version.h"
if [ -f "$H" ]; then
  want=$(awk '/^#define SPECSEG_VERSION_(MAJOR|MINOR|PATCH) / { v[$2] = $3 }
              END { print "specseg " v["SPECSEG_VERSION_MAJOR"] "." v["SPECSEG_VERSION_MINOR"] "." v["SPECSEG_VERSION_PATCH"] }' "$H")
  [ "$V" = "$want" ] && ok || bad "--version '$V', version.h says '$want'"
fi
"$BIN" --version extra > /dev/null 2>&1; [ $? = 2 ] && ok || bad "--version extra: not a usage error"

# ---- help ---------------------------------------------------------------------------------------
CMDS="info eigs descriptors demo smooth remesh geodesic segment match error eval render"
"$BIN" help > "$TMP/help" 2> "$TMP/err" && [ ! -s "$TMP/err" ] && ok || bad "help: exit $? $(cat "$TMP/err")"
for c in $CMDS help version; do
  grep -q "^  $c " "$TMP/help" && ok || bad "help does not list $c"
done
"$BIN" --help | cmp -s - "$TMP/help" && ok || bad "--help differs from help"
for c in $CMDS; do
  "$BIN" help "$c" > "$TMP/h1" 2> "$TMP/err" && [ ! -s "$TMP/err" ] && ok || bad "help $c: exit $? $(cat "$TMP/err")"
  head -1 "$TMP/h1" | grep -q "^usage: specseg $c" && ok || bad "help $c: first line '$(head -1 "$TMP/h1")'"
  [ "$(wc -l < "$TMP/h1")" -ge 4 ] && ok || bad "help $c: only $(wc -l < "$TMP/h1") lines"
  grep -q -- '--opt=VALUE' "$TMP/h1" && ok || bad "help $c: the --opt=VALUE convention is not mentioned"
  for h in --help -h; do
    "$BIN" "$c" "$h" > "$TMP/h2" 2> "$TMP/err"; rc=$?
    [ $rc = 0 ] && cmp -s "$TMP/h1" "$TMP/h2" && ok || bad "$c $h: exit $rc or differs from 'help $c'"
  done
  # --help wins wherever it stands, also after arguments that are errors
  "$BIN" "$c" --no-such-option --help > "$TMP/h2" 2>&1 && cmp -s "$TMP/h1" "$TMP/h2" && ok || bad "$c --bogus --help"
  # a usage error repeats the synopsis (the first line of the same text)
  "$BIN" "$c" --no-such-option > /dev/null 2> "$TMP/err"; rc=$?
  [ $rc = 2 ] && grep -q "^specseg: usage: $c: unknown option '--no-such-option'" "$TMP/err" &&
    grep -qxF "$(head -1 "$TMP/h1")" "$TMP/err" && ok || bad "$c --no-such-option: exit $rc $(head -3 "$TMP/err")"
done
"$BIN" eval merge --help | cmp -s - <("$BIN" help eval) && ok || bad "eval merge --help"
"$BIN" help nosuch > /dev/null 2>&1; [ $? = 2 ] && ok || bad "help nosuch: not exit 2"
"$BIN" nosuch > /dev/null 2>&1; [ $? = 2 ] && ok || bad "unknown command: not exit 2"
# "-o --help" is a file named --help, not a help request
(cd "$TMP" && "$BIN" geodesic "$S" --source 0 -o --help > /dev/null 2>&1) && [ -s "$TMP/--help" ] && ok ||
  bad "-o --help did not write a file '--help'"

# ---- --opt=value is --opt value -------------------------------------------------------------------
# same NAME FILE_A FILE_B: the two runs' outputs are identical
same() {
  if cmp -s "$2" "$3"; then ok; else bad "$1: outputs differ"; fi
}
run geodesic "$S" --source 3 --source 40 --method graph --max-dist 1.5 -o "$TMP/a.txt" || bad "geodesic: $(cat "$TMP/run.err")"
run geodesic "$S" --source=3 -s=40 --method=graph --max-dist=1.5 -o="$TMP/b.txt" || bad "geodesic =: $(cat "$TMP/run.err")"
same geodesic "$TMP/a.txt" "$TMP/b.txt"
[ "$(wc -l < "$TMP/a.txt")" = "$NV" ] && ok || bad "geodesic: $(wc -l < "$TMP/a.txt") lines, want $NV"
run geodesic "$S" --output="$TMP/c.txt" --source=3 --source 40 --method graph --max-dist=1.5 && same "geodesic mixed" "$TMP/a.txt" "$TMP/c.txt"

run eigs "$S" -k 4 --mass voronoi --sigma -0.5 --evecs "$TMP/a.npy" && cp "$TMP/run.out" "$TMP/a.ev" || bad "eigs: $(cat "$TMP/run.err")"
run eigs "$S" -k=4 --mass=voronoi --sigma=-0.5 --evecs="$TMP/b.npy" && cp "$TMP/run.out" "$TMP/b.ev" || bad "eigs =: $(cat "$TMP/run.err")"
same eigs "$TMP/a.ev" "$TMP/b.ev"
same "eigs --evecs" "$TMP/a.npy" "$TMP/b.npy"

run smooth "$S" -o "$TMP/a.off" --steps 2 --dt 1e-4 && run smooth "$S" -o="$TMP/b.off" --steps=2 --dt=1e-4 &&
  same smooth "$TMP/a.off" "$TMP/b.off" || bad "smooth: $(cat "$TMP/run.err")"
run remesh "$S" -o "$TMP/a.ply" --faces 300 --iterations 2 && run remesh "$S" -o="$TMP/b.ply" --faces=300 --iterations=2 &&
  same remesh "$TMP/a.ply" "$TMP/b.ply" || bad "remesh: $(cat "$TMP/run.err")"

run segment "$S" -o "$TMP/a.lab" --centers "$TMP/a.cen" --faces 600 || bad "segment: $(cat "$TMP/run.err")"
run segment "$S" --output="$TMP/b.lab" --centers="$TMP/b.cen" --faces=600 || bad "segment =: $(cat "$TMP/run.err")"
same segment "$TMP/a.lab" "$TMP/b.lab"
same "segment --centers" "$TMP/a.cen" "$TMP/b.cen"

# any valid map will do: vertex i -> 7 i mod NV
awk -v n="$NV" 'BEGIN { for (i = 0; i < n; i++) print (i * 7) % n }' > "$TMP/map.txt"
run error "$TMP/map.txt" "$S" --gt "$TMP/map.txt" -o "$TMP/a.err" && cp "$TMP/run.out" "$TMP/a.me" &&
  run error "$TMP/map.txt" "$S" --gt="$TMP/map.txt" -o="$TMP/b.err" && cp "$TMP/run.out" "$TMP/b.me" &&
  same error "$TMP/a.me" "$TMP/b.me" && same "error -o" "$TMP/a.err" "$TMP/b.err" || bad "error: $(cat "$TMP/run.err")"
grep -q '^mean_error: 0.000000$' "$TMP/a.me" && ok || bad "error of a map against itself: $(cat "$TMP/a.me")"

run render "$S" --labels "$TMP/a.lab" --view left --size 64x48 --supersample 1 -o "$TMP/a.png" &&
  run render "$S" --labels="$TMP/a.lab" --view=left --size=64x48 --supersample=1 -o="$TMP/b.png" &&
  same render "$TMP/a.png" "$TMP/b.png" || bad "render: $(cat "$TMP/run.err")"

# ---- flags take no value; values must be there --------------------------------------------------
expect2() { # expect2 WHAT ARGS...: exit 2 with a "specseg: usage:" line containing WHAT
  local what=$1
  shift
  "$BIN" "$@" > "$TMP/out" 2> "$TMP/err"
  local rc=$?
  if [ $rc = 2 ] && grep -q "^specseg: usage: .*$what" "$TMP/err"; then ok; else bad "$* -> exit $rc: $(head -2 "$TMP/err")"; fi
}
expect2 "--timings takes no value" segment "$S" -o "$TMP/x.txt" --timings=1
expect2 "--no-streamline takes no value" segment "$S" -o "$TMP/x.txt" --no-streamline=yes
expect2 "--bbox takes no value" smooth "$S" -o "$TMP/x.off" --bbox=1
expect2 "--no-titles takes no value" render "$S" -o "$TMP/x.png" --no-titles=0
expect2 "--timings takes no value" match "$S" "$S" --landmarks "$TMP/x" -o "$TMP/x" --timings=
expect2 "--quiet takes no value" eval --table1 --data /nonexistent --quiet=1
expect2 "--source needs a value" geodesic "$S" -o "$TMP/x.txt" --source
expect2 "--source needs a value" geodesic "$S" -o "$TMP/x.txt" --source=
expect2 "-o needs a value" geodesic "$S" --source 0 -o=
expect2 "-k needs a value" eigs "$S" -k
expect2 "unknown option '--bogus'" info "$S" --bogus=1
expect2 "--faces needs an integer" segment "$S" -o "$TMP/x.txt" --faces=many
expect2 "unknown method 'fast'" geodesic "$S" --source 0 --method=fast -o "$TMP/x.txt"
expect2 "--view needs" render "$S" -o "$TMP/x.png" --view=sideways
expect2 "--shard" eval --table1 --data /nonexistent --shard=3/2
expect2 "needs a value" eval merge --out

# ---- "-" is standard input ------------------------------------------------------------------------
"$BIN" info "$S" > "$TMP/info.file" || bad "info file"
"$BIN" info - < "$S" > "$TMP/info.stdin" 2> "$TMP/err" && cmp -s "$TMP/info.file" "$TMP/info.stdin" && ok ||
  bad "info - < mesh differs from info mesh: $(cat "$TMP/err")"
cat "$S" | "$BIN" info - > "$TMP/info.pipe" && cmp -s "$TMP/info.file" "$TMP/info.pipe" && ok || bad "cat mesh | info -"
"$BIN" info - < "$TMP/s.obj" > "$TMP/info.obj" && cmp -s "$TMP/info.file" "$TMP/info.obj" && ok || bad "OBJ on stdin (sniffed)"
"$BIN" smooth "$S" --steps 0 -o "$TMP/s.ply" 2> /dev/null || bad "smooth to .ply"
"$BIN" info "$TMP/s.ply" > "$TMP/info.plyf" && "$BIN" info - < "$TMP/s.ply" > "$TMP/info.ply" &&
  cmp -s "$TMP/info.plyf" "$TMP/info.ply" && ok || bad "binary PLY on stdin"
"$BIN" info "$TMP/big.off" > "$TMP/info.bf" && cat "$TMP/big.off" | "$BIN" info - > "$TMP/info.bs" &&
  cmp -s "$TMP/info.bf" "$TMP/info.bs" && grep -q '^vertices: 9902$' "$TMP/info.bs" && ok || bad "a 0.4 MB mesh through a pipe"
"$BIN" eigs - -k 3 < "$S" > "$TMP/ev.stdin" && "$BIN" eigs "$S" -k 3 > "$TMP/ev.file" && cmp -s "$TMP/ev.stdin" "$TMP/ev.file" &&
  ok || bad "eigs - differs"
"$BIN" geodesic - --source 5 -o "$TMP/g.stdin" < "$S" && "$BIN" geodesic "$S" --source 5 -o "$TMP/g.file" &&
  cmp -s "$TMP/g.stdin" "$TMP/g.file" && ok || bad "geodesic - differs"
"$BIN" segment - -o "$TMP/l.stdin" --faces 600 < "$S" > /dev/null && same "segment - (stdin)" "$TMP/a.lab" "$TMP/l.stdin"
"$BIN" error - "$S" --gt "$TMP/map.txt" < "$TMP/map.txt" > "$TMP/me.stdin" && cmp -s "$TMP/me.stdin" "$TMP/a.me" && ok ||
  bad "error with the map on stdin"
"$BIN" error "$TMP/map.txt" - --gt "$TMP/map.txt" < "$S" > "$TMP/me.stdin2" && cmp -s "$TMP/me.stdin2" "$TMP/a.me" && ok ||
  bad "error with the mesh on stdin"
# messages name <stdin>
printf 'OFF\n3 1 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 9\n' | "$BIN" info - > /dev/null 2> "$TMP/err"; rc=$?
[ $rc = 1 ] && grep -q '^specseg: error: <stdin>:6: ' "$TMP/err" && ok || bad "bad mesh on stdin: exit $rc $(cat "$TMP/err")"
echo "hello" | "$BIN" info - > /dev/null 2> "$TMP/err"; rc=$?
[ $rc = 1 ] && grep -q '^specseg: error: <stdin>:1: unknown mesh format' "$TMP/err" && ok || bad "garbage on stdin: $(cat "$TMP/err")"
"$BIN" info - < /dev/null > /dev/null 2> "$TMP/err"; [ $? = 1 ] && grep -q '<stdin>' "$TMP/err" && ok || bad "stdin /dev/null"
printf '0\nx\n' | "$BIN" error - "$S" > /dev/null 2> "$TMP/err"; rc=$?
[ $rc = 1 ] && grep -q '^specseg: error: <stdin>:2: ' "$TMP/err" && ok || bad "bad map on stdin: $(cat "$TMP/err")"
# standard input holds one file
expect2 "only one input" error - - < "$S"
expect2 "only one input" match - - --landmarks "$TMP/x" -o "$TMP/x" < "$S"
expect2 "only one input" render - --labels - -o "$TMP/x.png" < "$S"

# landmarks from a pipe or stdin (render reads a landmark file twice: columns, then markers)
echo 7 > "$TMP/lm.txt"
"$BIN" render "$S" --landmarks "$TMP/lm.txt" --size 64x48 --supersample 1 -o "$TMP/lf.png" > /dev/null || bad "render --landmarks file"
"$BIN" render "$S" --landmarks <(echo 7) --size 64x48 --supersample 1 -o "$TMP/lp.png" > /dev/null 2> "$TMP/err" &&
  cmp -s "$TMP/lf.png" "$TMP/lp.png" && ok || bad "render --landmarks <(echo 7): $(cat "$TMP/err")"
echo 7 | "$BIN" render "$S" --landmarks - --size 64x48 --supersample 1 -o "$TMP/ls.png" > /dev/null 2> "$TMP/err" &&
  cmp -s "$TMP/lf.png" "$TMP/ls.png" && ok || bad "render --landmarks -: $(cat "$TMP/err")"
# one labels file from a pipe for two meshes (read once, used twice)
"$BIN" render "$S" "$S" --labels "$TMP/a.lab" --size 64x48 --supersample 1 -o "$TMP/lab2.png" > /dev/null || bad "render 2 meshes"
"$BIN" render "$S" "$S" --labels <(cat "$TMP/a.lab") --size 64x48 --supersample 1 -o "$TMP/lab2p.png" > /dev/null 2> "$TMP/err" &&
  cmp -s "$TMP/lab2.png" "$TMP/lab2p.png" && ok || bad "render two meshes, labels from a pipe: $(cat "$TMP/err")"
"$BIN" render "$S" --labels "$TMP/a.lab" --size 64x48 --supersample 1 --no-titles -o "$TMP/m1.png" > /dev/null &&
  "$BIN" render - --labels "$TMP/a.lab" --size 64x48 --supersample 1 --no-titles -o "$TMP/m2.png" < "$S" > /dev/null 2> "$TMP/err" &&
  cmp -s "$TMP/m1.png" "$TMP/m2.png" && ok || bad "render - (mesh on stdin): $(cat "$TMP/err")"

# ---- "-" is standard output -----------------------------------------------------------------------
"$BIN" geodesic "$S" --source 3 --source 40 --method graph --max-dist 1.5 -o - > "$TMP/g.out" && same "geodesic -o -" "$TMP/a.txt" "$TMP/g.out"
"$BIN" segment "$S" --faces 600 -o - > "$TMP/l.out" 2> "$TMP/err" && same "segment -o -" "$TMP/a.lab" "$TMP/l.out"
grep -q ' segments .* -> <stdout>' "$TMP/err" && ok || bad "segment -o -: summary not on stderr: $(cat "$TMP/err")"
"$BIN" segment "$S" --faces 600 -o "$TMP/x.lab" --centers - > "$TMP/c.out" 2> /dev/null && same "segment --centers -" "$TMP/a.cen" "$TMP/c.out"
"$BIN" segment "$S" --faces 600 -o "$TMP/x.lab" --ply - > "$TMP/p.out" 2> /dev/null && head -c 4 "$TMP/p.out" | grep -q '^ply' &&
  "$BIN" info - < "$TMP/p.out" | cmp -s - "$TMP/info.file" && ok || bad "segment --ply - (binary PLY on stdout)"
expect2 "only one output" segment "$S" -o - --centers -
"$BIN" error "$TMP/map.txt" "$S" --gt "$TMP/map.txt" -o - > "$TMP/e.out" 2> "$TMP/e.err" && same "error -o -" "$TMP/a.err" "$TMP/e.out"
grep -q '^mean_error: ' "$TMP/e.err" && ok || bad "error -o -: mean_error not on stderr"
"$BIN" smooth "$S" --steps 2 --dt 1e-4 -o - 2> /dev/null > "$TMP/sm.out" && same "smooth -o - (OFF)" "$TMP/a.off" "$TMP/sm.out"
"$BIN" smooth "$S" --steps 2 --dt 1e-4 -o - 2> /dev/null | "$BIN" remesh - --faces 300 --iterations 2 -o "$TMP/pp.ply" 2> /dev/null &&
  "$BIN" remesh "$TMP/a.off" --faces 300 --iterations 2 -o "$TMP/pf.ply" 2> /dev/null && same "smooth -o - | remesh -" "$TMP/pf.ply" "$TMP/pp.ply"
"$BIN" render "$S" --labels "$TMP/a.lab" --view left --size 64x48 --supersample 1 -o - > "$TMP/r.out" 2> "$TMP/err" &&
  same "render -o -" "$TMP/a.png" "$TMP/r.out"
grep -q 'rendered in .* -> <stdout>' "$TMP/err" && ok || bad "render -o -: summary not on stderr"
"$BIN" eigs "$S" -k 4 --evecs - > /dev/null 2> "$TMP/err"; [ $? = 2 ] && ok || bad "eigs --evecs - (stdout holds the eigenvalues) not refused"
expect2 "folder" demo -o -
expect2 "folder" eval --figures - --data /nonexistent
expect2 "not standard input" eval merge -

# ---- FAUST (last: skips the whole script when the data is absent) ---------------------------------
D=${SS_DATA_DIR:-}
if [ -z "$D" ] || [ ! -d "$D/faust" ] || [ ! -f "$D/faust/tr_reg_000.off" ] || [ ! -f "$D/faust/landmarks_best.txt" ]; then
  echo "SKIP: no FAUST data under \$SS_DATA_DIR/faust (the checks above ran: $pass passed, $fail failed)"
  [ "$fail" -gt 0 ] && exit 1
  exit 77
fi
F=$D/faust/tr_reg_000.off
"$BIN" info - < "$F" | cmp -s - <("$BIN" info "$F") && ok || bad "FAUST info - differs"
# match X to itself: landmarks from stdin, map to stdout, the same map as with files and "=" options
"$BIN" match "$F" "$F" --landmarks "$D/faust/landmarks_best.txt" --k 20 -o "$TMP/fm.txt" > "$TMP/fm.out" 2> "$TMP/err" ||
  bad "FAUST match: $(cat "$TMP/err")"
"$BIN" match "$F" "$F" --landmarks=- --k=20 -o=- < "$D/faust/landmarks_best.txt" > "$TMP/fm.stdout" 2> "$TMP/fm.err" &&
  same "match --landmarks=- -o=-" "$TMP/fm.txt" "$TMP/fm.stdout" || bad "FAUST match through stdin/stdout: $(cat "$TMP/fm.err")"
grep -q 'vertices.* -> <stdout>' "$TMP/fm.err" && ok || bad "match -o -: summary not on stderr"
[ "$(wc -l < "$TMP/fm.stdout")" = 6890 ] && ok || bad "match -o -: $(wc -l < "$TMP/fm.stdout") lines"

echo "$pass passed, $fail failed"
exit $((fail > 0))

#!/usr/bin/env bash
# Standard output (issue 32, item 5): a write error on stdout (/dev/full) is an error (exit 1) for
# every command that prints there; --json is valid JSON (strict UTF-8) for a file name that is not
# valid UTF-8 (its bytes escaped); a usage error under --json prints a JSON object saying so.
# Usage: cli_stdout.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
demo_outputs "$TMP/demo" || { bad "demo"; finish; }
S="$TMP/demo/sphere.off"
T="$TMP/demo/torus.off"
[ -w /dev/full ] || { skip "no /dev/full"; finish; }
printf '0\n1\n2\n' > "$TMP/lm.txt"
for cmd in "pair $S $S" "pair $S $S --timings" "info $S" "eigs $S -k 3" "segment $S -o $TMP/l.txt" "geodesic $S -s 0 -o -" \
           "match $S $S --landmarks $TMP/lm.txt --no-refine --k 20 --descr-k 20 -o $TMP/m.txt" "error $TMP/l.txt $S --gt $TMP/l.txt" \
           "info $S --json" "segment $S -o $TMP/l.txt --json" "prepare $S -k 20 -o $TMP/s.sss" \
           "descriptors $S --wks -o $TMP/d.npy" "render $S -o $TMP/s.png"; do
  # shellcheck disable=SC2086
  "$BIN" $cmd > /dev/full 2> "$TMP/err"; rc=$?
  [ $rc -eq 1 ] && grep -Eq "standard output|<stdout>|cannot write" "$TMP/err" && ok || bad "$cmd > /dev/full: rc $rc $(cat "$TMP/err")"
done

# JSON: strict UTF-8 whatever the bytes of a file name (invalid UTF-8 escaped as \udcXX, Python's
# surrogateescape: os.fsencode gives the bytes back)
if [ -n "$PY" ]; then
  bad_name=$(printf '%s/caf\xe9-\xff.off' "$TMP")
  cp "$S" "$bad_name"
  good_name=$(printf '%s/caf\xc3\xa9.off' "$TMP")
  cp "$S" "$good_name"
  check_json() { "$PY" -c '
import json, os, sys
raw = sys.stdin.buffer.read()
d = json.loads(raw.decode("utf-8"))  # strict: invalid UTF-8 raises
want = sys.argv[1:]
got = [os.fsencode(r["input"]) for r in d["results"]]
assert got == [os.fsencode(w) for w in want], (got, want)
' "$@"; }
  "$BIN" info "$bad_name" --json 2> /dev/null | check_json "$bad_name" && ok || bad "info --json with a non-UTF-8 name"
  "$BIN" info "$good_name" "$bad_name" --json 2> /dev/null | check_json "$good_name" "$bad_name" && ok ||
    bad "info --json, UTF-8 and not"
  # a usage error under --json: a JSON object on stdout (and the message on stderr as always)
  for cmd in "info $S --json --bogus" "match $S --json" "error --json" "segment $S --json --faces 1 -o $TMP/l.txt"; do
    # shellcheck disable=SC2086
    "$BIN" $cmd > "$TMP/out" 2> "$TMP/err"; rc=$?
    [ $rc -eq 2 ] && grep -q "specseg: usage:" "$TMP/err" &&
      "$PY" -c 'import json, sys; d = json.load(open(sys.argv[1])); assert d["usage_error"] and d["ok"] == 0 and d["results"] == []' \
        "$TMP/out" && ok || bad "$cmd: rc $rc, stdout $(cat "$TMP/out")"
  done
else
  skip "no python3 for the JSON checks"
fi
finish

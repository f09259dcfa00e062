# Shared preamble of the CLI test scripts (sourced, not run): counters, a scratch folder removed on exit,
# PNG checks (png, PY), the demo's outputs (demo_outputs).
# Each script ends with `finish`: it prints "N passed, N failed[, N skipped]" and exits 1 on a failure,
# 77 (CTest's SKIP_RETURN_CODE: the test shows as skipped) when checks were skipped for lack of data
# or tools, else 0.
pass=0
fail=0
skipped=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }
skip() { skipped=$((skipped + 1)); echo "SKIP: $*"; }
finish() {
  echo "$pass passed, $fail failed${skipped:+, $skipped skipped}"
  [ "$fail" -gt 0 ] && exit 1
  [ "$skipped" -gt 0 ] && exit 77
  exit 0
}
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
# PNG checks through tests/python/png_check.py with the system python3 (PY empty when there is none)
PY=""
for p in /usr/bin/python3 python3; do command -v "$p" > /dev/null 2>&1 && { PY=$p; break; }; done
png() { PYTHONDONTWRITEBYTECODE=1 "$PY" "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/python/png_check.py" "$@"; }
# The demo's files (meshes of the humanoid poses, sphere, torus, pictures) in DIR and its summary in
# LOG (default: none): under CTest a copy of those the fixture tests/fixture_demo.sh wrote once with
# this binary (SS_DEMO_DIR), else (a script run by hand, another binary) `specseg demo -o DIR` here.
bin_stamp() { echo "$(stat -L -c '%s %Y' "$BIN") $(realpath "$BIN")"; }
demo_outputs() {
  local log=${2:-/dev/null}
  if [ -n "${SS_DEMO_DIR:-}" ] && [ -s "$SS_DEMO_DIR/stamp" ] && [ "$(cat "$SS_DEMO_DIR/stamp")" = "$(bin_stamp)" ]; then
    mkdir -p "$1" && cp -r "$SS_DEMO_DIR/out/." "$1/" && cp "$SS_DEMO_DIR/demo.out" "$log"
  else
    "$BIN" demo -o "$1" > "$log" 2>&1
  fi
}

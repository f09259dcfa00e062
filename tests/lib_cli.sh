# Shared preamble of the CLI test scripts (sourced, not run): counters, a scratch folder removed on exit,
# PNG checks (png, PY).
# Each script prints "N passed, N failed" at its end.
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
# PNG checks through tests/python/png_check.py with the system python3 (PY empty when there is none)
PY=""
for p in /usr/bin/python3 python3; do command -v "$p" > /dev/null 2>&1 && { PY=$p; break; }; done
png() { PYTHONDONTWRITEBYTECODE=1 "$PY" "$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)/python/png_check.py" "$@"; }

# Shared preamble of the CLI test scripts (sourced, not run): counters, a scratch folder removed on
# exit. Each script prints "N passed, N failed" at its end.
pass=0
fail=0
ok() { pass=$((pass + 1)); }
bad() { fail=$((fail + 1)); echo "FAIL: $*" >&2; }
TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT

#!/usr/bin/env bash
# docs/cli.md against the program: every command `specseg help` lists has a section '## specseg CMD'
# in docs/cli.md, and the options of that section's tables (the backticked -x / --xxx names in the
# first cell of each table row) are exactly those the command's --help defines (its usage lines and
# the options listed at the start of its indented lines). A missing option, an option the command
# does not have, a section without a command or a command without a section: FAIL.
# Usage: cli_docs_help.sh PATH/TO/specseg [PATH/TO/cli.md]
set -u
BIN=${1:?usage: $0 PATH/TO/specseg [docs/cli.md]}
DOC=${2:-$(dirname "$0")/../docs/cli.md}
. "$(dirname "$0")/lib_cli.sh"
[ -f "$DOC" ] || { bad "$DOC not found"; finish; }

# the options a command's --help defines, one a line: long options anywhere in the usage lines (up to
# the first empty line), short and long ones in the option column (22 characters) of lines '  -...'
help_options() {
  "$BIN" "$1" --help | awk '
    NR == 1 { usage = 1 }
    usage && /^$/ { usage = 0 }
    usage { s = $0; while (match(s, /--[a-z][a-z0-9-]*/)) { print substr(s, RSTART, RLENGTH); s = substr(s, RSTART + RLENGTH) }; next }
    /^  -/ { s = substr($0, 1, 22)
             while (match(s, /(^|[ ,])--?[a-zA-Z][a-z0-9-]*/)) { t = substr(s, RSTART, RLENGTH); sub(/^[ ,]/, "", t); print t; s = substr(s, RSTART + RLENGTH) } }
  ' | sort -u
}
# the options docs/cli.md gives command $1: first cells of the table rows in its section
doc_options() {
  awk -v cmd="$1" '
    /^## / { insec = ($0 == "## specseg " cmd); next }
    insec && /^\|/ && !/^\| *(option|mode|file) *\|/ && !/^\| *---/ {
      cell = $0; sub(/^\| */, "", cell); sub(/ *\|.*/, "", cell)
      while (match(cell, /`[^`]*`/)) {
        code = substr(cell, RSTART + 1, RLENGTH - 2); cell = substr(cell, RSTART + RLENGTH)
        while (match(code, /(^|[ ,])--?[a-zA-Z][a-z0-9-]*/)) { t = substr(code, RSTART, RLENGTH); sub(/^[ ,]/, "", t); print t; code = substr(code, RSTART + RLENGTH) }
      }
    }' "$DOC" | sort -u
}

cmds=$("$BIN" help | awk '/^commands:/ { on = 1; next } on && /^$/ { exit } on { print $1 }' | grep -vx 'help\|version')
[ -n "$cmds" ] && ok || bad "specseg help lists no commands"
for c in $cmds; do
  if ! grep -qx "## specseg $c" "$DOC"; then bad "docs/cli.md has no section '## specseg $c'"; continue; fi
  h=$(help_options "$c")
  d=$(doc_options "$c")
  [ -n "$h" ] || { bad "$c --help: no options found"; continue; }
  missing=$(comm -23 <(echo "$h") <(echo "$d") | tr '\n' ' ')
  extra=$(comm -13 <(echo "$h") <(echo "$d") | tr '\n' ' ')
  [ -z "$missing" ] && ok || bad "$c: options in --help missing from docs/cli.md: $missing"
  [ -z "$extra" ] && ok || bad "$c: docs/cli.md names options '$c --help' does not have: $extra"
done
# every section names a command
for s in $(sed -n 's/^## specseg \([a-z]*\)$/\1/p' "$DOC"); do
  echo "$cmds" | grep -qx "$s" && ok || bad "docs/cli.md: section 'specseg $s' is not a command of specseg help"
done
finish

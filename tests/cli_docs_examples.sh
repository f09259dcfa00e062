#!/usr/bin/env bash
# The examples of README.md and docs/*.md still run: every fenced block right after a line
# '<!-- doc-test -->' (```sh: bash -e -o pipefail; ```python: python3 with NumPy, skipped when there is
# none) runs, in the order of its file, in one fresh folder per file holding
#   A.off, B.off   two small meshes with one vertex order (the demo's humanoid remeshed to 2,000 faces,
#                  and that mesh smoothed a little), so `specseg error` with the identity applies
#   build/, python/ links to the binary's build folder and the checkout's Python package
# with the binary's folder first on PATH (`specseg ...` and `build/specseg ...` both run it).
# No data set or network is used. A block that fails (or a file that lost all its marks) is a FAIL.
# Usage: cli_docs_examples.sh PATH/TO/specseg [FILE.md...]
set -u
BIN=$(realpath "${1:?usage: $0 PATH/TO/specseg [FILE.md...]}")
shift
ROOT=$(cd "$(dirname "$0")/.." && pwd)
. "$(dirname "$0")/lib_cli.sh"
BUILD=$(dirname "$BIN")
if [ $# -gt 0 ]; then files=("$@"); else files=("$ROOT/README.md" "$ROOT"/docs/*.md); fi

# the two meshes, once
demo_outputs "$TMP/demo"
"$BIN" remesh "$TMP/demo/humanoid_pose0.off" --faces 2000 -o "$TMP/A.off" 2> /dev/null &&
  "$BIN" smooth "$TMP/A.off" --steps 3 -o "$TMP/B.off" 2> /dev/null || { bad "cannot make A.off, B.off"; finish; }

# python with NumPy; under an ASan build the runtime is preloaded (as tests/cli_python.sh does)
PYNP=""
for p in /usr/bin/python3 python3; do
  if command -v "$p" > /dev/null 2>&1 && "$p" -c "import numpy" > /dev/null 2>&1; then PYNP=$p; break; fi
done
PYENV=(PYTHONDONTWRITEBYTECODE=1 SPECSEG_LIB="$BUILD/libspecseg.so")
if ldd "$BUILD/libspecseg.so" 2> /dev/null | grep -q libasan; then
  PYENV+=(LD_PRELOAD="$(gcc -print-file-name=libasan.so)" ASAN_OPTIONS=detect_leaks=0)
fi

# blocks of FILE into DIR/NNN.sh / NNN.py, each with the line of its mark in DIR/NNN.line
extract() {
  awk -v dir="$2" '
    /^<!-- doc-test -->[ \t]*$/ { mark = NR; next }
    mark && !inb && /^```/ {
      lang = substr($0, 4); n++; out = sprintf("%s/%03d.%s", dir, n, lang == "python" ? "py" : lang)
      print mark > sprintf("%s/%03d.line", dir, n); inb = 1; next }
    inb && /^```[ \t]*$/ { inb = 0; mark = 0; close(out); next }
    inb { print > out; next }
    mark && !/^[ \t]*$/ { print mark > sprintf("%s/bad.line", dir); mark = 0 }
  ' "$1"
}

for f in "${files[@]}"; do
  name=$(basename "$f" .md)
  W="$TMP/run_$name"
  B="$TMP/blocks_$name"
  mkdir -p "$W" "$B"
  cp "$TMP/A.off" "$TMP/B.off" "$W/"
  ln -s "$BUILD" "$W/build"
  ln -s "$ROOT/python" "$W/python"
  extract "$f" "$B"
  [ -f "$B/bad.line" ] && bad "$f:$(cat "$B/bad.line"): a doc-test mark not followed by a code block"
  n=0
  for blk in "$B"/[0-9][0-9][0-9].*; do
    [ -e "$blk" ] || continue
    case "$blk" in *.line) continue ;; esac
    n=$((n + 1))
    line=$(cat "${blk%.*}.line")
    t0=$(date +%s%N)
    case "$blk" in
      *.sh) (cd "$W" && PATH="$BUILD:$PATH" bash -e -o pipefail "$blk") > "$blk.out" 2>&1; rc=$? ;;
      *.py)
        if [ -z "$PYNP" ]; then skip "$f:$line: python block (no python3 with numpy)"; continue; fi
        (cd "$W" && env "${PYENV[@]}" PATH="$BUILD:$PATH" "$PYNP" "$blk") > "$blk.out" 2>&1; rc=$? ;;
      *) bad "$f:$line: block of unknown language ($(basename "$blk"))"; continue ;;
    esac
    secs=$(awk -v a="$t0" -v b="$(date +%s%N)" 'BEGIN { printf "%.1f", (b - a) / 1e9 }')
    if [ $rc -eq 0 ]; then
      ok; echo "${f#"$ROOT"/}:$line: ok ($secs s)"
    else
      bad "${f#"$ROOT"/}:$line: the example exited $rc; its last output:"; tail -n 15 "$blk.out" >&2
    fi
  done
  case "$(basename "$f")" in
    README.md | cli.md) [ $n -gt 0 ] || bad "$f: no doc-test blocks (the marks were lost?)" ;;
  esac
done
finish

#!/usr/bin/env bash
# Installs a build into a fresh prefix and uses it as an outside project would:
#   - the installed shared libraries export only the public ss_ API, and the core links neither libpng
#     nor the render / eval libraries;
#   - examples/segment_sizes.c builds against the installed package through pkg-config and through
#     CMake's find_package(specseg), links and runs (both builds print the same);
#   - the installed `specseg --version` runs;
#   - the Python package installs with pip into a fresh venv and imports from another folder
#     (tests/install/check_python.sh), when that script is present.
#   scripts/check_install.sh BUILD_DIR [PREFIX]
set -euo pipefail
cd "$(dirname "$0")/.."
BUILD=${1:?usage: $0 BUILD_DIR [PREFIX]}
PREFIX=${2:-$(mktemp -d)/prefix}
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
fail() { echo "check_install: FAIL: $*" >&2; exit 1; }

rm -rf "$PREFIX"
cmake --install "$BUILD" --prefix "$PREFIX" > "$WORK/install.log" || fail "cmake --install: $(tail -3 "$WORK/install.log")"
LIBDIR=$(dirname "$(find "$PREFIX" -name libspecseg.so -print -quit)")
[ -f "$LIBDIR/libspecseg.so" ] || fail "no libspecseg.so under $PREFIX"
for f in include/specseg/specseg.h include/specseg/version.h bin/specseg; do
  [ -e "$PREFIX/$f" ] || fail "$f not installed"
done
[ -f "$LIBDIR/pkgconfig/specseg.pc" ] || fail "specseg.pc not installed"
[ -f "$LIBDIR/cmake/specseg/specsegConfig.cmake" ] || fail "specsegConfig.cmake not installed"

# exported symbols: the public API only
for l in specseg specseg_synth specseg_render specseg_eval; do
  other=$(nm -D --defined-only "$LIBDIR/lib$l.so" | awk '{print $3}' | grep -v '^ss_' || true)
  [ -z "$other" ] || fail "lib$l.so exports non-ss_ symbols: $(echo $other | head -c 300)"
done
if ldd "$LIBDIR/libspecseg.so" | grep -Eq 'libpng|libspecseg_(render|eval|synth)'; then
  fail "the core library links $(ldd "$LIBDIR/libspecseg.so" | grep -Eo 'libpng[^ ]*|libspecseg_[a-z]+' | tr '\n' ' ')"
fi
echo "check_install: $(ls "$LIBDIR"/libspecseg*.so | wc -l) shared libraries export only ss_ symbols; core links no png/render/eval"

"$PREFIX/bin/specseg" --version > "$WORK/version" 2>&1 || fail "installed specseg --version: $(cat "$WORK/version")"
vpart() { sed -n "s/^#define SPECSEG_VERSION_$1 \\([0-9]*\\)\$/\\1/p" include/specseg/version.h; }
want="specseg $(vpart MAJOR).$(vpart MINOR).$(vpart PATCH)"
[ "$(cat "$WORK/version")" = "$want" ] || fail "installed specseg --version says '$(cat "$WORK/version")', want '$want'"
"$PREFIX/bin/specseg" demo -o "$WORK/demo" > /dev/null || fail "installed specseg demo"
MESH="$WORK/demo/humanoid_pose0.off"

# an outside C program, built both ways against the installed package
PKG_CONFIG_PATH="$LIBDIR/pkgconfig" make -s -C "$WORK" -f "$PWD/examples/Makefile" > "$WORK/make.log" 2>&1 ||
  fail "pkg-config build: $(tail -5 "$WORK/make.log")"
cmake -S examples -B "$WORK/cmake-build" -DCMAKE_PREFIX_PATH="$PREFIX" > "$WORK/cmake.log" 2>&1 ||
  fail "find_package configure: $(tail -5 "$WORK/cmake.log")"
cmake --build "$WORK/cmake-build" > "$WORK/cmake-build.log" 2>&1 || fail "find_package build: $(tail -5 "$WORK/cmake-build.log")"
"$WORK/segment_sizes" "$MESH" > "$WORK/pc.out" || fail "pkg-config build does not run"
"$WORK/cmake-build/segment_sizes" "$MESH" > "$WORK/cm.out" || fail "find_package build does not run"
cmp -s "$WORK/pc.out" "$WORK/cm.out" || fail "the two builds print different results"
grep -q "segments" "$WORK/pc.out" || fail "unexpected output: $(head -2 "$WORK/pc.out")"
used=$(ldd "$WORK/segment_sizes" | awk '/libspecseg\.so/ {print $3}')
[ -n "$used" ] && [ "$(readlink -f "$used")" = "$(readlink -f "$LIBDIR/libspecseg.so")" ] ||
  fail "the pkg-config build does not use the installed library (uses '$used')"
echo "check_install: examples/segment_sizes built with pkg-config and find_package: $(head -1 "$WORK/pc.out")"

if [ -f tests/install/check_python.sh ]; then
  bash tests/install/check_python.sh "$PREFIX" || fail "python package"
fi
echo "check_install: ok ($PREFIX)"

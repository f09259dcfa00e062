#!/usr/bin/env bash
# Meshes in other formats from the command line: the demo humanoid written as ascii and binary STL and as
# a glTF with an embedded base64 buffer (our readers, in every build; python3 writes them, no numpy
# needed) reads back with the OFF's counts and checks (welded, closed), from a file and from standard
# input, and goes through smooth / segment; a malformed STL or glTF fails with the file's name and cause.
# Usage: cli_mesh_formats.sh PATH/TO/specseg
set -u
BIN=${1:?usage: $0 PATH/TO/specseg}
. "$(dirname "$0")/lib_cli.sh"
[ -n "$PY" ] || { skip "no python3 to write the files"; finish; }

demo_outputs "$TMP/demo" "$TMP/demo.out" || bad "demo failed: $(tail -3 "$TMP/demo.out")"
M="$TMP/demo/humanoid_pose0.off"
[ -s "$M" ] || { bad "the demo wrote no humanoid"; finish; }

# OFF -> ascii STL, binary STL, glTF (positions float32 + uint32 indices, translated by a node) and the
# OFF as it reads back from float32 coordinates (the reference for the coordinates)
"$PY" - "$M" "$TMP" <<'PYEOF' || bad "writing the STL / glTF files"
import base64, json, struct, sys
src, t = sys.argv[1], sys.argv[2]
lines = [l for l in open(src).read().split("\n") if l.strip() and not l.startswith("#")]
nv, nf = map(int, lines[1].split()[:2])
V = [tuple(float(x) for x in l.split()[:3]) for l in lines[2:2 + nv]]
F = [tuple(int(x) for x in l.split()[1:4]) for l in lines[2 + nv:2 + nv + nf]]
f32 = lambda x: struct.unpack("<f", struct.pack("<f", x))[0]
with open(t + "/h.stl", "w") as f:
    f.write("solid humanoid\n")
    for a in F:
        f.write(" facet normal 0 0 0\n  outer loop\n")
        for v in a:
            f.write("   vertex %.9g %.9g %.9g\n" % tuple(f32(c) for c in V[v]))
        f.write("  endloop\n endfacet\n")
    f.write("endsolid humanoid\n")
with open(t + "/hb.stl", "wb") as f:
    f.write(b"solid but binary".ljust(80, b" ") + struct.pack("<I", len(F)))
    for a in F:
        f.write(struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *V[v]) for v in a) + b"\0\0")
vb = b"".join(struct.pack("<3f", *v) for v in V)
ib = b"".join(struct.pack("<3I", *a) for a in F)
g = {"asset": {"version": "2.0"}, "scene": 0, "scenes": [{"nodes": [0]}],
     "nodes": [{"children": [1], "translation": [0, 0, 0]}, {"mesh": 0, "translation": [2, 0, 0]}],
     "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
     "buffers": [{"byteLength": len(vb) + len(ib),
                  "uri": "data:application/octet-stream;base64," + base64.b64encode(vb + ib).decode()}],
     "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": len(vb)},
                     {"buffer": 0, "byteOffset": len(vb), "byteLength": len(ib)}],
     "accessors": [{"bufferView": 0, "componentType": 5126, "count": nv, "type": "VEC3",
                    "min": [min(v[i] for v in V) for i in range(3)], "max": [max(v[i] for v in V) for i in range(3)]},
                   {"bufferView": 1, "componentType": 5125, "count": 3 * nf, "type": "SCALAR"}]}
open(t + "/h.gltf", "w").write(json.dumps(g))
with open(t + "/h32.off", "w") as f:  # the humanoid in float32, in OFF, shifted as the glTF node does
    f.write("OFF\n%d %d 0\n" % (nv, nf))
    for v in V:
        f.write("%.17g %.17g %.17g\n" % (f32(v[0]) + 2, f32(v[1]), f32(v[2])))
    for a in F:
        f.write("3 %d %d %d\n" % a)
PYEOF

FORMATS="h.stl hb.stl h.gltf"

"$BIN" info "$M" | grep -v -e '^area' -e '^bbox' > "$TMP/off.info" || bad "info OFF"
for f in $FORMATS; do
  "$BIN" info "$TMP/$f" > "$TMP/$f.info" 2> "$TMP/$f.err" && ok || bad "info $f: $(cat "$TMP/$f.err")"
  grep -v -e '^area' -e '^bbox' "$TMP/$f.info" | diff -q - "$TMP/off.info" > /dev/null && ok ||
    bad "info $f differs from the OFF's: $(grep -v -e '^area' -e '^bbox' "$TMP/$f.info" | diff - "$TMP/off.info" | head -6)"
  grep -q '^boundary_edges: 0$' "$TMP/$f.info" && grep -q '^components: 1$' "$TMP/$f.info" && ok || bad "$f is not closed after welding"
done
# standard input: recognised by content
for f in $FORMATS; do
  "$BIN" info - < "$TMP/$f" > "$TMP/$f.stdin" 2>&1 && cmp -s "$TMP/$f.stdin" "$TMP/$f.info" && ok ||
    bad "info - < $f: $(diff "$TMP/$f.stdin" "$TMP/$f.info" | head -4)"
done
# the coordinates: float32 values, the glTF node translation applied
"$BIN" smooth "$TMP/h.gltf" --steps 0 -o "$TMP/g.off" > /dev/null 2>&1 && ok || bad "smooth --steps 0 of the glTF"
# (smooth --steps 0 normalises and restores the scale: equal up to rounding, not bit for bit)
"$PY" - "$TMP/g.off" "$TMP/h32.off" <<'PYEOF' && ok || bad "the glTF's vertices are not the float32 OFF shifted by the node"
import sys
a, b = (open(p).read().split("\n") for p in sys.argv[1:])
assert a[1] == b[1], (a[1], b[1])
nv = int(a[1].split()[0])
for la, lb in zip(a[2:2 + nv], b[2:2 + nv]):
    for x, y in zip(map(float, la.split()), map(float, lb.split())):
        assert abs(x - y) <= 1e-14 * max(1.0, abs(y)), (la, lb)
assert a[2 + nv:] == b[2 + nv:], "faces differ"
PYEOF
"$BIN" segment "$TMP/hb.stl" -o "$TMP/l.txt" --faces 4000 > "$TMP/seg.out" 2>&1 && ok || bad "segment an STL: $(cat "$TMP/seg.out")"
[ "$(wc -l < "$TMP/l.txt")" = "$(sed -n 2p "$M" | awk '{print $1}')" ] && ok || bad "segment STL: one label per welded vertex"
# malformed: the name of the file and the format in the message
printf 'solid x\n  facet normal 0 0 1\n    outer loop\n      vertex 0 0\n' > "$TMP/bad.stl"
"$BIN" info "$TMP/bad.stl" > /dev/null 2> "$TMP/bad.err"
[ $? = 1 ] && grep -q "^specseg: error: .*bad.stl:4: the file ends inside a vertex" "$TMP/bad.err" && ok ||
  bad "malformed STL: $(cat "$TMP/bad.err")"
printf '{"asset":{"version":"1.0"}}' > "$TMP/old.gltf"
"$BIN" info "$TMP/old.gltf" > /dev/null 2> "$TMP/old.err"
[ $? = 1 ] && grep -q "^specseg: error: .*old.gltf: glTF version '1.0': only glTF 2.0 is read" "$TMP/old.err" && ok ||
  bad "glTF 1.0: $(cat "$TMP/old.err")"
finish

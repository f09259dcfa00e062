#!/usr/bin/env python3
"""Writes the binary-PLY part of the malformed corpus (plyb_*.ply) next to this script.

Every file must make `specseg info FILE` exit 1 with a clear message: truncations at every stage,
absurd declared counts and list lengths, out-of-range and negative indices. Run it again after
changing the list; the outputs are committed so the tests do not need Python."""
import os
import struct

HERE = os.path.dirname(os.path.abspath(__file__))
TRI = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0)]


def header(fmt, nv, nf, coord="float", count="uchar", index="int", extra=""):
    return (
        "ply\nformat %s 1.0\n%selement vertex %d\nproperty %s x\nproperty %s y\nproperty %s z\n"
        "element face %d\nproperty list %s %s vertex_indices\nend_header\n"
        % (fmt, extra, nv, coord, coord, coord, nf, count, index)
    ).encode()


def body(e, verts, faces, coord="f", count="B", index="i"):
    out = b"".join(struct.pack(e + coord * 3, *v) for v in verts)
    for f in faces:
        out += struct.pack(e + count, len(f)) + struct.pack(e + index * len(f), *f)
    return out


def good(fmt="binary_little_endian"):
    e = "<" if "little" in fmt else ">"
    return header(fmt, 3, 1), body(e, TRI, [(0, 1, 2)])


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data)


h, b = good()
write("plyb_le_header_only.ply", h)
write("plyb_le_truncated_in_vertex.ply", h + b[:17])
write("plyb_le_truncated_in_face.ply", h + b[:36 + 1 + 5])
hb, bb = good("binary_big_endian")
write("plyb_be_truncated_in_face.ply", hb + bb[:-2])
write("plyb_be_truncated_in_vertex.ply", hb + bb[:30])
# a face list declaring 4 billion indices with 12 bytes left
write("plyb_le_huge_list_length.ply",
      header("binary_little_endian", 3, 1, count="uint") + body("<", TRI, []) + struct.pack("<I", 0xFFFFFFFF) + struct.pack("<3i", 0, 1, 2))
write("plyb_le_index_out_of_range.ply", h + body("<", TRI, [(0, 1, 3)]))
write("plyb_be_negative_index.ply", hb + body(">", TRI, [(0, -1, 2)]))
# 700 million declared vertices, 3 present: must fail at once without allocating for 700M
write("plyb_le_huge_vertex_count.ply", header("binary_little_endian", 700000000, 1) + body("<", TRI, [(0, 1, 2)]))
# an extra element with a list property and 2^31-1 declared instances before the real data
write("plyb_le_huge_skipped_element.ply",
      header("binary_little_endian", 3, 1, extra="element junk 2147483647\nproperty list uchar int stuff\n") + b)
write("plyb_le_face_two_vertices.ply", h + body("<", TRI, [(0, 1)]))
write("plyb_be_double_truncated.ply", header("binary_big_endian", 3, 1, coord="double") + body(">", TRI, [(0, 1, 2)], coord="d")[:50])
write("plyb_le_no_newline_after_header.ply", h[:-1])
# declares one face, holds two: wrong counts must not pass silently
write("plyb_le_more_faces_than_declared.ply", h + b + struct.pack("<B3i", 3, 0, 2, 1))

"""Pixel checks on PNG files for tests/cli_render.sh (stdlib only: zlib + struct).

usage: png_check.py FILE size                 -> "W H"
       png_check.py FILE pixel X Y            -> "R G B"
       png_check.py FILE chroma R G B [XMAX]  -> number of pixels (x < XMAX) whose colour is a shade of RGB
       png_check.py FILE grey [XMAX]          -> number of non-background grey pixels (x < XMAX)
       png_check.py FILE red [XMAX]           -> number of strongly red pixels (x < XMAX)
       png_check.py FILE top                  -> "X Y" of the topmost non-white pixel
       png_check.py FILE bbox [XMIN XMAX]     -> "X0 Y0 X1 Y1" of the non-white pixels (XMIN <= x < XMAX)
       png_check.py FILE row Y [XMIN XMAX]    -> R+G+B of each pixel of row Y, space-separated
"""
import struct
import sys
import zlib


def read_png(path):
    with open(path, "rb") as f:
        data = f.read()
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise SystemExit("not a PNG: %s" % path)
    pos, idat, w = 8, b"", 0
    while pos < len(data):
        n, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + n]
        if kind == b"IHDR":
            w, h, depth, ctype = struct.unpack(">IIBB", body[:10])
            if depth != 8 or ctype != 2:
                raise SystemExit("only 8-bit RGB PNGs")
        elif kind == b"IDAT":
            idat += body
        pos += 12 + n
    raw, stride, bpp = zlib.decompress(idat), 3 * w, 3
    rows, prev, i = [], bytearray(stride), 0
    for _ in range(h):
        ft, line = raw[i], bytearray(raw[i + 1:i + 1 + stride])
        i += 1 + stride
        for x in range(stride):
            a = line[x - bpp] if x >= bpp else 0
            b = prev[x]
            c = prev[x - bpp] if x >= bpp else 0
            if ft == 1:
                line[x] = (line[x] + a) & 255
            elif ft == 2:
                line[x] = (line[x] + b) & 255
            elif ft == 3:
                line[x] = (line[x] + (a + b) // 2) & 255
            elif ft == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(line)
        prev = line
    return w, h, rows


def pixels(w, h, rows, xmax):
    for y in range(h):
        r = rows[y]
        for x in range(min(w, xmax)):
            yield x, y, r[3 * x], r[3 * x + 1], r[3 * x + 2]


def main():
    path, cmd, args = sys.argv[1], sys.argv[2], sys.argv[3:]
    w, h, rows = read_png(path)
    if cmd == "size":
        print(w, h)
    elif cmd == "pixel":
        x, y = int(args[0]), int(args[1])
        print(*rows[y][3 * x:3 * x + 3])
    elif cmd == "chroma":
        c = [int(v) for v in args[:3]]
        xmax = int(args[3]) if len(args) > 3 else w
        nc = sum(v * v for v in c) ** 0.5
        cnt = 0
        for _, _, r, g, b in pixels(w, h, rows, xmax):
            if r + g + b >= 760:
                continue
            n = (r * r + g * g + b * b) ** 0.5
            if n > 30 and (r * c[0] + g * c[1] + b * c[2]) / (n * nc) > 0.99:
                cnt += 1
        print(cnt)
    elif cmd == "grey":
        xmax = int(args[0]) if args else w
        print(sum(1 for _, _, r, g, b in pixels(w, h, rows, xmax)
                  if max(r, g, b) - min(r, g, b) < 12 and 90 < (r + g + b) / 3 < 245))
    elif cmd == "red":
        xmax = int(args[0]) if args else w
        print(sum(1 for _, _, r, g, b in pixels(w, h, rows, xmax) if r > 150 and g < 100 and b < 100))
    elif cmd == "top":
        for y in range(h):
            for x in range(w):
                if rows[y][3 * x:3 * x + 3] != b"\xff\xff\xff":
                    print(x, y)
                    return
        print(-1, -1)
    elif cmd == "bbox":
        x0, x1 = (int(args[0]), int(args[1])) if len(args) > 1 else (0, w)
        xs, ys = [], []
        for y in range(h):
            r = rows[y]
            for x in range(x0, min(x1, w)):
                if r[3 * x:3 * x + 3] != b"\xff\xff\xff":
                    xs.append(x)
                    ys.append(y)
        print(*((min(xs), min(ys), max(xs), max(ys)) if xs else (-1, -1, -1, -1)))
    elif cmd == "row":
        y = int(args[0])
        x0, x1 = (int(args[1]), int(args[2])) if len(args) > 2 else (0, w)
        print(*(sum(rows[y][3 * x:3 * x + 3]) for x in range(x0, min(x1, w))))
    else:
        raise SystemExit("unknown command " + cmd)


if __name__ == "__main__":
    main()

#!/usr/bin/env python3
"""A stereo pair side by side as one PNG: LEFT | RIGHT at native size.

    python3 scripts/stereo_pair_png.py LEFT.png RIGHT.png OUT.png

For the 8-bit grey PNGs a run saves (outputs.save_images: kitti); Python's standard
library only (zlib), so that scripts/image_statistics_table.sh needs no image tool.
Each output row is filtered Sub or Up, whichever sums smaller, and deflated at level 9.
"""
import struct
import sys
import zlib

SIGNATURE = b"\x89PNG\r\n\x1a\n"


def _unfilter(kind, line, prev):
    width = len(line)
    for x in range(width):
        a = line[x - 1] if x else 0
        b = prev[x]
        c = prev[x - 1] if x else 0
        if kind == 1:
            line[x] = (line[x] + a) & 255
        elif kind == 2:
            line[x] = (line[x] + b) & 255
        elif kind == 3:
            line[x] = (line[x] + (a + b) // 2) & 255
        elif kind == 4:
            p = a + b - c
            pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
            line[x] = (line[x] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
    return line


def read_gray_png(path):
    """The rows (bytearrays) of an 8-bit grey, non-interlaced PNG."""
    data = open(path, "rb").read()
    if data[:8] != SIGNATURE:
        raise SystemExit(path + ": not a PNG")
    pos, idat, width, height = 8, b"", 0, 0
    while pos < len(data):
        length, kind = struct.unpack(">I4s", data[pos:pos + 8])
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, depth, colour, _, _, interlace = struct.unpack(">IIBBBBB", body)
            if depth != 8 or colour != 0 or interlace != 0:
                raise SystemExit(path + ": not an 8-bit grey, non-interlaced PNG")
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    raw = zlib.decompress(idat)
    rows, prev = [], bytearray(width)
    for y in range(height):
        start = y * (width + 1)
        line = _unfilter(raw[start], bytearray(raw[start + 1:start + 1 + width]), prev)
        rows.append(line)
        prev = line
    return rows


def _chunk(kind, body):
    return (struct.pack(">I", len(body)) + kind + body +
            struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))


def write_gray_png(path, rows):
    width = len(rows[0])
    out, prev = bytearray(), bytearray(width)

    def cost(filtered):
        return sum(v if v < 128 else 256 - v for v in filtered)

    for line in rows:
        sub = bytes([line[0]] + [(line[x] - line[x - 1]) & 255 for x in range(1, width)])
        up = bytes((line[x] - prev[x]) & 255 for x in range(width))
        out += (b"\x01" + sub) if cost(sub) <= cost(up) else (b"\x02" + up)
        prev = line
    header = struct.pack(">IIBBBBB", width, len(rows), 8, 0, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(SIGNATURE + _chunk(b"IHDR", header) + _chunk(b"IDAT", zlib.compress(bytes(out), 9)) +
                _chunk(b"IEND", b""))


def main(argv):
    if len(argv) != 4:
        raise SystemExit(__doc__.strip().splitlines()[2].strip())
    left, right = read_gray_png(argv[1]), read_gray_png(argv[2])
    if len(left) != len(right):
        raise SystemExit("stereo_pair_png: the two images differ in height")
    write_gray_png(argv[3], [l + r for l, r in zip(left, right)])


if __name__ == "__main__":
    main(sys.argv)

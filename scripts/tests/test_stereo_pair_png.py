#!/usr/bin/env python3
"""Unit tests of scripts/stereo_pair_png.py: every PNG row filter read back exactly, a
pair written side by side and read again.

Run: python3 -m unittest discover -s scripts/tests
"""

import os
import struct
import sys
import tempfile
import unittest
import zlib

sys.path.insert(0, os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
import stereo_pair_png  # noqa: E402


def _paeth(a, b, c):
    p = a + b - c
    pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
    return a if pa <= pb and pa <= pc else b if pb <= pc else c


def _filtered(rows):
    """The rows filtered None, Sub, Up, Average, Paeth in turn (as libpng may)."""
    out, prev = bytearray(), [0] * len(rows[0])
    for y, line in enumerate(rows):
        kind = y % 5
        out.append(kind)
        for x, v in enumerate(line):
            a = line[x - 1] if x else 0
            b, c = prev[x], prev[x - 1] if x else 0
            pred = [0, a, b, (a + b) // 2, _paeth(a, b, c)][kind]
            out.append((v - pred) & 255)
        prev = line
    return bytes(out)


def _write_png(path, rows):
    def chunk(kind, body):
        return (struct.pack(">I", len(body)) + kind + body +
                struct.pack(">I", zlib.crc32(kind + body) & 0xFFFFFFFF))
    header = struct.pack(">IIBBBBB", len(rows[0]), len(rows), 8, 0, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(stereo_pair_png.SIGNATURE + chunk(b"IHDR", header) +
                chunk(b"IDAT", zlib.compress(_filtered(rows))) + chunk(b"IEND", b""))


class StereoPairPngTest(unittest.TestCase):
    def setUp(self):
        self._dir = tempfile.TemporaryDirectory()
        self.dir = self._dir.name
        # A pattern with edges in every direction, 10 rows so each filter is used twice.
        self.left = [[(x * 37 + y * 91 + (x * y) % 13) % 256 for x in range(23)] for y in range(10)]
        self.right = [[255 - v for v in row] for row in self.left]

    def tearDown(self):
        self._dir.cleanup()

    def test_every_filter_is_read_exactly(self):
        path = os.path.join(self.dir, "left.png")
        _write_png(path, self.left)
        self.assertEqual([list(r) for r in stereo_pair_png.read_gray_png(path)], self.left)

    def test_a_pair_is_written_side_by_side(self):
        left, right, out = (os.path.join(self.dir, n) for n in ("l.png", "r.png", "pair.png"))
        _write_png(left, self.left)
        _write_png(right, self.right)
        stereo_pair_png.main(["stereo_pair_png.py", left, right, out])
        pair = stereo_pair_png.read_gray_png(out)
        self.assertEqual([list(r) for r in pair], [l + r for l, r in zip(self.left, self.right)])

    def test_a_colour_png_is_refused(self):
        path = os.path.join(self.dir, "rgb.png")
        with open(path, "wb") as f:
            body = struct.pack(">IIBBBBB", 1, 1, 8, 2, 0, 0, 0)
            f.write(stereo_pair_png.SIGNATURE + struct.pack(">I", len(body)) + b"IHDR" + body +
                    b"\0\0\0\0")
        with self.assertRaises(SystemExit):
            stereo_pair_png.read_gray_png(path)


if __name__ == "__main__":
    unittest.main()

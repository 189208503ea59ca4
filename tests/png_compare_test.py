#!/usr/bin/env python3
"""png_compare.py against figures worked out by hand: two small PNGs written here (with the row
filters a PNG encoder may use) that differ in one value by 10 levels, so that
MSE = 100 / (3 * 4 * 2) and PSNR = 10 log10(255^2 / MSE) = 41.93 dB; the same picture twice is
infinite; a size mismatch fails.
Usage: png_compare_test.py"""
import math
import os
import struct
import subprocess
import sys
import tempfile
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))


def write_png(path, width, height, rows, filters):
    def chunk(kind, body):
        return struct.pack(">I", len(body)) + kind + body + struct.pack(
            ">I", zlib.crc32(kind + body) & 0xFFFFFFFF)

    raw, previous = b"", bytes(3 * width)
    for row, kind in zip(rows, filters):
        line = bytearray(row)
        if kind == 1:  # Sub
            line = bytearray((row[i] - (row[i - 3] if i >= 3 else 0)) & 255 for i in range(len(row)))
        elif kind == 2:  # Up
            line = bytearray((row[i] - previous[i]) & 255 for i in range(len(row)))
        raw += bytes([kind]) + bytes(line)
        previous = row
    header = struct.pack(">IIBBBBB", width, height, 8, 2, 0, 0, 0)
    with open(path, "wb") as f:
        f.write(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(raw))
                + chunk(b"IEND", b""))


def compare(a, b, threshold):
    run = subprocess.run([sys.executable, os.path.join(HERE, "png_compare.py"), a, b, str(threshold)],
                         capture_output=True, text=True)
    return run.returncode, run.stdout


def main():
    rows = [bytes(range(10, 22)), bytes(range(100, 112))]
    changed = [rows[0], rows[1][:5] + bytes([rows[1][5] + 10]) + rows[1][6:]]
    with tempfile.TemporaryDirectory() as tmp:
        a, b, c = (os.path.join(tmp, n) for n in ("a.png", "b.png", "c.png"))
        write_png(a, 4, 2, rows, [0, 1])
        write_png(b, 4, 2, changed, [2, 1])
        write_png(c, 2, 2, [rows[0][:6], rows[1][:6]], [0, 0])
        expected = 10 * math.log10(255 ** 2 / (100 / 24))
        code, out = compare(a, b, 50)
        assert code == 1 and f"PSNR {expected:.1f} dB" in out and "largest difference 10" in out \
            and "1 of 24 values" in out, out
        code, out = compare(a, b, 40)
        assert code == 0 and f"PSNR {expected:.1f} dB" in out, out
        code, out = compare(a, a, 50)
        assert code == 0 and "PSNR inf dB" in out, out
        code, out = compare(a, c, 0)
        assert code == 1 and "sizes differ" in out, out
    print(f"png_compare: {expected:.2f} dB as worked out, identical inf, sizes checked")


if __name__ == "__main__":
    main()

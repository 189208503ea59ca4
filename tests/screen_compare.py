#!/usr/bin/env python3
"""Compares a region of an X screenshot (xwd -root) with a PNG picture, pixel by pixel.

Usage: screen_compare.py SHOT.xwd PICTURE.png X Y [MEAN]
Exits 0 when every pixel of the picture, placed with its top-left corner at (X, Y) on the
screen, matches the screen within one 8-bit level per channel; prints the first mismatch
otherwise. With MEAN (a lossy video's frame against its source picture): exits 0 when the mean
absolute difference over the picture's channels is at most MEAN levels instead. Both formats are read here (XWD's header, PNG's zlib stream and its row filters),
so the check depends on nothing but the Python standard library.
"""
import struct
import sys
import zlib


def read_xwd(path):
    data = open(path, "rb").read()
    header = struct.unpack(">25I", data[:100])
    header_size, depth, width, height = header[0], header[3], header[4], header[5]
    bits_per_pixel, bytes_per_line, ncolors = header[11], header[12], header[19]
    byte_order = header[7]  # 0 LSBFirst, 1 MSBFirst
    red_mask, green_mask, blue_mask = header[14], header[15], header[16]
    assert bits_per_pixel in (24, 32), f"{bits_per_pixel} bits per pixel"
    step = bits_per_pixel // 8
    offset = header_size + 12 * ncolors

    def shift(mask):
        s = 0
        while mask and not (mask >> s) & 1:
            s += 1
        return s

    rs, gs, bs = shift(red_mask), shift(green_mask), shift(blue_mask)

    def pixel(x, y):
        at = offset + y * bytes_per_line + step * x
        v = int.from_bytes(data[at:at + step], "little" if byte_order == 0 else "big")
        return ((v & red_mask) >> rs, (v & green_mask) >> gs, (v & blue_mask) >> bs)

    return width, height, pixel


def read_png(path):
    data = open(path, "rb").read()
    assert data[:8] == b"\x89PNG\r\n\x1a\n"
    pos, idat = 8, b""
    while pos < len(data):
        (length,) = struct.unpack(">I", data[pos:pos + 4])
        kind = data[pos + 4:pos + 8]
        body = data[pos + 8:pos + 8 + length]
        if kind == b"IHDR":
            width, height, bit_depth, colour_type, _, _, interlace = struct.unpack(">IIBBBBB", body)
        elif kind == b"IDAT":
            idat += body
        pos += 12 + length
    assert bit_depth == 8 and interlace == 0
    channels = {0: 1, 2: 3, 4: 2, 6: 4}[colour_type]
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous = [], bytearray(stride)
    for y in range(height):
        kind = raw[y * (stride + 1)]
        line = bytearray(raw[y * (stride + 1) + 1:(y + 1) * (stride + 1)])
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                pred = a if pa <= pb and pa <= pc else (b if pb <= pc else c)
                line[i] = (line[i] + pred) & 255
        rows.append(line)
        previous = line

    def pixel(x, y):
        v = rows[y][x * channels:(x + 1) * channels]
        return (v[0], v[0], v[0]) if channels < 3 else (v[0], v[1], v[2])

    return width, height, pixel


def main():
    shot, picture, x0, y0 = sys.argv[1], sys.argv[2], int(sys.argv[3]), int(sys.argv[4])
    sw, sh, screen = read_xwd(shot)
    pw, ph, png = read_png(picture)
    if x0 + pw > sw or y0 + ph > sh:
        print(f"the picture ({pw}x{ph} at {x0},{y0}) does not fit the screen {sw}x{sh}")
        return 1
    if len(sys.argv) > 5:
        limit, total = float(sys.argv[5]), 0
        for y in range(ph):
            for x in range(pw):
                total += sum(abs(w - g) for w, g in zip(png(x, y), screen(x0 + x, y0 + y)))
        mean = total / (3 * pw * ph)
        print(f"mean difference {mean:.2f} levels (at most {limit})")
        return 0 if mean <= limit else 1
    for y in range(ph):
        for x in range(pw):
            want, got = png(x, y), screen(x0 + x, y0 + y)
            if any(abs(w - g) > 1 for w, g in zip(want, got)):
                print(f"pixel {x},{y}: the picture has {want}, the screen {got}")
                return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

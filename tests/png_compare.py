#!/usr/bin/env python3
"""Compares two 8-bit PNG pictures of the same size channel by channel.

Usage: png_compare.py A.png B.png [MIN_PSNR]
Prints PSNR (peak 255, over every channel of every pixel), the largest difference and the share
of differing values; exits 1 when the PSNR is below MIN_PSNR dB (default 50) or the sizes
differ. PNG is decoded by screen_compare.read_png (the standard library alone).
"""
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from screen_compare import read_png  # noqa: E402


def main():
    a_path, b_path = sys.argv[1], sys.argv[2]
    min_psnr = float(sys.argv[3]) if len(sys.argv) > 3 else 50.0
    aw, ah, a = read_png(a_path)
    bw, bh, b = read_png(b_path)
    name = os.path.basename(a_path)
    if (aw, ah) != (bw, bh):
        print(f"  {name}: sizes differ, {aw}x{ah} against {bw}x{bh}")
        return 1
    squared, largest, differing = 0, 0, 0
    for y in range(ah):
        for x in range(aw):
            for u, v in zip(a(x, y), b(x, y)):
                d = abs(u - v)
                if d:
                    squared += d * d
                    differing += 1
                    largest = max(largest, d)
    values = 3 * aw * ah
    mse = squared / values
    psnr = math.inf if mse == 0 else 10 * math.log10(255 * 255 / mse)
    print(f"  {name}: PSNR {psnr:.1f} dB, largest difference {largest} levels, "
          f"{differing} of {values} values differ ({100 * differing / values:.4f} %)")
    if psnr < min_psnr:
        print(f"  {name}: below {min_psnr} dB")
        return 1
    return 0


if __name__ == "__main__":
    sys.exit(main())

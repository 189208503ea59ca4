#!/usr/bin/env bash
# The portable binary on older CPUs, emulated with QEMU's user mode (qemu-user): "Haswell" has
# AVX2 and FMA but no AVX-512 (x86-64-v3), "qemu64" only the x86-64 baseline (SSE2). On each:
# the lane kernels' dispatch picks that level (bench reports it), nothing dies of an illegal
# instruction, Embree runs its narrower kernels, and the pictures are this machine's up to
# float rounding (a picture's values within 1e-5 relative; the 8-bit layers nearly identical).
#   cpu_levels_test.sh PARALLAX SOURCE_DIR
set -euo pipefail
bin=$1
source=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }
command -v qemu-x86_64 >/dev/null || fail "qemu-x86_64 (Debian package qemu-user) is not installed"

display="$source/displays/small.json"
"$bin" view --size 160x90 --spp 4 -o "$work/host.pfm" >/dev/null 2>&1 || fail "view failed"
"$bin" render --display "$display" --spp 4 -o "$work/host" >/dev/null 2>&1 || fail "render failed"

for level in Haswell:x86-64-v3 qemu64:x86-64; do
  cpu=${level%%:*} expected=${level#*:}
  run() { qemu-x86_64 -cpu "$cpu" "$bin" "$@"; }
  kernels=$(run bench --spp 1 --size 32x32 --repeats 1 2>&1 | grep -oP '^our kernels +\K\S+') ||
    fail "$cpu: bench did not run"
  [ "$kernels" = "$expected" ] || fail "$cpu: the lane kernels are $kernels, expected $expected"
  run view --size 160x90 --spp 4 -o "$work/$cpu.pfm" >/dev/null 2>&1 || fail "$cpu: view failed"
  run render --display "$display" --spp 4 -o "$work/$cpu" >/dev/null 2>&1 ||
    fail "$cpu: render failed"
  /usr/bin/python3 - "$work/host.pfm" "$work/$cpu.pfm" "$work/host/image.png" \
    "$work/$cpu/image.png" "$work/host/mask.png" "$work/$cpu/mask.png" "$cpu" <<'PY' || exit 1
import sys
import zlib

import numpy as np

def pfm(path):
    data = open(path, "rb").read()
    kind, size, scale, pixels = data.split(b"\n", 3)
    width, height = map(int, size.split())
    return np.frombuffer(pixels, dtype="<f4" if float(scale) < 0 else ">f4").reshape(height, width, 3)

host, other = pfm(sys.argv[1]), pfm(sys.argv[2])
cpu = sys.argv[7]
relative = float((np.abs(other - host) / np.maximum(np.abs(host), 1e-3)).max())
if relative > 1e-5:
    sys.exit(f"FAIL: {cpu}: the view differs from this machine's by {relative:.2e} relative")
def filtered_rows(path):  # the PNG's decompressed scanlines: a changed code changes its row only
    png, data, pos = open(path, "rb").read(), b"", 8
    while pos < len(png):
        length = int.from_bytes(png[pos:pos + 4], "big")
        if png[pos + 4:pos + 8] == b"IDAT":
            data += png[pos + 8:pos + 8 + length]
        pos += 12 + length
    return zlib.decompress(data)

for host_png, other_png in ((sys.argv[3], sys.argv[4]), (sys.argv[5], sys.argv[6])):
    a, b = filtered_rows(host_png), filtered_rows(other_png)
    changed = sum(x != y for x, y in zip(a, b)) + abs(len(a) - len(b))
    if changed > len(a) // 1000:
        sys.exit(f"FAIL: {cpu}: {other_png} has {changed} of {len(a)} bytes changed")
print(f"{cpu}: view within {relative:.1e} relative of this machine's")
PY
done
echo "cpu levels: x86-64-v3 and x86-64 run, pick their kernels, and agree with this machine"

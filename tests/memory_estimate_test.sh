#!/usr/bin/env bash
# Memory is known before the work starts (docs/inputs.md, "Memory"): for a matrix of commands and
# sizes, the peak resident set size `/usr/bin/time -v` measures must be within 0.9-1.1 times the
# estimate `parallax --estimate` prints (the same figure the command checks against
# --max-memory). Prints the table; fails on any row outside the band.
# Python's functions the same way, through parallax.estimate_memory, when the module is given.
# Usage: memory_estimate_test.sh PARALLAX_BINARY SOURCE_DIR [PYTHON_PACKAGE_DIR PYTHON]
set -u
bin=$1
src=$2
pydir=${3:-}
python=${4:-python3}
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
if [ ! -x /usr/bin/time ]; then
  echo "FAIL: /usr/bin/time is missing (package time; tools/install-deps test installs it)"
  exit 1
fi

# Inputs: barrier displays of several sizes, an RGB-D photo, a mesh of 180 k triangles.
display() {  # display NAME WIDTH HEIGHT
  sed "s/\[1920, 1080\]/[$2, $3]/" "$src/displays/default.json" >"$tmp/$1.json"
}
display d480 480 270
display d960 960 540
display d1000 1000 1000
display d2000 2000 2000
display d4000 4000 4000
python3 - "$tmp" <<'PY'
import struct, sys, zlib
tmp = sys.argv[1]
def png(path, w, h, depth16):
    rows = []
    for y in range(h):
        row = bytearray([0])
        for x in range(w):
            if depth16:
                near = (x - w / 2) ** 2 + (y - h / 2) ** 2 < (h / 3) ** 2
                row += struct.pack(">H", 60000 if near else 8000)
            else:
                row += bytes([255 * x // (w - 1), 255 * y // (h - 1), 128])
        rows.append(bytes(row))
    depth, ctype = (16, 0) if depth16 else (8, 2)
    def chunk(t, d):
        return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
    data = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, depth, ctype, 0, 0, 0))
    data += chunk(b"IDAT", zlib.compress(b"".join(rows))) + chunk(b"IEND", b"")
    open(path, "wb").write(data)
png(tmp + "/photo.png", 1000, 750, False)
png(tmp + "/depth.png", 1000, 750, True)
n = 300
with open(tmp + "/grid.obj", "w") as f:
    for j in range(n + 1):
        for i in range(n + 1):
            f.write(f"v {i / n - 0.5:.5f} {j / n - 0.5:.5f} {0.1 * ((i * 7 + j * 13) % 17) / 17:.5f}\n")
    for j in range(n):
        for i in range(n):
            a = j * (n + 1) + i + 1
            f.write(f"f {a} {a + 1} {a + n + 2}\nf {a} {a + n + 2} {a + n + 1}\n")
PY
# Render folders for simulate and show.
"$bin" render --display "$tmp/d480.json" --spp 1 -o "$tmp/r480" >/dev/null 2>&1
"$bin" render --display "$tmp/d960.json" --spp 1 -o "$tmp/r960" >/dev/null 2>&1
"$bin" render --display "$tmp/d2000.json" --spp 1 -o "$tmp/r2000" >/dev/null 2>&1

failures=0
printf "%-34s %-12s %10s %10s %6s\n" command size "estimate" "peak" ratio
# row LABEL SIZE ARGS...: the estimate (--estimate) and the measured peak of the same command.
row() {
  local label=$1 size=$2
  shift 2
  local est peak
  est=$("$bin" --estimate "$@" 2>"$tmp/err" | sed -n 's/.*memory, \([0-9]*\) bytes.*/\1/p')
  /usr/bin/time -v "$bin" "$@" >"$tmp/out" 2>"$tmp/time"
  local rc=$?
  peak=$(awk '/Maximum resident set size/ {print $NF * 1024}' "$tmp/time")
  judge "$label" "$size" "$rc" "$est" "$peak"
}
# judge LABEL SIZE EXIT ESTIMATE PEAK: one line of the table; counts a failure.
judge() {
  local label=$1 size=$2 rc=$3 est=$4 peak=$5
  if [ "$rc" != 0 ] || [ -z "$est" ] || [ -z "$peak" ]; then
    printf "%-34s %-12s FAIL: exit %s, estimate '%s', peak '%s'\n" "$label" "$size" "$rc" "$est" "$peak"
    sed -n 1,3p "$tmp/err" "$tmp/time" | grep -v "^\s*$" | head -3
    failures=$((failures + 1))
    return
  fi
  local verdict
  verdict=$(awk -v e="$est" -v p="$peak" 'BEGIN {
    r = p / e; printf "%10.1f %10.1f %6.3f %s", e / 1048576, p / 1048576, r,
      (r >= 0.9 && r <= 1.1) ? "" : "FAIL: outside 0.9-1.1" }')
  printf "%-34s %-12s %s\n" "$label" "$size" "$verdict"
  case $verdict in *FAIL*) failures=$((failures + 1)) ;; esac
}

o=$tmp/o
row "render barrier" 480x270 render --display "$tmp/d480.json" --spp 1 -o "$o"
row "render barrier" 2000x2000 render --display "$tmp/d2000.json" --spp 1 -o "$o"
row "render barrier" 4000x4000 render --display "$tmp/d4000.json" --spp 1 -o "$o"
row "render barrier --subpixels" 1000x1000 render --display "$tmp/d1000.json" --subpixels --spp 1 -o "$o"
row "render --direct-mapping" 960x540 render --display "$tmp/d960.json" --direct-mapping --spp 1 -o "$o"
row "render mesh 180k triangles" 1000x1000 render "$tmp/grid.obj" --display "$tmp/d1000.json" --spp 1 -o "$o"
row "render lenticular" lkg:portrait render --display lkg:portrait --spp 1 --filter none -o "$o"
row "--layers optimized-image" 480x270 render --display "$tmp/d480.json" --spp 1 --layers optimized-image --iterations 2 -o "$o"
row "--layers nmf --rank 1" 480x270 render --display "$tmp/d480.json" --spp 1 --layers nmf --iterations 2 -o "$o"
row "--layers nmf --rank 3" 480x270 render --display "$tmp/d480.json" --spp 1 --layers nmf --rank 3 --iterations 2 -o "$o"
row "--layers nmf --rank 1" 960x540 render --display "$tmp/d960.json" --spp 1 --layers nmf --iterations 2 -o "$o"
row "render --rgbd" 1000x750 render --rgbd "$tmp/photo.png" "$tmp/depth.png" --display "$tmp/d960.json" --spp 1 -o "$o"
row "render --rgbd layered" 1000x750 render --rgbd "$tmp/photo.png" "$tmp/depth.png" --rgbd-edges layered --display "$tmp/d960.json" --spp 1 -o "$o"
row "view" 1000x1000 view --size 1000x1000 --spp 1 -o "$tmp/v.png"
row "view" 3000x3000 view --size 3000x3000 --spp 1 -o "$tmp/v.png"
row "render --quilt 4x2" 500x500 render --quilt 4x2 --size 500x500 --spp 1 -o "$o"
row "render --quilt 8x6" 500x500 render --quilt 8x6 --size 500x500 --spp 1 -o "$o"
row "render --quilt 4x2 --linear" 500x500 render --quilt 4x2 --size 500x500 --linear --spp 1 -o "$o"
row "render --quilt auto" lkg:portrait render --display lkg:portrait --quilt auto --spp 1 -o "$o"
row "simulate (one eye)" 960x540 simulate "$tmp/r960" -o "$tmp/s.png"
row "simulate --sweep 50" 480x270 simulate "$tmp/r480" --sweep 50 -o "$tmp/s1/s"
row "simulate --sweep 400" 480x270 simulate "$tmp/r480" --sweep 400 -o "$tmp/s2/s"
row "simulate --sweep 100" 960x540 simulate "$tmp/r960" --sweep 100 -o "$tmp/s3/s"
row "simulate --reference (dense)" 480x270 simulate "$tmp/r480" --reference --reference-spp 1 -o "$tmp/d.png"
row "simulate --reference (dense)" 960x540 simulate "$tmp/r960" --reference --reference-spp 1 -o "$tmp/d.png"
row "simulate --reference --compare" 480x270 simulate "$tmp/r480" --reference --reference-spp 1 --compare "$tmp/r480" -o "$tmp/d.png"

# show under a virtual X server (as tests/cli_show_test.sh), when there is one.
if command -v Xvfb >/dev/null && command -v xdpyinfo >/dev/null; then
  screen=":$((500 + RANDOM % 400))"
  Xvfb "$screen" -screen 0 4200x2200x24 -nolisten tcp -noreset >/dev/null 2>&1 &
  xvfb=$!
  trap 'kill $xvfb 2>/dev/null; rm -rf "$tmp"' EXIT
  for _ in $(seq 300); do xdpyinfo -display "$screen" >/dev/null 2>&1 && break; sleep 0.1; done
  "$bin" calibrate patterns --display "$tmp/d960.json" --steps 5 -o "$tmp/c960" >/dev/null 2>&1
  DISPLAY=$screen row "show (layers)" 480x270 show "$tmp/r480" --windowed --exit-after 1
  DISPLAY=$screen row "show (layers)" 2000x2000 show "$tmp/r2000" --windowed --exit-after 1
  DISPLAY=$screen row "show (calibration patterns)" 960x540 show "$tmp/c960" --windowed --exit-after 1
else
  # Xvfb is a test dependency (tools/install-deps test installs it): missing, the show rows
  # would pass unmeasured.
  echo "FAIL: show rows not measured: Xvfb or xdpyinfo is missing (packages xvfb, x11-utils)"
  failures=$((failures + 1))
fi

# pyrow LABEL SIZE CODE: CODE sets up `call`; estimate_memory(call), then call() measured.
pyrow() {
  local label=$1 size=$2 code="import numpy as np, parallax as p
$3"
  local est peak
  est=$(cd "$tmp" && PYTHONPATH=$pydir "$python" -c "$code
print(p.estimate_memory(call))" 2>"$tmp/err")
  (cd "$tmp" && PYTHONPATH=$pydir /usr/bin/time -v "$python" -c "$code
call()" >"$tmp/out" 2>"$tmp/time")
  local rc=$?
  peak=$(awk '/Maximum resident set size/ {print $NF * 1024}' "$tmp/time")
  judge "$label" "$size" "$rc" "$est" "$peak"
}
if [ -n "$pydir" ]; then
  pyrow "python view" 2000x2000 "call = lambda: p.view(p.load_scene(), size=(2000, 2000), spp=1)"
  pyrow "python render" 1000x1000 "d = p.load_display('d1000.json')
call = lambda: p.render(p.load_scene(), d, spp=1)"
  pyrow "python render lenticular" lkg:portrait "d = p.load_display('lkg:portrait')
call = lambda: p.render(p.load_scene(), d, spp=1, filter='none')"
  pyrow "python quilt" lkg:portrait "d = p.load_display('lkg:portrait')
call = lambda: p.quilt(p.load_scene(), d, spp=1)"
  pyrow "python simulate (one eye)" 960x540 "d = p.load_display('d960.json')
r = p.render(p.load_scene(), d, spp=1)
call = lambda: p.simulate(r.image, r.mask, d, eye=(0, 0, 600))"
  pyrow "python sweep 100" 480x270 "d = p.load_display('d480.json')
r = p.render(p.load_scene(), d, spp=1)
call = lambda: p.sweep(r.image, r.mask, d, 100)"
fi

if [ "$failures" -gt 0 ]; then
  echo "FAIL: $failures rows outside 0.9-1.1 (peak / estimate) or failed"
  exit 1
fi
echo "all rows within 0.9-1.1"

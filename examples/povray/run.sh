#!/usr/bin/env bash
# The peer route, timed against `parallax render` in one session (docs/speed.md, "Against the
# peer route"): POV-Ray 3.7 renders one 1920x1080 view per design eye of the built-in display
# (9 views, 16 samples per pixel: +A0.0 +AM1 +R4, every pixel a 4x4 grid), and `parallax
# interlace` maps them onto the image layer (the paper's Fig. 2). Needs Debian's povray.
#
#   examples/povray/run.sh [BUILD_DIR] [OUT_DIR]
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
build="${1:-$here/../../build}"
out="${2:-$here/../../out/povray}"
command -v povray >/dev/null || { echo "run.sh: needs povray (apt-get install povray)" >&2; exit 1; }
mkdir -p "$out"
views=9
# The design eyes: the view zone (496.6 mm at 600 mm) split into 9, in POV units (131.82 mm).
start=$(date +%s.%N)
files=()
for k in $(seq 0 $((views - 1))); do
  eye=$(awk -v k="$k" -v n="$views" 'BEGIN { printf "%.6f", (496.5705 * ((k + 0.5) / n - 0.5)) / 131.82 }')
  povray +I"$here/builtin.pov" +O"$out/view-$k.png" +W1920 +H1080 +A0.0 +AM1 +R4 +FN \
    Declare=EYE_X="$eye" -D -V -GA 2>/dev/null
  files+=("$out/view-$k.png")
done
"$build/parallax" interlace "${files[@]}" -o "$out/interlaced" >/dev/null
end=$(date +%s.%N)
"$build/parallax" render -o "$out/parallax" >/dev/null 2>&1
end2=$(date +%s.%N)
awk -v a="$start" -v b="$end" -v c="$end2" \
  'BEGIN { printf "POV-Ray 9 views + interlace: %.1f s\nparallax render:             %.2f s\nratio: %.0fx\n", b - a, c - b, (b - a) / (c - b) }'

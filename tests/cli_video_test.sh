#!/usr/bin/env bash
# `parallax simulate --sweep N --video FILE`: the sweep's pictures as a video (docs/video.md).
# The frames' contents are checked by the video module's tests (decoded against their inputs);
# here: the files, the printed line, the container and codec in the file's bytes, determinism
# and the one-line errors.
# Usage: cli_video_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

cat >"$tmp/small.json" <<'JSON'
{"image_layer": {"resolution": [96, 54], "pixel_pitch_mm": 0.5}, "gap_mm": 3,
 "views": 9, "view_distance_mm": 600}
JSON
check "render small layers" run 0 render --display "$tmp/small.json" --spp 1 -o "$tmp/r"

# bytes FILE OFFSET COUNT: the bytes as hex
bytes() { od -An -tx1 -j"$2" -N"$3" "$1" | tr -d ' \n'; }

check "sweep to MP4" run 0 simulate "$tmp/r" --sweep 5 -o "$tmp/s/sweep" --video "$tmp/s/sweep.mp4"
check "MP4 written" test -s "$tmp/s/sweep.mp4"
check "MP4 'ftyp' box first" test "$(bytes "$tmp/s/sweep.mp4" 4 4)" = "66747970"
check "printed line: frames, size, codec" \
  grep -qE "^wrote $tmp/s/sweep.mp4: 5 frames, 96x54 \(coded 96x54\), h264, [0-9]+ bytes$" "$tmp/out"
check "printed bytes are the file's" \
  grep -q " $(stat -c %s "$tmp/s/sweep.mp4") bytes$" "$tmp/out"
check "H.264 in the file" grep -q "avc1" "$tmp/s/sweep.mp4"
check "the sweep's other files too" test -s "$tmp/s/sweep-anim.png" -a -s "$tmp/s/sweep.html"
check "no temporary file left" test "$(ls "$tmp/s" | wc -l)" -eq 4

# Deterministic: the same sweep gives the same bytes.
check "second run" run 0 simulate "$tmp/r" --sweep 5 -o "$tmp/s2/sweep" --video "$tmp/s2/sweep.mp4"
check "same bytes twice" cmp -s "$tmp/s/sweep.mp4" "$tmp/s2/sweep.mp4"

check "sweep to H.265" run 0 simulate "$tmp/r" --sweep 4 -o "$tmp/h/sweep" \
  --video "$tmp/h/sweep.mp4" --video-codec h265 --video-quality 30 --fps 12
check "H.265 printed" grep -q ": 4 frames, 96x54 (coded 96x54), h265, " "$tmp/out"
check "H.265 as 'hvc1' (Apple's players)" grep -q "hvc1" "$tmp/h/sweep.mp4"

check "sweep to WebM" run 0 simulate "$tmp/r" --sweep 3 -o "$tmp/w/sweep" --video "$tmp/w/sweep.webm" --json
check "WebM's EBML header" test "$(bytes "$tmp/w/sweep.webm" 0 4)" = "1a45dfa3"
check "JSON names the video" grep -q '"codec": "vp9"' "$tmp/out"
check "JSON counts its frames" grep -q '"frames": 3' "$tmp/out"

# Errors: one line naming the option, exit 2, before any work, and no file.
refuse() {  # refuse NAME OPTION ARGS...
  local name=$1 option=$2
  shift 2
  check "$name exits 2" run 2 "$@"
  check "$name names $option" one_line_naming "$option"
}
refuse "--video without --sweep" --video simulate "$tmp/r" -o "$tmp/e/one.png" --video "$tmp/e/v.mp4"
refuse "unknown extension" --video simulate "$tmp/r" --sweep 3 -o "$tmp/e/s" --video "$tmp/e/v.avi"
refuse "a folder as the video" --video simulate "$tmp/r" --sweep 3 -o "$tmp/e/s" --video "$tmp/s2/"
mkdir -p "$tmp/dir.mp4"
refuse "a folder named .mp4" --video simulate "$tmp/r" --sweep 3 -o "$tmp/e/s" --video "$tmp/dir.mp4"
refuse "VP9 in MP4" --video-codec simulate "$tmp/r" --sweep 3 -o "$tmp/e/s" --video "$tmp/e/v.mp4" \
  --video-codec vp9
refuse "unknown codec" --video-codec simulate "$tmp/r" --sweep 3 -o "$tmp/e/s" --video "$tmp/e/v.mp4" \
  --video-codec av1
refuse "quality 52 for h264" --video-quality simulate "$tmp/r" --sweep 3 -o "$tmp/e/s" \
  --video "$tmp/e/v.mp4" --video-quality 52
refuse "quality 64" --video-quality simulate "$tmp/r" --sweep 3 -o "$tmp/e/s" \
  --video "$tmp/e/v.webm" --video-quality 64
for bad in 0 -1 241 nan abc; do
  refuse "--fps $bad" --fps simulate "$tmp/r" --sweep 3 -o "$tmp/e/s" --video "$tmp/e/v.mp4" --fps "$bad"
done
check "nothing written after the errors" test ! -e "$tmp/e"
cli_summary

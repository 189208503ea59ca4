#!/usr/bin/env bash
# Content from the command line: a sequence encoded as a video (render and view), RGB-D photos
# rendered for a display, and their refusals.
# Usage: cli_content_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

cp "$src/tests/fixtures/displays/small-9-views.json" "$tmp/small.json"
record() {  # record FILE KEY...: a value of a JSON file
  python3 -c '
import json, sys
v = json.load(open(sys.argv[1]))
for k in sys.argv[2:]: v = v[k]
print(v)' "$@"
}

# A turntable of 3 frames as an MP4 of the image layers.
check "render a sequence with --video" run 0 render --display "$tmp/small.json" --spp 1 \
  --turntable 90 --duration 0.1 --fps 30 --video "$tmp/turn.mp4" -o "$tmp/turn"
check "the video is an MP4" bash -c "head -c 8 '$tmp/turn.mp4' | tail -c 4 | grep -q ftyp"
check "the video holds the 3 frames" grep -q "3 frames" "$tmp/out"
# Resumed with nothing left to render, the video is made again from the finished frames.
rm "$tmp/turn.mp4"
check "a finished sequence still makes its video" run 0 render --display "$tmp/small.json" --spp 1 \
  --turntable 90 --duration 0.1 --fps 30 --video "$tmp/turn.mp4" -o "$tmp/turn"
check "0 to render, 3 finished" grep -q "0 to render, 3 finished before" "$tmp/out"
check "the video is back" test -s "$tmp/turn.mp4"
check "view a sequence as a WebM" run 0 view --size 64x36 --spp 1 --turntable 180 --duration 0.1 \
  --fps 20 --video "$tmp/v.webm" -o "$tmp/v/view.png"
check "a WebM (EBML header)" bash -c "head -c 4 '$tmp/v.webm' | od -An -tx1 | tr -d ' \n' | grep -q 1a45dfa3"
check "--video needs a sequence" run 2 render --display "$tmp/small.json" --video "$tmp/x.mp4" -o "$tmp/bad"
check "names --video" one_line_naming "--video"
check "an unknown container" run 2 view --turntable 90 --video "$tmp/x.avi" -o "$tmp/bad/v.png"
check "names --video again" one_line_naming "--video"
check "nothing written" test ! -e "$tmp/bad"

# An RGB-D photo rendered for the display, and seen as an ordinary picture.
write_png "$tmp/photo.png" 64 48 colour
write_png "$tmp/depth.png" 64 48 depth16
check "render --rgbd" run 0 render --rgbd "$tmp/photo.png" "$tmp/depth.png" --display "$tmp/small.json" --spp 1 -o "$tmp/rgbd"
check "rgbd layers" bash -c "test -s '$tmp/rgbd/image.png' && test -s '$tmp/rgbd/mask.png'"
check "the photo's choices are recorded" test "$(record "$tmp/rgbd/render.json" rgbd convention)" = disparity
check "render --rgbd layered" run 0 render --rgbd "$tmp/photo.png" "$tmp/depth.png" --rgbd-edges layered \
  --depth-convention depth --depth-range 2:5 --display "$tmp/small.json" --spp 1 -o "$tmp/rgbd2"
check "layered is recorded" test "$(record "$tmp/rgbd2/render.json" rgbd edges)" = layered
check "layered differs from stretch" bash -c "! cmp -s '$tmp/rgbd/image.png' '$tmp/rgbd2/image.png'"
check "view --rgbd" run 0 view --rgbd "$tmp/photo.png" "$tmp/depth.png" --size 64x48 --spp 1 -o "$tmp/rgbd-view.png"
check "view --rgbd wrote a PNG" is_png "$tmp/rgbd-view.png"
check "render --rgbd for a Looking Glass panel" run 0 render --rgbd "$tmp/photo.png" "$tmp/depth.png" \
  --display lkg:go --spp 1 --filter none -o "$tmp/rgbd-lkg"
check "the panel's record names the photo" test "$(record "$tmp/rgbd-lkg/render.json" rgbd edges)" = stretch
write_png "$tmp/depth-small.png" 32 48 depth16
check "sizes must match" run 2 render --rgbd "$tmp/photo.png" "$tmp/depth-small.png" -o "$tmp/bad"
check "names the depth map and --rgbd" one_line_naming "--rgbd"
check "a bad range" run 2 render --rgbd "$tmp/photo.png" "$tmp/depth.png" --depth-range 3:1 -o "$tmp/bad"
check "names --depth-range" one_line_naming "--depth-range"
check "a scene and a photo at once" run 2 render scene.json --rgbd "$tmp/photo.png" "$tmp/depth.png" -o "$tmp/bad"
check "still nothing written" test ! -e "$tmp/bad"
cli_summary

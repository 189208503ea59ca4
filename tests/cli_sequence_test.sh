#!/usr/bin/env bash
# Frame sequences from the command line (docs/animation.md): a turntable rendered once and in
# parts (the same frames, byte for byte), a killed sequence resumed, framing fixed over the
# sequence, quilts and views per frame, camera keys from a scene file, and refusals.
# Usage: cli_sequence_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

cp "$src/tests/fixtures/displays/small-9-views.json" "$tmp/small.json"
frames() { ls -d "$1"/frame-* 2>/dev/null | xargs -n1 basename | tr '\n' ' '; }
record() {  # record FILE KEY...: a value of render.json
  python3 -c '
import json, sys
v = json.load(open(sys.argv[1]))
for k in sys.argv[2:]: v = v[k]
print(v)' "$@"
}

# A quarter turn over 4 frames (0.2 s at 20 fps): 0, 22.5, 45 and 67.5 degrees.
turn=(render --display "$tmp/small.json" --spp 4 --turntable 90 --duration 0.2 --fps 20)
check "render a turntable" run 0 "${turn[@]}" -o "$tmp/all"
check "four frame folders" test "$(frames "$tmp/all")" = "frame-0001 frame-0002 frame-0003 frame-0004 "
for k in 1 2 3 4; do
  check "frame $k has both layers" bash -c "test -s '$tmp/all/frame-000$k/image.png' && test -s '$tmp/all/frame-000$k/mask.png'"
done
check "frames differ as the content turns" bash -c "! cmp -s '$tmp/all/frame-0001/image.png' '$tmp/all/frame-0002/image.png'"
check "the sequence is recorded" test "$(record "$tmp/all/frame-0003/render.json" sequence frame)" = 3
check "frame 3 is at 0.1 s" python3 -c "import sys; assert abs(float(sys.argv[1]) - 0.1) < 1e-9" \
  "$(record "$tmp/all/frame-0003/render.json" sequence seconds)"
check "the BVH is refitted" grep -q "refitted" "$tmp/out"
# One framing for the whole sequence: the content keeps its size (no pumping).
w1=$(record "$tmp/all/frame-0001/render.json" scene_display width)
w4=$(record "$tmp/all/frame-0004/render.json" scene_display width)
check "the framing is the same in every frame ($w1, $w4)" test "$w1" = "$w4"
g1=$(record "$tmp/all/frame-0001/render.json" framing virtual_gap_mm)
g4=$(record "$tmp/all/frame-0004/render.json" framing virtual_gap_mm)
check "the depth framing is the same in every frame ($g1, $g4)" test "$g1" = "$g4"

# Frames 3 and 4 alone (a fresh BVH at frame 3, not a refitted one) are the same pictures.
check "render frames 3:4 apart" run 0 "${turn[@]}" --frames 3:4 -o "$tmp/part"
check "only frames 3 and 4" test "$(frames "$tmp/part")" = "frame-0003 frame-0004 "
for k in 3 4; do
  check "frame $k alone equals frame $k of the whole" cmp "$tmp/all/frame-000$k/image.png" "$tmp/part/frame-000$k/image.png"
done

# A killed sequence resumes: finished frames are skipped, the rest rendered.
rm -rf "$tmp/all/frame-0002"
mkdir -p "$tmp/all/.frame-0004.tmp-999999"  # the temporary folder of a killed run
touch -d '2001-01-01' "$tmp/all/frame-0001/image.png"
check "resume" run 0 "${turn[@]}" -o "$tmp/all"
check "resume renders only the missing frame" grep -q "1 to render, 3 finished before" "$tmp/out"
check "frame 2 is back" test -s "$tmp/all/frame-0002/image.png"
check "finished frames are left alone" test "$(stat -c %Y "$tmp/all/frame-0001/image.png")" = "$(date -d 2001-01-01 +%s)"
check "frame 2 again is the same picture" cmp "$tmp/all/frame-0002/image.png" "$tmp/part/../all/frame-0002/image.png"

# A resume with other settings is refused before it renders, naming the setting that differs
# (docs/animation.md, "Resuming"): never a video of mixed frames.
check "each frame records what it was made from" grep -q '"made_from"' "$tmp/all/frame-0001/render.json"
rm -rf "$tmp/all/frame-0003"
stamp=$(stat -c %Y "$tmp/all/frame-0001/image.png")
mixed() {  # mixed NAME TEXT ARGS...: a resume with ARGS is refused naming TEXT; nothing rendered
  local name=$1 text=$2
  shift 2
  check "resume with $name is refused" run 2 "$@" -o "$tmp/all"
  check "names $name" one_line_naming "$text"
  check "says how to start over" grep -qF "give another --output, or remove $tmp/all to start over" "$tmp/err"
  check "frame 3 was not rendered ($name)" test ! -e "$tmp/all/frame-0003"
}
mixed "--spp" "--spp: it was made with 4, this run asks 1" render --display "$tmp/small.json" --spp 1 --turntable 90 --duration 0.2 --fps 20
mixed "--turntable" "--turntable: it was made with 90, this run asks 180" render --display "$tmp/small.json" --spp 4 --turntable 180 --duration 0.4 --fps 10
mixed "--layers" "--layers: it was made with slits, this run asks nmf" "${turn[@]}" --layers nmf --iterations 1
mixed "--quilt" "--quilt: it was made with off, this run asks 3x1" "${turn[@]}" --quilt 3x1 --size 48x12
cp "$tmp/small.json" "$tmp/small-copy.json"
mixed "--display" "--display: it was made with $tmp/small.json, this run asks $tmp/small-copy.json" \
  render --display "$tmp/small-copy.json" --spp 4 --turntable 90 --duration 0.2 --fps 20
cp "$tmp/small.json" "$tmp/small.json.orig"
echo " " >>"$tmp/small.json"  # the same name, other bytes
mixed "a changed display file" "was made from another version of $tmp/small.json" "${turn[@]}"
mv "$tmp/small.json.orig" "$tmp/small.json"
check "the finished frames were left alone by the refusals" test "$(stat -c %Y "$tmp/all/frame-0001/image.png")" = "$stamp"
check "the matching resume still works" run 0 "${turn[@]}" -o "$tmp/all"
check "it renders only frame 3" grep -q "1 to render, 3 finished before" "$tmp/out"
check "frame 3 again is the same picture" cmp "$tmp/all/frame-0003/image.png" "$tmp/part/frame-0003/image.png"

# simulate --reference of a frame poses the scene at the frame's time (and frames it over the
# whole animation, as the render did): frame 4 scores as well as frame 1 (measured 31.9 and
# 31.5 dB; against the scene at rest, frame 4 scored 21.5 dB).
psnr_of() {
  "$bin" simulate "$1" --reference --eye 0,0,600 --json 2>/dev/null |
    python3 -c 'import json, sys; print(json.load(sys.stdin)["mean"]["psnr"])'
}
p1=$(psnr_of "$tmp/all/frame-0001")
p4=$(psnr_of "$tmp/all/frame-0004")
check "frame 4's reference is posed ($p1, $p4 dB)" awk -v a="$p1" -v b="$p4" 'BEGIN { exit !(a > 28 && b > 28 && b > a - 2) }'

# What one eye sees in each frame, and as a video.
check "simulate the frames" run 0 simulate "$tmp/all" --frames all --video "$tmp/seen.mp4" --fps 20 -o "$tmp/seen/eye.png"
check "one picture per frame" bash -c "for k in 1 2 3 4; do test -s '$tmp/seen/eye-000'\$k.png || exit 1; done"
check "the seen frames differ" bash -c "! cmp -s '$tmp/seen/eye-0001.png' '$tmp/seen/eye-0004.png'"
check "a video of the seen frames" grep -q "4 frames" "$tmp/out"
check "simulate frames 2:3" run 0 simulate "$tmp/all" --frames 2:3 --eye 30,0,600 -o "$tmp/seen2/eye.png"
check "only frames 2 and 3" bash -c "test -s '$tmp/seen2/eye-0002.png' && test -s '$tmp/seen2/eye-0003.png' && ! test -e '$tmp/seen2/eye-0001.png'"
check "simulate frames beyond the sequence" run 2 simulate "$tmp/all" --frames 2:9 -o "$tmp/bad/e.png"
check "names --frames" one_line_naming "--frames"
check "simulate --frames of a folder without frames" run 2 simulate "$tmp/all/frame-0001" --frames all -o "$tmp/bad/e.png"
check "names the folder" one_line_naming "no rendered frames"

# A full turn loops: frame N + 1 would be frame 1; with 360 degrees over 4 frames, frame 3 is
# the half turn.
check "quilt sequence" run 0 render --display "$tmp/small.json" --spp 1 --quilt 3x1 --size 48x12 \
  --turntable 360 --duration 0.2 --fps 20 --frames 1:2 -o "$tmp/quilts"
check "one quilt per frame" bash -c "ls '$tmp/quilts/frame-0001/'quilt_qs3x1*.png && ls '$tmp/quilts/frame-0002/'quilt_qs3x1*.png" 
# A quilt video carries the layout Looking Glass Studio imports it by, the display's aspect.
aspect=$(sed -n 's/.*quilt_qs3x1a\([0-9.]*\)\.png.*/\1/p' "$tmp/quilts/frame-0001/render.json" | head -1)
check "quilt video" run 0 render --display "$tmp/small.json" --spp 1 --quilt 3x1 --size 48x12 \
  --turntable 360 --duration 0.2 --fps 20 --frames 1:2 -o "$tmp/quilts" --video "$tmp/turn.mp4"
check "the video is named for its quilt" test -s "$tmp/turn_qs3x1a$aspect.mp4"
check "the result line names it" grep -qF "turn_qs3x1a$aspect.mp4: 2 frames" "$tmp/out"
check "no video under the bare name" test ! -e "$tmp/turn.mp4"
check "a video named for another quilt exits 2" run 2 render --display "$tmp/small.json" --spp 1 \
  --quilt 3x1 --size 48x12 --turntable 360 --duration 0.2 --fps 20 --frames 1:2 \
  -o "$tmp/quilts" --video "$tmp/turn_qs8x6a0.75.mp4"
check "and names --video" one_line_naming "--video"

# view: numbered pictures.
check "view sequence" run 0 view --size 64x36 --spp 1 --turntable 180 --duration 0.1 --fps 20 -o "$tmp/v/view.png"
check "numbered views" bash -c "test -s '$tmp/v/view-0001.png' && test -s '$tmp/v/view-0002.png' && ! test -e '$tmp/v/view-0003.png'"

# A scene file whose content changed, and a view sequence resumed with other settings.
cat >"$tmp/box.json" <<'JSON'
{
  "materials": {"grey": {"diffuse": [0.7, 0.7, 0.7]}},
  "objects": [{"shape": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "material": "grey"}],
  "lights": [{"type": "point", "position": [3, 4, 5], "intensity": [40, 40, 40]}]
}
JSON
boxturn=(render "$tmp/box.json" --display "$tmp/small.json" --spp 1 --turntable 90 --duration 0.2 --fps 20)
check "a scene file's sequence" run 0 "${boxturn[@]}" --frames 1:2 -o "$tmp/box"
sed -i 's/0.7, 0.7, 0.7/0.2, 0.7, 0.7/' "$tmp/box.json"
check "resumed after the scene file changed is refused" run 2 "${boxturn[@]}" -o "$tmp/box"
check "names the scene file" one_line_naming "was made from another version of $tmp/box.json"
check "no frame 3" test ! -e "$tmp/box/frame-0003"
check "view sequence resumed with another --spp is refused" run 2 view --size 64x36 --spp 2 --turntable 180 --duration 0.1 --fps 20 -o "$tmp/v/view.png"
check "names --spp" one_line_naming "--spp: it was made with 1, this run asks 2"
check "view sequence resumed with another --size is refused" run 2 view --size 64x32 --spp 1 --turntable 180 --duration 0.1 --fps 20 -o "$tmp/v/view.png"
check "names --size" one_line_naming "--size"
check "view sequence resumed as it was" run 0 view --size 64x36 --spp 1 --turntable 180 --duration 0.1 --fps 20 -o "$tmp/v/view.png"
check "nothing to render" grep -q "0 to render, 2 finished before" "$tmp/out"

# Camera keys in a scene file: the camera moves between them.
cat >"$tmp/keys.json" <<'JSON'
{
  "materials": {"grey": {"diffuse": [0.7, 0.7, 0.7]}},
  "objects": [{"shape": "box", "min": [-1, -1, -1], "max": [1, 1, 1], "material": "grey"}],
  "lights": [{"type": "point", "position": [3, 4, 5], "intensity": [40, 40, 40]}],
  "animation": {"camera": [
    {"time": 0, "eye": [0, 0, 6], "look_at": [0, 0, 0]},
    {"time": 1, "eye": [6, 0, 0], "look_at": [0, 0, 0]}
  ]}
}
JSON
check "camera keys" run 0 view "$tmp/keys.json" --size 64x36 --spp 1 --fps 2 -o "$tmp/k/view.png" --frames 1:3
check "three frames from 1 s at 2 fps" bash -c "test -s '$tmp/k/view-0003.png' && ! test -e '$tmp/k/view-0004.png'"
check "the camera moved" bash -c "! cmp -s '$tmp/k/view-0001.png' '$tmp/k/view-0003.png'"
# --video alone on an animated scene: its whole animation, as Blender renders a frame range.
check "--video alone plays the scene's animation" run 0 view "$tmp/keys.json" --size 64x36 \
  --spp 1 --fps 2 -o "$tmp/kv/view.png" --video "$tmp/keys.mp4"
check "all three frames, then the video" bash -c "test -s '$tmp/kv/view-0003.png' && \
  ! test -e '$tmp/kv/view-0004.png' && test -s '$tmp/keys.mp4'"
check "the video has the three frames" grep -q "keys.mp4: 3 frames" "$tmp/out"
check "and says so" grep -q "makes all 3 frames at 2 fps" "$tmp/err"
check "the same frames as --frames 1:3" cmp "$tmp/k/view-0002.png" "$tmp/kv/view-0002.png"
check "render --video alone too" run 0 render "$tmp/keys.json" --display "$tmp/small.json" \
  --spp 1 --fps 2 -o "$tmp/kr" --video "$tmp/kr.mp4"
check "render made the frames' layers" test -s "$tmp/kr/frame-0003/image.png"
check "--video of a still scene exits 2" run 2 view --size 64x36 --spp 1 -o "$tmp/still/v.png" \
  --video "$tmp/still.mp4"
check "names --video and what to add" one_line_naming "the scene has no animation: add --turntable"
check "no video of a still scene" test ! -e "$tmp/still.mp4"

# Refusals: one line naming the option, exit 2, nothing written.
check "frames beyond the animation" run 2 "${turn[@]}" --frames 3:9 -o "$tmp/bad"
check "names --frames and the count" one_line_naming "the animation has 4 frames"
check "frames reversed" run 2 "${turn[@]}" --frames 3:2 -o "$tmp/bad"
check "names --frames" one_line_naming "--frames"
check "frame zero" run 2 "${turn[@]}" --frames 0:2 -o "$tmp/bad"
check "bad fps" run 2 "${turn[@]}" --fps 0 -o "$tmp/bad"
check "names --fps" one_line_naming "--fps"
check "keys out of order" bash -c "sed 's/\"time\": 1/\"time\": 0/' '$tmp/keys.json' > '$tmp/bad-keys.json'"
check "key times must increase" run 2 view "$tmp/bad-keys.json" --frames 1:2 -o "$tmp/bad/v.png"
check "names the key" one_line_naming "time"
check "nothing written" test ! -e "$tmp/bad"
cli_summary

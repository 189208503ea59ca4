#!/usr/bin/env bash
# `parallax show` under a virtual X server (Xvfb): the windows carry the layer pictures 1:1,
# read back from the screen (xwd) and compared with the PNG files pixel by pixel.
# Usage: cli_show_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"
compare="python3 $(dirname "$0")/screen_compare.py"
# Under the sanitizers: SDL loads the X11 and D-Bus client libraries at run time and unloads them
# at exit; what they keep past exit is reported as leaks in modules LeakSanitizer can no longer
# name. Leak checks stay on for every other command (the suite runs them all under ASan).
export ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0"

cat >"$tmp/small.json" <<'JSON'
{"image_layer": {"resolution": [96, 54], "pixel_pitch_mm": 0.5}, "gap_mm": 3,
 "views": 9, "view_distance_mm": 600}
JSON
check "render small layers" run 0 render --display "$tmp/small.json" --spp 1 -o "$tmp/r"
check "calibration patterns" run 0 calibrate patterns --display "$tmp/small.json" \
  --steps 3 -o "$tmp/c"

check "render nmf frame pairs" run 0 render --display "$tmp/small.json" --spp 1 --layers nmf \
  --rank 2 --iterations 1 --train-eyes 1 -o "$tmp/pairs"
check "render a two-frame sequence" run 0 render --display "$tmp/small.json" --spp 1 \
  --turntable 90 --frames 1:2 --fps 2 -o "$tmp/seq"
check "render a quilt" run 0 render --display "$tmp/small.json" --spp 1 --quilt 3x2 \
  --size 32x18 -o "$tmp/quilt"
# A small lenticular panel (96x128), a quilt for it, the same quilt interlaced by `interlace`,
# and a two-frame quilt video (a turntable) with each frame's quilt picture interlaced too.
cp "$src/tests/fixtures/displays/small-lenticular-96x128.json" "$tmp/lkg.json"
check "render a lenticular quilt" run 0 render --display "$tmp/lkg.json" --spp 1 --quilt 4x3 --size 24x32 \
  -o "$tmp/lq"
lquilt=$(ls "$tmp"/lq/*_qs4x3*.png)
check "interlace it" run 0 interlace "$lquilt" --display "$tmp/lkg.json" -o "$tmp/li"
check "render a quilt video" run 0 render --display "$tmp/lkg.json" --spp 1 --quilt 4x3 --size 24x32 \
  --turntable 180 --frames 1:2 --fps 2 --video "$tmp/lv/turn_qs4x3a0.75.mp4" -o "$tmp/lv"
for k in 1 2; do
  check "interlace the video's frame $k" run 0 interlace \
    "$(ls "$tmp"/lv/frame-000$k/*_qs4x3*.png)" --display "$tmp/lkg.json" -o "$tmp/lv$k"
done

# Errors come before any window, with or without a display.
check "a quilt without --display exits 2" run 2 show "$tmp/quilt"
check "it asks for the panel" one_line_naming "--display: a quilt is shown on the lenticular panel"
check "a quilt on a barrier display exits 2" run 2 show "$lquilt" --display "$tmp/small.json"
check "it names the display and interlace" one_line_naming "--display: a quilt is played on a lenticular panel"
check "--display without a quilt exits 2" run 2 show "$tmp/r" --display "$tmp/lkg.json"
check "it says what --display is for" one_line_naming "--display: applies to a quilt"
mkdir -p "$tmp/empty"
check "a folder of no layers exits 2" run 2 show "$tmp/empty"
check "it names what show plays" one_line_naming "image-K.png pairs"
check "a missing folder exits 2" run 2 show "$tmp/nothing"
check "a missing folder is named" one_line_naming "$tmp/nothing"
check "an unknown key exits 2" run 2 show "$tmp/r" --keys next,jump
check "an unknown key names the option" one_line_naming "--keys"
check "a pattern out of range exits 2" run 2 show "$tmp/c" --pattern 999
check "the pattern range names the option" one_line_naming "--pattern"
check "no display is one clear line" bash -c "DISPLAY= '$bin' show '$tmp/r' --windowed \
  --exit-after 1 2>'$tmp/nodisplay'; [ \$? -eq 1 ] && grep -q 'no display' '$tmp/nodisplay'"

# A virtual screen: the windows open at their places without a window manager. Without
# -noreset, as a user's own server runs: it resets whenever its last client leaves, which a show
# that connected twice (monitors, then windows) did not survive about 40 % of the time.
display=":$((90 + RANDOM % 400))"
Xvfb "$display" -screen 0 400x200x24 -nolisten tcp >/dev/null 2>&1 &
xvfb=$!
trap 'kill $xvfb 2>/dev/null; rm -rf "$tmp"' EXIT
for _ in $(seq 300); do xdpyinfo -display "$display" >/dev/null 2>&1 && break; sleep 0.1; done

# Shows DIR with the given options for a few seconds and takes a screenshot while it runs:
# retried until the screen matches or the time is up.
shot_matches() {  # shot_matches PICTURE X Y [MEAN] -- SHOW-ARGS...
  local picture=$1 x=$2 y=$3 mean=""
  shift 3
  if [ "$1" != "--" ]; then mean=$1; shift; fi
  shift
  DISPLAY=$display "$bin" show "$@" --windowed --exit-after 60 >"$tmp/show.out" 2>&1 &
  local pid=$!
  local ok=1
  # Up to about 30 s on a loaded machine; a match usually comes within the first second.
  for _ in $(seq 150); do
    sleep 0.2
    xwd -root -silent -display "$display" >"$tmp/shot.xwd" 2>/dev/null || continue
    if $compare "$tmp/shot.xwd" "$picture" "$x" "$y" $mean >"$tmp/compare.out"; then ok=0; break; fi
  done
  kill "$pid" 2>/dev/null
  wait "$pid" 2>/dev/null
  [ $ok -eq 0 ] || cat "$tmp/compare.out" "$tmp/show.out" >&2
  return $ok
}

check "the image layer is on the screen 1:1" shot_matches "$tmp/r/image.png" 0 0 -- "$tmp/r"
check "the mask layer is beside it 1:1" shot_matches "$tmp/r/mask.png" 96 0 -- "$tmp/r"
first_mask=$(python3 -c 'import json,sys; p=[q for q in json.load(open(sys.argv[1]))["patterns"] if q["layer"]=="mask"]; print(p[0]["file"], p[2]["file"])' "$tmp/c/index.json")
read -r mask0 mask2 <<<"$first_mask"
check "the first mask pattern is shown" shot_matches "$tmp/c/$mask0" 96 0 -- "$tmp/c"
check "two steps forward show the third pattern" shot_matches "$tmp/c/$mask2" 96 0 -- \
  "$tmp/c" --keys next,next
check "each step prints the pattern's period and phase" \
  bash -c "grep -c 'slit period .* phase' '$tmp/show.out' | grep -qx 3"
check "info prints the current pattern again" bash -c "DISPLAY=$display '$bin' show '$tmp/c' \
  --windowed --keys info,quit | grep -c 'pattern 1/' | grep -qx 2"
# nmf's pairs and a sequence's frames are played: every frame reaches the screen in turn (the
# pairs at 4 frames/s so that each stays up for several screenshots).
check "nmf pair 1's image is shown" shot_matches "$tmp/pairs/image-1.png" 0 0 -- "$tmp/pairs" --fps 4
check "nmf pair 2's image is shown" shot_matches "$tmp/pairs/image-2.png" 0 0 -- "$tmp/pairs" --fps 4
check "nmf pair 2's mask is shown beside it" shot_matches "$tmp/pairs/mask-2.png" 96 0 -- \
  "$tmp/pairs" --fps 4
check "show says what it plays" grep -q "playing 2 time-multiplexed frame pairs at 4 frames/s" \
  "$tmp/show.out"
check "the sequence's first frame is shown" shot_matches "$tmp/seq/frame-0001/image.png" 0 0 -- \
  "$tmp/seq"
check "the sequence's second frame is shown" shot_matches "$tmp/seq/frame-0002/image.png" 0 0 -- \
  "$tmp/seq"
check "at the sequence's own fps" grep -q "playing 2 sequence frames at 2 frames/s (the sequence's)" \
  "$tmp/show.out"

# A quilt picture and a quilt video on the lenticular panel, interlaced as shown: the picture
# is `interlace`'s (within one level), and each frame of the video is its frame's quilt
# interlaced (within the video's loss: a mean of a few levels).
check "a quilt on its panel is interlace's picture" shot_matches "$tmp/li/image.png" 0 0 -- \
  "$lquilt" --display "$tmp/lkg.json"
check "show says what it shows" grep -q "showing .*_qs4x3.* interlaced for 96x128" "$tmp/show.out"
check "a quilt's folder is played too" shot_matches "$tmp/li/image.png" 0 0 -- "$tmp/lq" \
  --display "$tmp/lkg.json"
for k in 1 2; do
  check "the quilt video's frame $k is shown interlaced" shot_matches "$tmp/lv$k/image.png" 0 0 \
    4 -- "$tmp/lv/turn_qs4x3a0.75.mp4" --display "$tmp/lkg.json" --fps 4
done
check "show says what it plays" grep -q "playing turn_qs4x3a0.75.mp4: 2 frames at 4 frames/s (--fps), interlaced for 96x128 as shown" "$tmp/show.out"
check "and how fast it went" grep -qE "shown [0-9]+ frames in .* frames/s\); per frame: decode" "$tmp/show.out"

# An X server that is not listening yet (being started with the show, or resetting after its
# last client left) is waited for a few seconds; one that never comes is one clear line.
late=":$((500 + RANDOM % 400))"
DISPLAY=$late "$bin" show "$tmp/r" --windowed --exit-after 1 >"$tmp/late.out" 2>&1 &
late_show=$!
sleep 0.7
Xvfb "$late" -screen 0 200x100x24 -nolisten tcp >/dev/null 2>&1 &
late_xvfb=$!
trap 'kill $xvfb $late_xvfb 2>/dev/null; rm -rf "$tmp"' EXIT
check "a server started after the show is waited for" wait "$late_show"
# Stopped once it answers: a TERM before its exec would reach the forked shell, not Xvfb.
for _ in $(seq 300); do xdpyinfo -display "$late" >/dev/null 2>&1 && break; sleep 0.1; done
kill "$late_xvfb" 2>/dev/null
wait "$late_xvfb" 2>/dev/null
check "a server that never comes is one clear line" bash -c "DISPLAY=$late '$bin' show '$tmp/r' \
  --windowed --exit-after 1 2>'$tmp/gone'; [ \$? -eq 1 ] && [ \$(wc -l <'$tmp/gone') -eq 1 ] \
  && grep -q 'no display' '$tmp/gone'"

check "quit closes at once" bash -c "DISPLAY=$display timeout 5 '$bin' show '$tmp/r' --windowed \
  --keys quit"

# The shots to photograph (calibrate patterns --photo) shown 1:1: a barrier's two layers side by
# side, a lenticular panel's one picture, on a screen wide enough for them.
cat >"$tmp/mid.json" <<'JSON'
{"image_layer": {"resolution": [640, 360], "pixel_pitch_mm": 0.5}, "gap_mm": 3,
 "views": 9, "view_distance_mm": 600}
JSON
sed 's/"screenW": {"value": 96}, "screenH": {"value": 128}/"screenW": {"value": 240}, "screenH": {"value": 320}/' \
  "$tmp/lkg.json" >"$tmp/lkg240.json"
check "barrier shots" run 0 calibrate patterns --photo --display "$tmp/mid.json" -o "$tmp/shots"
check "lenticular shots" run 0 calibrate patterns --photo --display "$tmp/lkg240.json" \
  -o "$tmp/lshots"
display=":$((500 + RANDOM % 400))"
Xvfb "$display" -screen 0 1300x400x24 -nolisten tcp >/dev/null 2>&1 &
wide_xvfb=$!
trap 'kill $xvfb $wide_xvfb 2>/dev/null; rm -rf "$tmp"' EXIT
for _ in $(seq 300); do xdpyinfo -display "$display" >/dev/null 2>&1 && break; sleep 0.1; done
check "the shot's image layer is on the screen 1:1" shot_matches "$tmp/shots/grid-image.png" 0 0 \
  -- "$tmp/shots"
check "the shot's mask layer is beside it 1:1" shot_matches "$tmp/shots/grid-mask.png" 640 0 \
  -- "$tmp/shots"
check "a lenticular shot is on its panel 1:1" shot_matches "$tmp/lshots/lens-panel.png" 0 0 \
  -- "$tmp/lshots"

cli_summary

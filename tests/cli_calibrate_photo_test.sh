#!/usr/bin/env bash
# `parallax calibrate patterns --photo`, `calibrate photo` and `calibrate study` as a user meets
# them: the shots for each display kind, photos made by the photo maker (the study keeps them)
# measured through the command line as a user's are, and the refusals of bad photos.
# Usage: cli_calibrate_photo_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"
# near A B TOLERANCE: |A - B| <= TOLERANCE
near() {
  [ -n "$1" ] && [ -n "$2" ] &&
    awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'
}

# The shots: the barrier's two layers at their resolution, and the index naming them.
check "barrier shots" run 0 calibrate patterns --photo -o "$tmp/shots"
check "shots: index kind" test "$(json_at "$tmp/shots/index.json" /kind)" = barrier
check "shots: the grid shot" test "$(json_at "$tmp/shots/index.json" /shots/0/name)" = grid
for f in grid-image grid-mask; do
  check "shots: $f.png is 1920x1080" test "$(png_size "$tmp/shots/$f.png")" = 1920x1080
done
check "shots: the nominal display kept" run 0 design "$tmp/shots/display.json"
# Any display kind, Looking Glass presets by name too.
check "lenticular shots" run 0 calibrate patterns --photo --display lkg:portrait -o "$tmp/lshots"
# The paper's slit patterns are a barrier's: a lenticular panel is told to use the photo shots.
check "slit patterns for a lenticular panel: exit 2" run 2 calibrate patterns --display \
  lkg:portrait -o "$tmp/slits"
check "slit patterns for a lenticular panel: one line" one_line_naming "calibrate patterns --photo"
check "lenticular shot: the panel" test "$(png_size "$tmp/lshots/lens-panel.png")" = 1536x2048
check "lenticular shot: index" test "$(json_at "$tmp/lshots/index.json" /shots/0/panel)" = \
  lens-panel.png

# Photos from the photo maker: one set of the built-in display as a 12-megapixel phone takes
# them, the true display's gap up to 20 % off and its mask panel sitting pixels off, kept as
# JPEG files.
check "study keeps its photos" run 0 calibrate study --sets 1 --samples 16 --seed 3 \
  --keep-photos "$tmp/photos" --json
cp "$tmp/out" "$tmp/study.json"
check "study: nothing refused" test "$(json_at "$tmp/study.json" /refused)" = 0
gap_true=$(json_at "$tmp/study.json" /trials/0/truths/0)
offset_true=$(json_at "$tmp/study.json" /trials/0/truths/1)
check "study: gap within 1 %" near "$(json_at "$tmp/study.json" /trials/0/errors/0)" 0 0.01
check "study: offset within 0.1 px" near "$(json_at "$tmp/study.json" /trials/0/errors/1)" 0 0.1

# The same photos through calibrate photo, in either order: the display file it writes.
photos=("$tmp/photos/grid-1-2.jpg" "$tmp/photos/grid-1-1.jpg")
check "calibrate photo" run 0 calibrate photo --shots "$tmp/shots" "${photos[@]}" \
  -o "$tmp/measured.json" --json
cp "$tmp/out" "$tmp/report.json"
check "measured gap near the truth" near "$(json_at "$tmp/measured.json" /gap_mm)" "$gap_true" \
  "$(awk -v g="$gap_true" 'BEGIN { print 0.01 * g }')"
check "measured offset near the truth" \
  near "$(json_at "$tmp/measured.json" /mask/panel_offset_px)" "$offset_true" 0.1
check "measured: the same as the study's" near "$(json_at "$tmp/measured.json" /gap_mm)" \
  "$(json_at "$tmp/study.json" /trials/0/estimates/0)" 1e-6
check "measured: the nominal's views kept" near "$(json_at "$tmp/measured.json" /views)" 9 0
check "report: every estimate has a sigma" \
  python3 -c 'import json, sys
r = json.load(open(sys.argv[1]))
assert r["gap_mm"]["sigma"] > 0 and r["mask"]["panel_offset_px"]["sigma"] > 0' "$tmp/report.json"
check "the measured display renders" run 0 design "$tmp/measured.json"
check "text report" run 0 calibrate photo --shots "$tmp/shots" "${photos[@]}" -o "$tmp/m2.json"
check "text report: gap with its sigma" grep -q "^gap .* ± " "$tmp/out"

# Refusals: one line naming the photo or the option, exit 2, nothing written.
refused() {  # refused NAME TEXT ARGS...
  local name=$1 text=$2
  shift 2
  rm -f "$tmp/refused.json"
  check "$name: exit 2" run 2 calibrate photo --shots "$tmp/shots" "$@" -o "$tmp/refused.json"
  check "$name: one line" one_line_naming "$text"
  check "$name: nothing written" test ! -e "$tmp/refused.json"
}
cp "${photos[0]}" "$tmp/photo.jpg"
refused "a photo named after no shot" "photo.jpg: matches no shot" "$tmp/photo.jpg"
refused "a missing photo" "grid-9.jpg: file not found" "$tmp/grid-9.jpg"
mkfifo "$tmp/grid-fifo.jpg"
refused "a FIFO" "grid-fifo.jpg: not a regular file" "$tmp/grid-fifo.jpg"
echo "not a photo" >"$tmp/grid-text.jpg"
refused "not a photo" "grid-text.jpg: not a JPEG or PNG" "$tmp/grid-text.jpg"
head -c 300 "${photos[0]}" >"$tmp/grid-cut.jpg"
refused "a truncated JPEG" "grid-cut.jpg" "$tmp/grid-cut.jpg"
write_png "$tmp/grid-blank.png" 640 480 colour
refused "a photo of no panel" "grid-blank.png: the panel was not found" "$tmp/grid-blank.png"
# The memory is estimated from the photos' headers before any is decoded.
rm -f "$tmp/refused.json"
check "over the memory limit: exit 2" run 2 calibrate photo --max-memory 0.3 --shots "$tmp/shots" \
  "${photos[@]}" -o "$tmp/refused.json"
check "over the memory limit: one line" one_line_naming "for the photos and finding their markers"
check "over the memory limit: nothing written" test ! -e "$tmp/refused.json"
check "shots not a folder: exit 2" run 2 calibrate photo --shots "$tmp/shots/index.json" \
  "${photos[@]}" -o "$tmp/refused.json"
check "shots not a folder: one line" one_line_naming "not a folder"
check "barrier photos against lenticular shots: exit 2" run 2 calibrate photo --shots \
  "$tmp/lshots" "${photos[@]}" -o "$tmp/refused.json"
check "barrier photos against lenticular shots: one line" one_line_naming "matches no shot"

# The seat check: photos of a lenticular panel's lens shot (the photo maker's, through a true
# sheet up to 1 % off the nominal Portrait's), read against the calibration the shot was drawn
# with: the view each seat sees, how it fans across the panel, the crosstalk.
check "lenticular study keeps its photos" run 0 calibrate study --display lkg:portrait --sets 1 \
  --samples 4 --seed 2 --photo-width 1512 --photo-height 1134 --keep-photos "$tmp/lphotos" --json
lphotos=("$tmp/lphotos/lens-1-1.jpg" "$tmp/lphotos/lens-1-2.jpg")
check "calibrate check" run 0 calibrate check --shots "$tmp/lshots" "${lphotos[@]}" --json
cp "$tmp/out" "$tmp/check.json"
check "check: a seat per photo, each view a fraction with its sigma" python3 -c 'import json, sys
r = json.load(open(sys.argv[1]))
assert len(r["seats"]) == 2 and r["views"] == 48
for s in r["seats"]:
    assert 0 <= s["view_seen"]["value"] < 1 and 0 < s["view_seen"]["sigma"] < 0.05
    assert 0 <= s["view_aimed"] < 1 and 0 < s["amplitude"] <= 1.2
    assert 0 <= s["other_views_share"] <= 1 and s["markers"] >= 6' "$tmp/check.json"
check "check: text" run 0 calibrate check --shots "$tmp/lshots" "${lphotos[0]}"
check "check: the view seen and the crosstalk" grep -q "^  sees .* at the panel's centre" "$tmp/out"
check "check: crosstalk line" grep -q "^  crosstalk .*of the light from other views" "$tmp/out"
check "check of barrier shots: exit 2" run 2 calibrate check --shots "$tmp/shots" "${photos[@]}"
check "check of barrier shots: one line" one_line_naming "holds barrier shots"

cli_summary

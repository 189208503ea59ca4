#!/usr/bin/env bash
# Multi-view content end to end: `render --quilt`, `interlace` from views and from a quilt, and
# their errors. Usage: cli_quilt_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"
# pfm_close A B: two PFM images of one size agree to 1e-3 in at least 99% of their values.
pfm_close() {
  [ "$(head -3 "$1")" = "$(head -3 "$2")" ] || return 1
  local header
  header=$(head -3 "$1" | wc -c)
  paste <(tail -c +$((header + 1)) "$1" | od -An -v -f -w4) \
    <(tail -c +$((header + 1)) "$2" | od -An -v -f -w4) |
    awk '{ n++; d = $1 - $2; if (d < 0) d = -d; if (d <= 1e-3) ok++ } END { exit !(n > 0 && ok >= 0.99 * n) }'
}

# A small 9-view display: 96 x 54 pixels, 16:9.
cat >"$tmp/small.json" <<'JSON'
{"image_layer": {"resolution": [96, 54], "pixel_pitch_mm": 0.2745, "subpixels": "RGB"},
 "gap_mm": 3, "view_distance_mm": 600, "views": 9}
JSON
small=(--display "$tmp/small.json")

# render --quilt: the file name carries the layout and the aspect of one view.
check "render --quilt" run 0 render "${small[@]}" --quilt 3x3 --spp 1 -o "$tmp/q" --linear
check "quilt file named in the convention" is_png "$tmp/q/quilt_qs3x3a1.7778.png"
check "linear quilt beside it" test -s "$tmp/q/quilt_qs3x3a1.7778.pfm"
check "render reports the quilt" grep -qF "quilt_qs3x3a1.7778.png" "$tmp/out"
check "quilt recorded in render.json" grep -q '"method": "quilt"' "$tmp/q/render.json"
# Without --linear the quilt is kept as 8-bit codes view by view: the same PNG, byte for byte,
# as the float quilt's.
check "render --quilt without --linear" run 0 render "${small[@]}" --quilt 3x3 --spp 1 -o "$tmp/q8"
check "8-bit quilt = float quilt's PNG" cmp -s "$tmp/q/quilt_qs3x3a1.7778.png" \
  "$tmp/q8/quilt_qs3x3a1.7778.png"
check "no linear quilt without --linear" test ! -e "$tmp/q8/quilt_qs3x3a1.7778.pfm"
check "quilt with another view size" run 0 render "${small[@]}" --quilt 5x2 --size 40x30 --spp 1 \
  -o "$tmp/q2"
# The name's aspect is the display's (Looking Glass's convention), whatever the tiles' shape.
check "5x2 of 40x30 on a 16:9 display: a1.7778" is_png "$tmp/q2/quilt_qs5x2a1.7778.png"
check "a stretched view size is reported" grep -q "stretched" "$tmp/err"
check "bad --quilt exits 2" run 2 render --quilt 3by3 -o "$tmp/bq"
check "bad --quilt names the option" one_line_naming "--quilt"
check "--size without --quilt exits 2" run 2 render --size 10x10 -o "$tmp/bs"
check "--size without --quilt names the option" one_line_naming "--size"
check "no output after the errors" test ! -e "$tmp/bq" -a ! -e "$tmp/bs"

# interlace a quilt: the same image as render --direct-mapping (same eyes, another code path).
check "interlace a quilt" run 0 interlace "$tmp/q/quilt_qs3x3a1.7778.pfm" "${small[@]}" \
  --linear -o "$tmp/iq"
for f in image.png mask.png display.json render.json image.pfm; do
  check "interlace wrote $f" test -s "$tmp/iq/$f"
done
check "interlace recorded" grep -q '"method": "interlace"' "$tmp/iq/render.json"
check "direct mapping" run 0 render "${small[@]}" --direct-mapping --spp 1 --linear -o "$tmp/dm"
check "interlaced quilt = direct mapping" pfm_close "$tmp/iq/image.pfm" "$tmp/dm/image.pfm"
check "same mask as render" cmp -s "$tmp/iq/mask.png" "$tmp/dm/mask.png"
check "simulate reads the interlace output" run 0 simulate "$tmp/iq" --eye 0,0,600 -o "$tmp/s.png"

# interlace nine views, leftmost camera first: the window from the design eyes, 55.17 mm apart
# (S / 9 = dx (D + g) / g), centred on x = 0.
views=()
for k in 0 1 2 3 4 5 6 7 8; do
  x=$(awk -v k="$k" 'BEGIN { printf "%.6f", (k - 4) * 0.2745 * 603 / 3 }')
  check "view $k" run 0 view "${small[@]}" --display-eye "$x,0,600" --spp 1 -o "$tmp/v$k.pfm"
  views+=("$tmp/v$k.pfm")
done
check "interlace views" run 0 interlace "${views[@]}" "${small[@]}" --linear -o "$tmp/iv"
check "interlaced views = direct mapping" pfm_close "$tmp/iv/image.pfm" "$tmp/dm/image.pfm"
check "views in the wrong order differ" run 0 interlace $(printf '%s\n' "${views[@]}" | tac) \
  "${small[@]}" --linear -o "$tmp/ir"
check "reversed views are not the direct mapping" bash -c "! cmp -s '$tmp/ir/image.pfm' '$tmp/iv/image.pfm'"
small_views=()
for k in 0 1 2 3 4 5 6 7 8; do
  check "small view $k" run 0 view --size 48x27 --spp 1 -o "$tmp/w$k.png"
  small_views+=("$tmp/w$k.png")
done
check "views of another size" run 0 interlace "${small_views[@]}" "${small[@]}" -o "$tmp/iw"
check "resampling is reported" grep -q "resampling.*48x27.*96x54" "$tmp/err"

# Errors: one line, exit 2, nothing written.
# Another count of views is resampled across views, named in the note and the record.
check "eight views are resampled to nine" run 0 interlace "${views[@]:0:8}" "${small[@]}" \
  -o "$tmp/e1"
check "the resampling is noted with the count expected" \
  grep -q "8 views given, the display takes 9 views.*resampled across views (linear)" "$tmp/err"
check "the record names the resampling" grep -q '"view_resampling": "linear"' "$tmp/e1/render.json"
check "nearest resampling" run 0 interlace "${views[@]:0:8}" "${small[@]}" \
  --view-resampling nearest -o "$tmp/e1n"
check "nearest and linear differ" bash -c "! cmp -s '$tmp/e1/image.png' '$tmp/e1n/image.png'"
check "nine views need no resampling" bash -c "! '$bin' interlace ${views[*]} ${small[*]} \
  -o '$tmp/e1x' 2>&1 | grep -q resampled"
check "an unknown resampling exits 2" run 2 interlace "${views[@]}" "${small[@]}" \
  --view-resampling cubic -o "$tmp/e2"
check "an unknown resampling names the option" one_line_naming "--view-resampling"
cp "$tmp/q/quilt_qs3x3a1.7778.png" "$tmp/plain.png"
check "quilt without a layout exits 2" run 2 interlace "$tmp/plain.png" "${small[@]}" -o "$tmp/e3"
check "missing layout names the file" one_line_naming "plain.png: no quilt layout"
cp "$tmp/plain.png" "$tmp/shot_qs3by3a1.png"
check "malformed layout exits 2" run 2 interlace "$tmp/shot_qs3by3a1.png" "${small[@]}" \
  -o "$tmp/e4"
check "malformed layout names the file" one_line_naming "shot_qs3by3a1.png: malformed quilt layout"
# As Looking Glass names quilts: no aspect (its example quilts), or another display's aspect,
# whatever the tiles' shape: read, the views stretched to this display with a note.
cp "$tmp/plain.png" "$tmp/shot_qs3x3.png"
check "a name without an aspect is read" run 0 interlace "$tmp/shot_qs3x3.png" "${small[@]}" \
  -o "$tmp/na"
cp "$tmp/plain.png" "$tmp/other_qs3x3a1.png"
check "another display's aspect is read" run 0 interlace "$tmp/other_qs3x3a1.png" \
  "${small[@]}" -o "$tmp/e5"
check "and noted" grep -q "named for a display of aspect 1, this one's is 1.7778" "$tmp/err"
check "a quilt of ten views is resampled" run 0 interlace "$tmp/q2/quilt_qs5x2a1.7778.png" \
  "${small[@]}" -o "$tmp/e6"
check "the quilt's resampling is noted" grep -q "10 views given, the display takes 9 views" \
  "$tmp/err"
check "--quilt-layout reads an unnamed quilt" run 0 interlace "$tmp/plain.png" "${small[@]}" \
  --quilt-layout 3x3 -o "$tmp/il"
check "interlace the PNG quilt" run 0 interlace "$tmp/q/quilt_qs3x3a1.7778.png" "${small[@]}" \
  -o "$tmp/iqp"
check "--quilt-layout gives the same image" cmp -s "$tmp/il/image.png" "$tmp/iqp/image.png"
check "a name without an aspect gives the same image" cmp -s "$tmp/na/image.png" \
  "$tmp/iqp/image.png"
check "no output after the errors" bash -c "! ls -d '$tmp'/e[234] 2>/dev/null | grep -q ."

cli_summary

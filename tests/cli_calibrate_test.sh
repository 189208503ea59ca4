#!/usr/bin/env bash
# `parallax calibrate` as a user meets it: patterns, prediction, and the display file it writes.
# Usage: cli_calibrate_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"
# json_number KEY: the first number stored under "KEY" in $tmp/out (JsonWriter: one key a line)
json_number() { sed -n "s/^ *\"$1\": \\([-0-9.eE+]*\\),\\{0,1\\}$/\\1/p" "$tmp/out" | head -1; }
# near A B TOLERANCE: |A - B| <= TOLERANCE
near() {
  [ -n "$1" ] && [ -n "$2" ] &&
    awk -v a="$1" -v b="$2" -v t="$3" 'BEGIN { d = a - b; if (d < 0) d = -d; exit !(d <= t) }'
}

cat >"$tmp/back.json" <<'JSON'
{"image_layer": {"resolution": [240, 60], "pixel_pitch_mm": 0.2745}, "gap_mm": 3,
 "view_distance_mm": 600, "views": 9}
JSON
cat >"$tmp/front.json" <<'JSON'
{"image_layer": {"resolution": [240, 60], "pixel_pitch_mm": 0.2745}, "gap_mm": 3,
 "view_distance_mm": 600, "views": 9, "layer_order": "barrier-front"}
JSON

# Patterns: every file at its layer's resolution, listed in index.json.
for order in back front; do
  dir="$tmp/patterns-$order"
  check "patterns ($order)" run 0 calibrate patterns --display "$tmp/$order.json" -o "$dir"
  for f in image-slits image-views image-colours mask-slits mask-period-01 mask-period-09 \
    mask-phase-01; do
    check "$order: $f.png is a PNG" is_png "$dir/$f.png"
    check "$order: $f.png is 240x60" test "$(png_size "$dir/$f.png")" = 240x60
  done
  check "$order: nine periods" test "$(ls "$dir" | grep -c '^mask-period-')" -eq 9
  check "$order: index.json lists every PNG" \
    test "$(grep -c '"file"' "$dir/index.json")" -eq "$(ls "$dir" | grep -c '\.png$')"
  check "$order: README lists the patterns" grep -q "mask-period-05.png" "$dir/README.txt"
done
check "the middle of the sweep is the design's period" \
  grep -qE '^mask-period-05.png +mask +9 +9.0450 ' "$tmp/patterns-back/README.txt"
check "patterns with a narrower sweep" run 0 calibrate patterns --display "$tmp/back.json" \
  --from 9.03 --to 9.05 --steps 5 --phase-step 1 --duty 0.2 -o "$tmp/narrow"
check "five periods" test "$(ls "$tmp/narrow" | grep -c '^mask-period-')" -eq 5
check "last period labelled in the index" grep -q '"label": "TV 9.0500 PH 0.00"' \
  "$tmp/narrow/index.json"
check "a sweep that breaks G1 exits 2" run 2 calibrate patterns --display "$tmp/back.json" \
  --from 8.8 --to 9.1 -o "$tmp/bad-sweep"
check "the error names --from" one_line_naming "--from"
check "nothing written after the error" test ! -e "$tmp/bad-sweep"
check "zero steps exit 2" run 2 calibrate patterns --steps 0 -o "$tmp/zero"
check "the error names --steps" one_line_naming "--steps"

# Prediction against G1: an eye at 800 mm wants Tv = 9 (800 + 3) / 800 for the built-in
# display; tolerance 1 / (2N) + step / 2 with N = 213 groups (calibration_test.cpp).
check "predict --json" run 0 calibrate predict --eye 0,0,800 --json
for key in screen_period_px slit_period_px phase_px distance_over_gap view_distance_mm contrast \
  at_range_edge; do
  check "predict reports $key" grep -q "\"$key\"" "$tmp/out"
done
check "predicted slit period follows G1" near "$(json_number slit_period_px)" 9.03375 0.0025
check "predicted distance is near 800 mm" near "$(json_number view_distance_mm)" 800 60
check "predicted phase is near 0" near "$(json_number phase_px)" 0 0.25
check "predict (text) on a small barrier-front display" run 0 calibrate predict \
  --display "$tmp/front.json"
check "predict prints the slit period" grep -q "slit period Tv" "$tmp/out"
check "eye behind the display exits 2" run 2 calibrate predict --eye 0,0,-5
check "the error names --eye" one_line_naming "--eye"

# Apply: the file round-trips through design to the given periods and D = g / (Tr/Tf - 1).
check "apply" run 0 calibrate apply --screen-period 9 --slit-period 9.0347 --phase 0.25 \
  --gap 2.7 --display "$tmp/back.json" -o "$tmp/cal/back.json"
check "design reads the applied file" run 0 design "$tmp/cal/back.json" --json
check "screen period kept" near "$(json_number screen_period_px)" 9 1e-9
check "slit period kept" near "$(json_number slit_period_px)" 9.0347 1e-9
check "gap kept" near "$(json_number gap_mm)" 2.7 1e-9
check "D = g / (Tv/Tx - 1) (barrier-back)" near "$(json_number view_distance_mm)" \
  "$(awk 'BEGIN { printf "%.10f", 2.7 / (9.0347 / 9 - 1) }')" 1e-6
check "measured phase kept as the panel offset" grep -q '"panel_offset_px": 0.25' "$tmp/cal/back.json"
check "apply (barrier-front)" run 0 calibrate apply --screen-period 9 --slit-period 8.97 \
  --display "$tmp/front.json" -o "$tmp/cal/front.json"
check "design reads it" run 0 design "$tmp/cal/front.json" --json
check "D = g / (Tx/Tv - 1) (barrier-front)" near "$(json_number view_distance_mm)" \
  "$(awk 'BEGIN { printf "%.10f", 3 / (9 / 8.97 - 1) }')" 1e-6
check "render uses the applied file" run 0 render --display "$tmp/cal/back.json" --spp 1 \
  -o "$tmp/render"
check "render wrote the mask" is_png "$tmp/render/mask.png"

check "periods that break G1 exit 2" run 2 calibrate apply --screen-period 9 --slit-period 8.9 \
  -o "$tmp/cal/bad.json"
check "the error names the option" one_line_naming "--slit-period: G1 needs"
check "a slit period beyond a panel exits 2" run 2 calibrate apply --screen-period 9 \
  --slit-period 100000 -o "$tmp/cal/bad.json"
check "the error names the option, not the file key" one_line_naming "--slit-period: must be above 0"
check "a reversed predict range exits 2" run 2 calibrate predict --from 11 --to 10 --json
check "the error names --to" one_line_naming "--to: must not be below --from"
check "a zero gap exits 2" run 2 calibrate apply --screen-period 9 --slit-period 9.04 --gap 0 \
  -o "$tmp/cal/bad.json"
check "the error names the gap" one_line_naming "--gap"
check "no file after the errors" test ! -e "$tmp/cal/bad.json"
check "apply without a slit period exits 2" run 2 calibrate apply --screen-period 9 \
  -o "$tmp/cal/bad.json"

cli_summary

#!/usr/bin/env bash
# The depth budget end to end (docs/display-geometry.md, "Depth budget"): a bare mesh framed by
# default with --fit depth shows sharp at the centre eye, and no worse than the central-ray
# render across the view zone. Usage: cli_depth_test.sh PARALLAX_BINARY SOURCE_DIR
# PARALLAX_SLOW=1 adds the nine eyes (-248,0,600) .. (248,0,600) one by one (about 50 s more).
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

box="$src/data/assimp/glTF2/BoxTextured-glTF/BoxTextured.gltf"
if [ ! -f "$box" ]; then
  # 77: CTest counts the test as skipped (SKIP_RETURN_CODE), not passed.
  echo "skipped: $box is missing (tools/fetch-data)"
  exit 77
fi
at_least() { python3 -c 'import sys; sys.exit(0 if float(sys.argv[1]) >= float(sys.argv[2]) else 1)' "$1" "$2"; }

check "render frames a bare mesh in depth by default" run 0 render "$box" --spp 4 -o "$tmp/depth"
check "render reports the framing" grep -q "depth (fit depth)" "$tmp/out"
check "the framed content does not warn" bash -c "! grep -q 'warning: the content spans' '$tmp/err'"
check "render.json records the framing" grep -q '"fit": "depth"' "$tmp/depth/render.json"
check "render.json records g'" bash -c "grep -q '\"virtual_gap_mm\"' '$tmp/depth/render.json'"
check "the display file carries g'" grep -q '"virtual"' "$tmp/depth/display.json"
check "shown depth within the depth of field" at_least \
  "$(json_at "$tmp/depth/render.json" /framing/depth_budget_mm)" \
  "$(json_at "$tmp/depth/render.json" /framing/shown_near_mm)"
check "the window fit warns with numbers" run 0 render "$box" --spp 1 --fit window -o "$tmp/window"
check "warning names the depth of field" grep -q "the display is sharp within ±27 mm (G4); --fit depth compresses it" "$tmp/err"
check "central-ray render" run 0 render "$box" --filter none -o "$tmp/none"
check "a given budget and focus are recorded" run 0 render "$box" --spp 1 --focus 5 --depth-budget 10 -o "$tmp/given"
check "given focus in render.json" bash -c "[ \"\$(python3 -c 'import json; print(json.load(open(\"$tmp/given/render.json\"))[\"framing\"][\"focus_mm\"])')\" = 5.0 ]"
check "bad --focus" run 2 render "$box" --focus near -o "$tmp/bad"
check "bad --focus: one line" one_line_naming "--focus"
check "bad --depth-budget" run 2 render "$box" --depth-budget 0 -o "$tmp/bad"
check "bad --fit" run 2 render "$box" --fit wide -o "$tmp/bad"
check "info prints the depth range" run 0 info "$box"
check "info: depth line" grep -q "^depth (fit depth)" "$tmp/out"
check "design --scene warns for the window fit" run 0 design --scene "$box" --fit window
check "design: warning" grep -q "warning: the content spans" "$tmp/out"
check "view --display-eye frames the same way" run 0 view "$box" --display-eye 0,0,600 --size 96x54 --spp 1 -o "$tmp/eye.png"

# The centre eye against the ideal view from (0, 0, 600): at least 28 dB.
check "simulate the centre eye" run 0 simulate "$tmp/depth" --reference --eye 0,0,600 --json --reference-spp 4
cp "$tmp/out" "$tmp/centre.json"
check "centre eye at least 28 dB" at_least "$(json_at "$tmp/centre.json" /mean/psnr)" 28
check "simulate the window fit's centre eye" run 0 simulate "$tmp/window" --reference --eye 0,0,600 --json --reference-spp 4
check "the depth fit beats the window fit" at_least "$(json_at "$tmp/centre.json" /mean/psnr)" "$(json_at "$tmp/out" /mean/psnr)"

# No worse than the central ray: one eye in every view at D (the quick dense measure), both
# renders against the same ideal views.
check "dense measure, both renders" run 0 simulate "$tmp/depth" --reference --eyes-per-view 1 --distances 1 --compare "$tmp/none" --json --reference-spp 4
cp "$tmp/out" "$tmp/dense.json"
check "dense mean no worse than --filter none" at_least \
  "$(json_at "$tmp/dense.json" /renders/0/mean/psnr)" "$(json_at "$tmp/dense.json" /renders/1/mean/psnr)"
check "dense worst eye no worse than --filter none" at_least \
  "$(json_at "$tmp/dense.json" /renders/0/mean/worst_psnr)" "$(json_at "$tmp/dense.json" /renders/1/mean/worst_psnr)"

if [ "${PARALLAX_SLOW:-0}" = 1 ]; then
  eyes=()
  for i in 0 1 2 3 4 5 6 7 8; do eyes+=(--eye "$((-248 + 62 * i)),0,600"); done
  check "nine eyes, depth" run 0 simulate "$tmp/depth" --reference "${eyes[@]}" --json --reference-spp 4
  cp "$tmp/out" "$tmp/nine-depth.json"
  check "nine eyes, none" run 0 simulate "$tmp/none" --reference "${eyes[@]}" --json --reference-spp 4
  check "nine eyes: no worse than --filter none" at_least \
    "$(json_at "$tmp/nine-depth.json" /mean/psnr)" "$(json_at "$tmp/out" /mean/psnr)"
fi
cli_summary

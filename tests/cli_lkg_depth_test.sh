#!/usr/bin/env bash
# Depth and focus on Looking Glass panels (docs/lenticular.md, "Depth of field"): the options that
# were refused for lenticular displays (--fit, --focus, --depth-budget, design --scene) work on
# lkg:portrait, lkg:16-gen3 and a visual.json; a glTF is fitted into the lens's depth of field by
# default; the window fit warns; simulate --reference judges the scaled render; an RGB-D photo of
# the panel's aspect fills the framebuffer. Usage: cli_lkg_depth_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

box="$src/data/assimp/glTF2/BoxTextured-glTF/BoxTextured.gltf"
if [ ! -f "$box" ]; then
  # 77: CTest counts the test as skipped (SKIP_RETURN_CODE), not passed.
  echo "skipped: $box is missing (tools/fetch-data)"
  exit 77
fi
true_that() { python3 -c "import sys; sys.exit(0 if ($1) else 1)"; }

# The lens's depth of field: 12.8 mm on a Portrait (by hand in docs/lenticular.md), 11.8 on a 16".
check "design prints the lens's depth of field" run 0 design lkg:portrait
check "+-12.8 mm on a Portrait" grep -q "depth of field       +-12.8 mm around the panel" "$tmp/out"
check "design --scene on a Portrait" run 0 design lkg:portrait --scene "$box" --json
cp "$tmp/out" "$tmp/design.json"
check "the depth fit by default" test "$(json_at "$tmp/design.json" /scene/fit)" = depth
check "within the budget" test "$(json_at "$tmp/design.json" /scene/within_budget)" = True
check "the shown depth lies within +-the depth of field" true_that \
  "max($(json_at "$tmp/design.json" /scene/shown_near_mm), -($(json_at "$tmp/design.json" /scene/shown_far_mm))) <= 1.005 * $(json_at "$tmp/design.json" /scene/depth_of_field_mm)"
check "the box is deeper than that, so it is scaled" true_that \
  "$(json_at "$tmp/design.json" /scene/depth_scale) < 0.5"
check "a glTF on a 16-inch: framed by default" run 0 design lkg:16-gen3 --scene "$box" --json
check "within its +-11.8 mm" test "$(json_at "$tmp/out" /scene/within_budget)" = True
check "the 16-inch's lens depth of field" true_that "abs($(json_at "$tmp/out" /depth_of_field_mm) - 11.8) < 0.05"
check "the window fit on a 16-inch warns" run 0 design lkg:16-gen3 --scene "$box" --fit window
check "the warning's words and figures" grep -q \
  "warning: the content spans -81 to +81 mm; the display is sharp within ±12 mm (the lens's depth of field); --fit depth compresses it" "$tmp/out"
check "focus and budget on a 16-inch" run 0 design lkg:16-gen3 --scene "$box" --focus 10 --depth-budget 20 --json
check "the given focus" test "$(json_at "$tmp/out" /scene/focus_mm)" = 10.0
check "the given budget bounds the deeper side" true_that \
  "abs(max($(json_at "$tmp/out" /scene/shown_near_mm), -($(json_at "$tmp/out" /scene/shown_far_mm))) - 20) < 1e-6"
check "framing needs a scene" run 2 design lkg:portrait --fit depth
check "bad --focus on a lenticular panel" run 2 render "$box" --display lkg:portrait --focus near -o "$tmp/bad"
check "named in one line" one_line_naming "--focus"

# A render on the Portrait: framed by default, recorded, no warning; its own visual.json frames
# the same way; simulate --reference looks from the intended eyes.
check "render a glTF on a Portrait" run 0 render "$box" --display lkg:portrait --spp 1 --filter none -o "$tmp/p"
check "render reports the framing" grep -q "depth (fit depth)" "$tmp/out"
check "and does not warn" bash -c "! grep -q 'warning: the content spans' '$tmp/err'"
check "render.json records the depth scale" true_that \
  "0 < $(json_at "$tmp/p/render.json" /framing/depth_scale) < 0.5"
check "the calibration written is the device's" run 0 design "$tmp/p/visual.json" --scene "$box" --json
check "its visual.json frames alike" test "$(json_at "$tmp/out" /scene/depth_scale)" = \
  "$(json_at "$tmp/p/render.json" /framing/depth_scale)"
check "simulate --reference from the centre eye" run 0 simulate "$tmp/p" --reference --eye 0,0,1374 \
  --reference-spp 1 -o "$tmp/p-seen.png"
check "a PSNR figure" grep -q "dB" "$tmp/out"
check "render with focus and budget" run 0 render "$box" --display lkg:portrait --spp 1 --filter none \
  --focus -20 --depth-budget 25 -o "$tmp/pf"
check "the focus recorded" test "$(json_at "$tmp/pf/render.json" /framing/focus)" = -20.0
check "the budget recorded" test "$(json_at "$tmp/pf/render.json" /framing/depth_budget)" = 25.0

# An RGB-D photo with the Portrait's aspect (3:4) covers the panel: no black border column or row
# in the framebuffer (every colour of the photo is at least 60/255).
write_png "$tmp/photo.png" 96 128 bright
write_png "$tmp/depth.png" 96 128 depth16
check "render a 3:4 photo on the Portrait" run 0 render --rgbd "$tmp/photo.png" "$tmp/depth.png" \
  --display lkg:portrait --spp 1 --filter none --linear -o "$tmp/rgbd"
check "its depth fitted" grep -q "depth (fit depth)" "$tmp/out"
border_black() {  # the black pixels of the border rows and columns of a PFM
  python3 - "$1" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
parts = data.split(b"\n", 3)
w, h = map(int, parts[1].split())
fmt = "<" if float(parts[2]) < 0 else ">"
px = struct.unpack(fmt + "%df" % (w * h * 3), parts[3][: w * h * 12])
at = lambda x, y: px[((h - 1 - y) * w + x) * 3:((h - 1 - y) * w + x) * 3 + 3]
border = [(x, 0) for x in range(w)] + [(x, h - 1) for x in range(w)] + \
         [(0, y) for y in range(h)] + [(w - 1, y) for y in range(h)]
print(sum(max(at(x, y)) < 1e-3 for x, y in border))
PY
}
check "no black pixel on the framebuffer's border" test "$(border_black "$tmp/rgbd/image.pfm")" = 0
check "--fit window keeps the whole photo inside, with bands" run 0 render --rgbd "$tmp/photo.png" \
  "$tmp/depth.png" --display lkg:portrait --spp 1 --filter none --linear --fit window -o "$tmp/rgbdw"
check "bands on the border then" true_that "$(border_black "$tmp/rgbdw/image.pfm") > 1000"

cli_summary

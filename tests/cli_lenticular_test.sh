#!/usr/bin/env bash
# `parallax lenticular` as a user meets it. Usage: cli_lenticular_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

# A small device-style calibration: every field {"value": n}.
cp "$src/tests/fixtures/displays/small-lenticular-96x128.json" "$tmp/small.json"

check "lenticular without a subcommand exits 2" run 2 lenticular
check "render" run 0 lenticular render "$tmp/small.json" -o "$tmp/r"
check "render wrote image.png" is_png "$tmp/r/image.png"
check "image has the panel's size" test "$(png_size "$tmp/r/image.png")" = "96x128"
check "render wrote render.json" grep -q '"pitch_px"' "$tmp/r/render.json"
check "render.json has the view distance" grep -q '"view_distance_mm"' "$tmp/r/render.json"
check "render wrote the calibration beside it" grep -q '"value"' "$tmp/r/visual.json"
check "render left no temporary files" bash -c "! ls '$tmp/r' | grep -q tmp"
check "render a scene file with spp 4" run 0 lenticular render "$tmp/small.json" \
  "$src/scenes/spheres.json" --spp 4 -o "$tmp/r4"
check "the default is 16 rays over each subpixel's view window" \
  bash -c "grep -q '\"spp\": 16' '$tmp/r/render.json' && grep -q '\"kind\": \"view\"' '$tmp/r/render.json'"
check "render --filter none" run 0 lenticular render "$tmp/small.json" --filter none -o "$tmp/rn"
check "--filter none casts one ray per subpixel" grep -q '"spp": 1,' "$tmp/rn/render.json"
check "render --filter tent --filter-width 2" run 0 lenticular render "$tmp/small.json" \
  --filter tent --filter-width 2 --spp 4 -o "$tmp/rt"
check "render.json records the filter's width" grep -q '"width_views": 2' "$tmp/rt/render.json"
check "an unknown --filter exits 2" run 2 lenticular render "$tmp/small.json" --filter box -o "$tmp/bad0"
check "an unknown --filter names the option" one_line_naming "--filter"
check "a refused filter writes nothing" test ! -e "$tmp/bad0"

check "simulate DIR" run 0 lenticular simulate "$tmp/r" --eye 0,0,1374 -o "$tmp/v.png"
check "simulated view has the panel's size" test "$(png_size "$tmp/v.png")" = "96x128"
check "simulate DIR CALIBRATION" run 0 lenticular simulate "$tmp/r" "$tmp/small.json" -o "$tmp/v2.png"
check "simulate --image" run 0 lenticular simulate --image "$tmp/r/image.png" "$tmp/small.json" \
  --eye 300,50,1000 -o "$tmp/v3.png"
check "simulate --image wrote a PNG" is_png "$tmp/v3.png"
check "every example calibration loads (up to the panel size check)" bash -c "for f in '$src'/displays/lenticular/*.json; do
  '$bin' lenticular simulate --image '$tmp/r/image.png' \"\$f\" -o '$tmp/x.png' 2>&1 |
  grep -q '/screenW' || exit 1; done"

# Bad input: one line naming the file and key, exit 2, no output.
sed 's/"slope": {"value": -6.2}, //' "$tmp/small.json" >"$tmp/noslope.json"
check "missing field exits 2" run 2 lenticular render "$tmp/noslope.json" -o "$tmp/bad1"
check "missing field names the key" one_line_naming "noslope.json: /slope: missing"
check "failed render writes nothing" test ! -e "$tmp/bad1"
sed 's/"serial"/"serail"/' "$tmp/small.json" >"$tmp/typo.json"
check "an unknown field (newer firmware) is read" run 0 lenticular render "$tmp/typo.json" \
  --spp 1 -o "$tmp/typo"
check "an unknown field is one warning naming the key" \
  bash -c "grep -c 'warning: .*typo.json: /serail: unknown key, ignored' '$tmp/err' | grep -qx 1"
sed 's/"invView": {"value": 1}, //' "$tmp/small.json" >"$tmp/noinv.json"
check "a calibration without invView is read" run 0 lenticular render "$tmp/noinv.json" \
  --spp 1 -o "$tmp/noinv"
check "the defaulted invView is a warning" grep -q "noinv.json: /invView: missing, taken as 1" \
  "$tmp/err"
check "the same picture as invView 1" cmp "$tmp/noinv/image.png" "$tmp/typo/image.png"
printf '{"pitch": 13.7, "slope": -6.2, "center": 0.4, "viewCone": 40, "invView": 1, "DPI": 81,
 "screenW": 96, "screenH": 128}' >"$tmp/plain.json"
check "plain numbers are accepted" run 0 lenticular simulate "$tmp/r" "$tmp/plain.json" -o "$tmp/p.png"
check "missing calibration exits 2" run 2 lenticular render "$tmp/nope.json" -o "$tmp/bad3"
check "missing calibration names the file" one_line_naming "nope.json"
check "wrong panel size exits 2" run 2 lenticular simulate --image "$tmp/r/image.png" \
  "$src/displays/lenticular/portrait-like.json" -o "$tmp/bad4.png"
check "wrong panel size names the key" one_line_naming "/screenW"
check "no view after the error" test ! -e "$tmp/bad4.png"
check "eye behind the panel exits 2" run 2 lenticular simulate "$tmp/r" --eye 0,0,-5 -o "$tmp/b.png"
check "eye behind the panel names the option" one_line_naming "--eye"
check "bad spp exits 2" run 2 lenticular render "$tmp/small.json" --spp 0 -o "$tmp/bad5"
check "simulate without inputs exits 2" run 2 lenticular simulate -o "$tmp/n.png"

# ---- One display, every kind: the general commands take calibrations and presets ----
check "render --display visual.json" run 0 render --display "$tmp/small.json" --spp 1 -o "$tmp/g"
check "render and lenticular render make the same picture" bash -c "'$bin' lenticular render \
  '$tmp/small.json' --spp 1 -o '$tmp/g2' >/dev/null 2>&1 && cmp '$tmp/g/image.png' '$tmp/g2/image.png'"
check "render writes the calibration, not a barrier display" \
  test -e "$tmp/g/visual.json" -a ! -e "$tmp/g/display.json"
check "simulate DIR reads visual.json" run 0 simulate "$tmp/g" -o "$tmp/gs.png"
check "simulate of a lenticular has the panel's size" test "$(png_size "$tmp/gs.png")" = "96x128"
check "simulate --sweep of a lenticular" run 0 simulate "$tmp/g" --sweep 3 -o "$tmp/gsweep"
check "the sweep wrote its page" test -s "$tmp/gsweep.html"
check "simulate --reference of a lenticular" run 0 simulate "$tmp/g" --reference \
  --eyes-per-view 1 --distances 1 --reference-spp 1 --json
check "the dense measure counts the quilt's views" grep -q '"eyes": 48' "$tmp/out"
check "a barrier-only option is refused for a lenticular" run 2 simulate "$tmp/g" --pupil 3
check "the refusal names the option" one_line_naming "--pupil"
check "render --subpixels is refused for a lenticular" run 2 render --display "$tmp/small.json" \
  --subpixels -o "$tmp/bad5"
check "a preset renders" run 0 render --display lkg:portrait --spp 1 -o "$tmp/preset"
check "the preset has the Portrait's panel" test "$(png_size "$tmp/preset/image.png")" = "1536x2048"
check "an unknown preset exits 2" run 2 render --display lkg:nonesuch -o "$tmp/bad6"
check "an unknown preset lists the presets" \
  one_line_naming "lkg:nonesuch: no such Looking Glass preset; the presets are portrait, go"
check "render --quilt auto uses the device's quilt" run 0 render --display lkg:portrait \
  --quilt auto --size 42x56 --spp 1 -o "$tmp/q"
check "the quilt is named for the device's 8x6 views" test -e "$tmp/q/quilt_qs8x6a0.75.png"
# A 16" Gen3 owner's own visual.json (its serial and measured figures): that device's quilt,
# 7x7, named for the panel's 16:9 whatever its tiles' shape, as Looking Glass names it.
cat >"$tmp/gen3.json" <<'JSON'
{"configVersion": "3.0", "serial": "LKG-J00332", "pitch": {"value": 44.61},
 "slope": {"value": -6.93}, "center": {"value": 0.137}, "viewCone": {"value": 50},
 "invView": {"value": 1}, "DPI": {"value": 283}, "screenW": {"value": 3840},
 "screenH": {"value": 2160}, "flipImageX": {"value": 0}, "flipImageY": {"value": 0},
 "flipSubp": {"value": 0}, "CellPatternMode": {"value": 2},
 "subpixelCells": [
   {"ROffsetX": -0.31, "ROffsetY": 0.25, "GOffsetX": 0.28, "GOffsetY": 0.25, "BOffsetX": 0,
    "BOffsetY": -0.25},
   {"ROffsetX": -0.31, "ROffsetY": -0.25, "GOffsetX": 0.28, "GOffsetY": -0.25, "BOffsetX": 0,
    "BOffsetY": 0.25}]}
JSON
check "a 16\" Gen3's own file, --quilt auto" run 0 render --display "$tmp/gen3.json" \
  --quilt auto --size 16x9 --spp 1 -o "$tmp/q3"
check "is recognised by its serial" grep -qF "(lkg:16-gen3, by its serial LKG-J00332)" "$tmp/err"
check "its quilt is the device's 7x7, a1.7778" test -e "$tmp/q3/quilt_qs7x7a1.7778.png"
check "render.json names the device" grep -qF '"device": "lkg:16-gen3"' "$tmp/q3/render.json"
check "the copy beside it keeps the serial" grep -qF '"serial": "LKG-J00332"' "$tmp/q3/visual.json"
check "a Looking Glass quilt name is read" run 0 interlace "$tmp/q3/quilt_qs7x7a1.7778.png" \
  --display "$tmp/gen3.json" -o "$tmp/iq3"
check "an unknown panel's quilt" run 0 render --display "$tmp/small.json" --quilt auto \
  --size 12x16 --spp 1 -o "$tmp/qd"
check "is derived from the panel, said" grep -qF \
  "is no Looking Glass device parallax knows: its default quilt is derived from the panel, 8x6" \
  "$tmp/err"
check "view --display-eye with a calibration" run 0 view --display "$tmp/small.json" \
  --display-eye 0,0,1374 --spp 1 -o "$tmp/ideal.png"
check "the ideal view has the panel's size" test "$(png_size "$tmp/ideal.png")" = "96x128"
check "bench --camera display with a calibration" run 0 bench --camera display \
  --display "$tmp/small.json" --spp 1 --repeats 1 --json
check "bench measures the panel's subpixel film" grep -q '"width": 288' "$tmp/out"
check "bench times the panel's own quilt route, its ratios from its times" python3 -c '
import json, sys
q = json.load(open(sys.argv[1]))["quilt_route"]
assert q["views"] == 48, q
assert min(q["direct_seconds"], q["quilt_seconds"], q["interlace_seconds"]) > 0, q
assert abs(q["direct_over_quilt"] - q["direct_seconds"] / q["quilt_seconds"]) < 1e-9, q
route = q["quilt_seconds"] + q["interlace_seconds"]
assert abs(q["direct_over_quilt_and_interlace"] - q["direct_seconds"] / route) < 1e-9, q
assert q["direct_rays"] > 0 and q["quilt_rays"] > 0, q
' "$tmp/out"
check "bench says the quilt route's ratios" run 0 bench --camera display \
  --display "$tmp/small.json" --spp 1 --repeats 1
check "in its own line" grep -q '^quilt route  direct' "$tmp/out"
check "interlace a quilt onto the panel" run 0 interlace "$tmp/q/quilt_qs8x6a0.75.png" \
  --display lkg:portrait -o "$tmp/iq"
check "the interlaced panel has the Portrait's size" \
  test "$(png_size "$tmp/iq/image.png")" = "1536x2048"
check "the interlaced panel carries its calibration" grep -q '"value"' "$tmp/iq/visual.json"
check "interlace --view-resampling nearest onto the panel" run 0 interlace \
  "$tmp/q/quilt_qs8x6a0.75.png" --display lkg:portrait --view-resampling nearest -o "$tmp/iqn"
check "nearest is not the linear blend" bash -c "! cmp -s '$tmp/iq/image.png' '$tmp/iqn/image.png'"
check "the record says nearest" grep -q '"view_resampling": "nearest"' "$tmp/iqn/render.json"
check "--filter none with --spp 4 says what it does" run 0 lenticular render "$tmp/small.json" \
  --filter none --spp 4 -o "$tmp/rn4"
check "the note names both options" grep -qF \
  "note: --filter none casts each film pixel's central ray only" "$tmp/err"
check "and what --spp 4 does" grep -qF "so --spp 4 renders as 1 sample a pixel" "$tmp/err"
# The lens optics (docs/lenticular.md, "The optics"): stated, and readable other ways.
check "render.json states the optics it rendered for" \
  bash -c "grep -q '\"bundles\": \"converging\"' '$tmp/r/render.json' &&
           grep -q '\"lens_spot_subpixels\": 1' '$tmp/r/render.json'"
check "simulate under another reading" run 0 simulate "$tmp/r" --lens-spot 0 --bundles parallel \
  -o "$tmp/ideal-lens.png"
check "simulate says the reading it used" \
  grep -q "0-subpixel focal spot, bundles parallel" "$tmp/err"
check "lenticular simulate takes the readings too" run 0 lenticular simulate "$tmp/r" \
  --lens-spot 3 --bundles converging -o "$tmp/pixel-spot.png"
check "the two readings see the panel differently" bash -c "! cmp -s '$tmp/ideal-lens.png' '$tmp/pixel-spot.png'"
check "an unknown --bundles exits 2" run 2 simulate "$tmp/r" --bundles sideways -o "$tmp/bad1.png"
check "an unknown --bundles names the option" one_line_naming "--bundles"
check "a spot past 12 subpixels exits 2" run 2 simulate "$tmp/r" --lens-spot 20 -o "$tmp/bad2.png"
check "--all-readings needs the dense measure" run 2 simulate "$tmp/r" --all-readings \
  -o "$tmp/bad3.png"
check "--all-readings names itself" one_line_naming "--all-readings"
check "the dense measure under every reading" run 0 simulate "$tmp/r" --reference --all-readings \
  --eyes-per-view 1 --distances 1 --reference-spp 1 --json
check "one row per reading, the display's own last" bash -c "
  python3 -c 'import json,sys; r=json.load(open(sys.argv[1]))[\"renders\"];
assert len(r)==5, r; assert \"spot 0, parallel\" in r[0][\"dir\"]; assert \"display\" in r[4][\"dir\"]' '$tmp/out'"

# A render made for another reading of the optics (the same options as simulate's).
check "render --lens-spot 0 --bundles parallel" run 0 lenticular render "$tmp/small.json" \
  --lens-spot 0 --bundles parallel -o "$tmp/r-ideal"
check "its render.json states the optics it was made for" \
  bash -c "grep -q '\"bundles\": \"parallel\"' '$tmp/r-ideal/render.json' &&
           grep -q '\"lens_spot_subpixels\": 0' '$tmp/r-ideal/render.json'"
check "a render for another spot is another picture" \
  bash -c "! cmp -s '$tmp/r/image.png' '$tmp/r-ideal/image.png'"
check "render --display takes them too" run 0 render --display "$tmp/small.json" --spp 1 \
  --lens-spot 3 -o "$tmp/r-spot3"
check "and states the spot" grep -q '"lens_spot_subpixels": 3' "$tmp/r-spot3/render.json"
# A quilt's cameras stand on the design line whatever the optics (interlace maps by them).
check "a quilt for parallel bundles" run 0 render --display "$tmp/small.json" --spp 1 \
  --quilt 4x2 --size 24x32 --bundles parallel -o "$tmp/q-par"
check "a quilt for converging bundles" run 0 render --display "$tmp/small.json" --spp 1 \
  --quilt 4x2 --size 24x32 --bundles converging -o "$tmp/q-conv"
check "the same cameras, the same quilt" \
  cmp "$tmp/q-par/quilt_qs4x2a0.75.png" "$tmp/q-conv/quilt_qs4x2a0.75.png"
check "interlace for parallel bundles" run 0 interlace "$tmp/q-par/quilt_qs4x2a0.75.png" \
  --display "$tmp/small.json" --bundles parallel -o "$tmp/qi-par"
check "interlace for converging bundles" run 0 interlace "$tmp/q-par/quilt_qs4x2a0.75.png" \
  --display "$tmp/small.json" --bundles converging -o "$tmp/qi-conv"
check "each subpixel takes the views its light reaches: other pictures" \
  bash -c "! cmp -s '$tmp/qi-par/image.png' '$tmp/qi-conv/image.png'"
check "the interlaced record states the optics" \
  grep -q '"bundles": "parallel"' "$tmp/qi-par/render.json"
check "interlace --bundles on a barrier exits 2" run 2 interlace "$tmp/q-par/quilt_qs4x2a0.75.png" \
  --bundles parallel -o "$tmp/bad-qi"
check "and names the option" one_line_naming "--bundles"
check "--lens-spot on a barrier exits 2" run 2 render --spp 1 --lens-spot 1 -o "$tmp/bad-barrier"
check "and names the option" one_line_naming "--lens-spot"
check "nothing written for it" test ! -e "$tmp/bad-barrier"

check "design reads a calibration" run 0 design "$tmp/small.json"
check "design prints the lens figures" grep -q 'pixels per lens' "$tmp/out"
check "design of a unit's file" run 0 design "$tmp/gen3.json"
check "names its device" grep -qF "device               lkg:16-gen3, by its serial LKG-J00332" \
  "$tmp/out"

cli_summary

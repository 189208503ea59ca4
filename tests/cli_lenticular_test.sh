#!/usr/bin/env bash
# `parallax lenticular` as a user meets it. Usage: cli_lenticular_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

# A small device-style calibration: every field {"value": n}.
cat >"$tmp/small.json" <<'JSON'
{"serial": "TEST", "pitch": {"value": 13.7}, "slope": {"value": -6.2}, "center": {"value": 0.4},
 "viewCone": {"value": 40}, "invView": {"value": 1}, "DPI": {"value": 81},
 "screenW": {"value": 96}, "screenH": {"value": 128}, "flipImageX": {"value": 0},
 "flipImageY": {"value": 0}, "flipSubp": {"value": 0}}
JSON

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
check "unknown field exits 2" run 2 lenticular render "$tmp/typo.json" -o "$tmp/bad2"
check "unknown field names the key" one_line_naming "typo.json: /serail: unknown key"
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

cli_summary

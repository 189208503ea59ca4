#!/usr/bin/env bash
# The command line as a user meets it. Usage: cli_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

check "help" run 0 --help
check "view renders the built-in scene" run 0 view --size 64x36 --spp 1 -o "$tmp/v.png"
check "view wrote a PNG" is_png "$tmp/v.png"
check "view reports where it wrote" grep -qF "$tmp/v.png" "$tmp/out"
check "pfm output" run 0 view --size 8x8 --spp 1 -o "$tmp/v.pfm"
check "pfm header" bash -c "head -c 2 '$tmp/v.pfm' | grep -q PF"

cp "$tmp/v.png" "$tmp/keep.png"
check "missing scene exits 2" run 2 view "$tmp/nope.json" -o "$tmp/keep.png"
check "missing scene: one line naming the file" one_line_naming "nope.json"
check "failed run leaves the old output untouched" cmp -s "$tmp/v.png" "$tmp/keep.png"
printf '{"objects": [ {"shape": "sphere", "radius": 1' >"$tmp/trunc.json"
check "truncated JSON exits 2" run 2 view "$tmp/trunc.json" -o "$tmp/t.png"
check "truncated JSON: one line naming the file" one_line_naming "trunc.json"
check "truncated JSON: no output" test ! -e "$tmp/t.png"
printf '{"objects": [{"shape": "sphere", "radius": 1, "colr": [1,0,0]}]}' >"$tmp/key.json"
check "unknown key exits 2" run 2 info "$tmp/key.json"
check "unknown key names its JSON path" one_line_naming "/objects/0/colr"
check "bad size exits 2" run 2 view --size 10by10 -o "$tmp/s.png"
check "bad size names the option" one_line_naming "--size"
check "bad eye exits 2" run 2 view --eye 1,2 -o "$tmp/e.png"
check "unknown option exits 2" run 2 view --no-such-option
check "no output file after errors" bash -c "! ls '$tmp' | grep -q -E '^(s|e)\.png|\.tmp'"

check "info --json" run 0 info --json
check "info --json has triangles and bounds" \
  bash -c "grep -q '\"triangles\": 16' '$tmp/out' && grep -q '\"min\"' '$tmp/out'"
check "info on an example scene" run 0 info "$src/scenes/spheres.json"
check "bench --json" run 0 bench --size 64x64 --spp 4 --repeats 1 --json
for key in rays_per_second limit_rays_per_second ratio peak_rss_mb same_rays_limit_rays_per_second \
  same_rays_ratio ray_order_ratio; do
  check "bench reports $key" grep -q "\"$key\"" "$tmp/out"
done
# The end-to-end phases add up to the total, the wall ratio is the total over the render loop,
# every rate's miss fraction is a fraction, and Embree alone traced the same-rays loop's rays.
check "bench phases and counts add up" python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
names = ["load", "bvh", "render", "encode", "write"]
phases = d["phases"]
assert all(n in phases for n in names), phases
total = sum(phases[n]["seconds"] for n in names)
assert abs(total - phases["total_seconds"]) < 1e-9, (total, phases["total_seconds"])
assert abs(d["wall_ratio"] - total / phases["render"]["seconds"]) < 1e-9
assert all(phases[n]["peak_rss_mb"] <= d["peak_rss_mb"] for n in names)
for key in ["", "limit_", "same_rays_limit_", "embree_alone_", "embree_on_ours_"]:
    assert 0 <= d[key + "miss_fraction"] <= 1, key
assert d["embree_alone_rays"] == d["same_rays_limit_rays"]
# Embree on our rays traced every ray the render loop traced.
assert d["embree_on_ours_rays"] == d["rays"], (d["embree_on_ours_rays"], d["rays"])
assert d["shading_over_embree"] >= 0 and d["traced_rays_ratio"] > 0
assert d["packet_width"] in (4, 8, 16) and d["bvh_quality"] in ("medium", "high")
assert abs(d["ray_order_ratio"] * d["same_rays_ratio"] - d["ratio"]) < 1e-9
' "$tmp/out"
check "bench --packet-width 8 --bvh-quality medium" run 0 bench --size 32x32 --spp 1 --repeats 1 \
  --packet-width 8 --bvh-quality medium --json
check "bench used 8-ray packets and a medium BVH" python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert d["packet_width"] == 8 and d["bvh_quality"] == "medium", d
' "$tmp/out"
check "bench --packet-width 12 exits 2" run 2 bench --packet-width 12
check "bench --bvh-quality best exits 2" run 2 bench --bvh-quality best

# The display: design, render, and the window view.
check "design" run 0 design
check "design prints the slit period" grep -q "9.045" "$tmp/out"
check "design --json" run 0 design --json
for key in screen_period_mm screen_period_px slit_period_mm slit_period_px views apertures \
  view_zone_width_mm view_distance_mm gap_mm depth_of_field_mm; do
  check "design reports $key" grep -q "\"$key\"" "$tmp/out"
done
printf '{"gap_mm": 0}' >"$tmp/zero-gap.json"
check "impossible display exits 2" run 2 design "$tmp/zero-gap.json"
check "impossible display names the key" one_line_naming "zero-gap.json: /gap_mm"
printf '{"screen_period_px": 9, "slit_period_px": 8.5}' >"$tmp/g1.json"
check "broken G1 exits 2" run 2 render --display "$tmp/g1.json" -o "$tmp/g1out"
check "broken G1 names the relation" one_line_naming "/slit_period_px"
check "failed render writes nothing" test ! -e "$tmp/g1out"
cat >"$tmp/small.json" <<'JSON'
{"image_layer": {"resolution": [96, 54], "pixel_pitch_mm": 0.2745, "subpixels": "RGB"},
 "gap_mm": 3, "view_distance_mm": 600, "views": 9,
 "mask": {"type": "slanted", "angle_deg": 10, "duty_cycle": 0.15}}
JSON
check "render a small display" run 0 render --display "$tmp/small.json" --spp 4 -o "$tmp/r" --linear
check "render wrote image.png" is_png "$tmp/r/image.png"
check "render wrote mask.png" is_png "$tmp/r/mask.png"
check "render wrote render.json" grep -q '"rays_per_second"' "$tmp/r/render.json"
check "render wrote image.pfm" test -s "$tmp/r/image.pfm"
check "render left no temporary files" bash -c "! ls '$tmp/r' | grep -q tmp"
check "render records the jitter" grep -q '"jitter": "auto"' "$tmp/r/render.json"
check "render --jitter pixel" run 0 render --display "$tmp/small.json" --spp 4 --jitter pixel \
  -o "$tmp/rp"
check "independent jitter is another image" bash -c "! cmp -s '$tmp/r/image.png' '$tmp/rp/image.png'"
check "unknown --jitter exits 2" run 2 render --display "$tmp/small.json" --jitter some -o "$tmp/rj"
check "unknown --jitter names the option" one_line_naming "--jitter"
check "no output after a bad --jitter" test ! -e "$tmp/rj"
check "render --subpixels" run 0 render --display "$tmp/small.json" --spp 1 --subpixels -o "$tmp/rs"
check "view --display-eye" run 0 view --display "$tmp/small.json" --display-eye 0,0,600 -o "$tmp/w.png"
check "window view has the front layer's size" grep -q "96x54" "$tmp/out"
check "eye behind the display exits 2" run 2 view --display-eye 0,0,-5 -o "$tmp/w2.png"
check "bench --camera display" run 0 bench --camera display --display "$tmp/small.json" --spp 1 \
  --repeats 1 --json
check "bench --camera display reports the views' limit of its views" python3 -c '
import json, subprocess, sys
b = json.load(open(sys.argv[1]))
d = json.loads(subprocess.run([sys.argv[2], "design", sys.argv[3], "--json"], check=True,
                              capture_output=True, text=True).stdout)
views = round(d["views"])
assert b["views_limit_views"] == views, (b["views_limit_views"], views)
assert b["views_limit_width"] == round(b["width"] / views), b["views_limit_width"]
assert abs(b["views_ratio"] - b["rays_per_second"] / b["views_limit_rays_per_second"]) < 1e-9
' "$tmp/out" "$bin" "$tmp/small.json"

check "lightfield" run 0 lightfield --from -2 --to 2 --spp 4 -o "$tmp/lf.svg"
check "lightfield wrote an SVG" grep -q "</svg>" "$tmp/lf.svg"
check "lightfield with a bad spp exits 2" run 2 lightfield --spp 3 -o "$tmp/lf2.svg"
check "no SVG after the error" test ! -e "$tmp/lf2.svg"
check "render --direct-mapping" run 0 render --display "$tmp/small.json" --spp 1 --direct-mapping \
  -o "$tmp/dm"
check "direct mapping is recorded" grep -q '"direct-mapping"' "$tmp/dm/render.json"

# Seeing the display: simulate the small render from above.
check "simulate one eye" run 0 simulate "$tmp/r" --eye 0,0,600 -o "$tmp/s.png"
check "simulate wrote a PNG" is_png "$tmp/s.png"
check "simulate two eyes" run 0 simulate "$tmp/r" --eye -30,0,600 --eye 30,0,600 -o "$tmp/two.png"
check "two eyes, two files" test -s "$tmp/two-0.png" -a -s "$tmp/two-1.png"
check "simulate a sweep" run 0 simulate "$tmp/r" --sweep 3 -o "$tmp/sweep"
check "sweep contact sheet" is_png "$tmp/sweep-sheet.png"
check "sweep animation" is_png "$tmp/sweep-anim.png"
check "sweep page" grep -q 'id="slider"' "$tmp/sweep.html"
check "sweep page's title names the display file, not its path" \
  grep -q '<title>parallax: eye sweep across display.json</title>' "$tmp/sweep.html"
check "simulate --reference --json" run 0 simulate "$tmp/r" --eye 0,0,600 -o "$tmp/q.png" \
  --reference --reference-spp 1 --json
for key in psnr ssim brightness crosstalk; do
  check "reference reports $key" grep -q "\"$key\"" "$tmp/out"
done
check "simulate an image and mask pair" run 0 simulate --image "$tmp/r/image.png" \
  --mask "$tmp/r/mask.png" --display "$tmp/small.json" --pupil 4 --diffuser 0.1 \
  --color-filters --spp 9 -o "$tmp/pair.png"
check "simulate without layers exits 2" run 2 simulate "$tmp/nothing-here" -o "$tmp/n.png"
check "missing layers name the file" one_line_naming "image.png"
check "mismatched display exits 2" run 2 simulate "$tmp/r" --display "$src/displays/default.json" \
  -o "$tmp/m.png"
check "mismatched display names the key" one_line_naming "/image_layer/resolution"
check "eye behind the display exits 2" run 2 simulate "$tmp/r" --eye 0,0,-1 -o "$tmp/b.png"
check "bench --simulate" run 0 bench --simulate 2 --display "$tmp/small.json" --json

cli_summary

#!/usr/bin/env bash
# Gaussian splats from the command line (docs/splats.md): splat files made by `parallax splats`,
# read back by `info`, rendered by every route (view, the barrier's slits and layers, the Looking
# Glass panel direct and its quilt, a turntable, the simulator's reference), placed by a scene
# file beside a mesh, and bad files and options refused in one line with exit code 2.
# Usage: cli_splats_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

differ() { ! cmp -s "$1" "$2"; }
json_number() {  # json_number KEY: the first number after "KEY": in $tmp/out
  tr -d ' \n' <"$tmp/out" | grep -o "\"$1\":[0-9.e+-]*" | head -1 | cut -d: -f2
}

# Made files.
check "from-mesh (the built-in scene)" run 0 splats from-mesh --count 3000 -o "$tmp/box.ply"
check "capture-like" run 0 splats capture-like --count 4000 -o "$tmp/capture.ply"
check "info counts the Gaussians" run 0 info --json "$tmp/capture.ply"
check "info: 4000 Gaussians" [ "$(json_number gaussians)" = 4000 ]
check "info: degree 3" [ "$(json_number sh_degree)" = 3 ]
check "info names the splat reader's up axis" grep -q '"up":"-y"' <(tr -d ' \n' <"$tmp/out")
check "same seed, same file" run 0 splats capture-like --count 4000 -o "$tmp/again.ply"
check "the file is the same byte for byte" cmp -s "$tmp/capture.ply" "$tmp/again.ply"

# Every route.
check "view" run 0 view "$tmp/box.ply" --size 96x54 --spp 1 -o "$tmp/view.png"
check "view reports the Gaussians a ray met" grep -q "Gaussians evaluated" "$tmp/out"
check "view is a PNG" is_png "$tmp/view.png"
check "render (slits)" run 0 render "$tmp/box.ply" --spp 1 -o "$tmp/slits"
check "render wrote both layers" is_png "$tmp/slits/mask.png"
check "render.json records the splats" grep -q '"splats_evaluated"' "$tmp/slits/render.json"
check "render --layers optimized-image" run 0 render "$tmp/box.ply" --spp 1 --iterations 1 \
  --layers optimized-image -o "$tmp/layers"
check "the Looking Glass Go direct" run 0 render "$tmp/capture.ply" --display lkg:go --spp 1 \
  -o "$tmp/go"
check "the Go's panel image" [ "$(png_size "$tmp/go/image.png")" = 1440x2560 ]
check "a Portrait quilt" run 0 render "$tmp/capture.ply" --display lkg:portrait --quilt 4x2 \
  --spp 1 -o "$tmp/quilt"
check "a turntable" run 0 render "$tmp/box.ply" --turntable 360 --frames 1:2 --fps 1 --spp 1 \
  -o "$tmp/turn"
check "the turntable's frames differ" differ "$tmp/turn/frame-0001/image.png" \
  "$tmp/turn/frame-0002/image.png"
check "simulate --reference" run 0 simulate "$tmp/slits" --reference --eye 0,0,600 --json \
  --reference-spp 1 -o "$tmp/sim.png"

# A scene file: splats beside a mesh, placed by a transform.
cat >"$tmp/scene.json" <<JSON
{"objects": [{"shape": "box", "min": [-1, -1, -1], "max": [1, -0.9, 1]}],
 "splats": {"file": "capture.ply", "transform": [{"scale": 0.3}]},
 "lights": [{"type": "directional", "direction": [0, -1, 0], "irradiance": [2, 2, 2]}]}
JSON
check "a scene file with splats" run 0 info --json "$tmp/scene.json"
check "its Gaussians" [ "$(json_number gaussians)" = 4000 ]
check "it renders" run 0 view "$tmp/scene.json" --size 64x36 --spp 1 -o "$tmp/scene.png"

# Refusals: one line, exit 2, nothing written.
printf 'ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nproperty float f_dc_0\nproperty float f_dc_1\nproperty float f_dc_2\nproperty float opacity\nproperty float scale_0\nproperty float scale_1\nproperty float scale_2\nproperty float rot_0\nproperty float rot_1\nproperty float rot_2\nproperty float rot_3\nend_header\n0 0 nan 0 0 0 0 0 0 0 1 0 0 0\n' >"$tmp/nan.ply"
check "a NaN centre" run 2 view "$tmp/nan.ply" -o "$tmp/nan.png"
check "names the file and the field" one_line_naming "z is not a finite number"
check "nothing written" [ ! -e "$tmp/nan.png" ]
cat >"$tmp/missing.json" <<JSON
{"splats": [{"file": "nowhere.ply"}]}
JSON
check "a missing splat file" run 2 info "$tmp/missing.json"
check "names the key" one_line_naming "/splats/0/file"
cat >"$tmp/meshsplats.json" <<JSON
{"splats": {"file": "$src/data/bunny.obj"}}
JSON
check "a mesh as splats" run 2 info "$tmp/meshsplats.json"
check "says it is not a splat file" one_line_naming "splat"
check "an output that is not .ply" run 2 splats capture-like --count 10 -o "$tmp/x.png"
check "names the output" one_line_naming "output"
check "a count of 0" run 2 splats capture-like --count 0 -o "$tmp/zero.ply"
check "nothing written for it" [ ! -e "$tmp/zero.ply" ]
check "a folder as the output" run 2 splats capture-like --count 10 -o "$tmp/slits.ply/"
check "a count beyond the memory limit" run 2 splats capture-like --count 90000000 \
  --max-memory 0.5 -o "$tmp/huge.ply"
check "names the count" one_line_naming "--count"
check "nothing written for it either" [ ! -e "$tmp/huge.ply" ]

cli_summary

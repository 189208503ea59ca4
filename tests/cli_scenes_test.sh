#!/usr/bin/env bash
# Every example scene in scenes/ is rendered, not only loaded: an ordinary view, the display's
# layers, and the simulated centre eye scored against the ideal view (a NaN or a black picture
# fails the PSNR floor). Usage: cli_scenes_test.sh PARALLAX_BINARY SOURCE_DIR
# CTest runs it twice: with Embree's best kernels and with PARALLAX_EMBREE_CONFIG=isa=sse4.2,
# the kernels of a CPU without AVX-512 (and without AVX2).
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

# The lowest acceptable PSNR of the centre eye against its ideal view (dB); today's scenes
# score 19-30 dB at 4 rays per pixel.
floor_db=15
psnr_above_floor() {  # the JSON on stdout has a finite mean PSNR above floor_db
  local value
  value=$(tr -d ' \n' <"$tmp/out" | grep -o '"mean":{[^}]*}' | grep -o '"psnr":[^,}]*' | cut -d: -f2)
  [ -n "$value" ] && [ "$value" != null ] && awk -v v="$value" -v f="$floor_db" 'BEGIN { exit !(v > f) }'
}

count=0
for scene in "$src"/scenes/*.json; do
  name=$(basename "$scene" .json)
  count=$((count + 1))
  check "$name: view" run 0 view "$scene" --size 96x54 --spp 1 -o "$tmp/$name-view.png"
  check "$name: view is a PNG" is_png "$tmp/$name-view.png"
  check "$name: render" run 0 render "$scene" --spp 4 -o "$tmp/$name"
  check "$name: render wrote both layers" is_png "$tmp/$name/image.png"
  check "$name: simulate --reference" run 0 simulate "$tmp/$name" --reference --eye 0,0,600 --json \
    --reference-spp 4 -o "$tmp/$name/sim.png"
  check "$name: centre eye above $floor_db dB" psnr_above_floor
done
check "found the example scenes" test "$count" -ge 6
cli_summary

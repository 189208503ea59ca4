#!/usr/bin/env bash
# What the viewer sees, from the command line: render --filter and the dense measure of
# simulate --reference, on a small display (240 x 60 pixels of the built-in pitch, 9 views).
# Usage: cli_quality_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

# A small display: 240 x 60 pixels of the built-in pitch, 9 views.
cp "$src/tests/fixtures/displays/small-9-views.json" "$tmp/small.json"
json_number() {  # json_number KEY_PATH_REGEX: the first number after it in $tmp/out
  tr -d ' \n' <"$tmp/out" | grep -o "$1" | head -1 | grep -o '[-0-9.e]*$'
}

for filter in none view tent gaussian period; do
  check "render --filter $filter" run 0 render --display "$tmp/small.json" --filter "$filter" \
    --spp 4 -o "$tmp/$filter"
  check "render.json records the filter $filter" \
    grep -q "\"kind\": \"$filter\"" "$tmp/$filter/render.json"
done
check "--filter none renders one ray per pixel" grep -q '"spp": 1' "$tmp/none/render.json"
check "unknown filter exits 2" run 2 render --display "$tmp/small.json" --filter box -o "$tmp/x"
check "unknown filter names the option" one_line_naming "--filter"
check "unknown filter writes nothing" test ! -e "$tmp/x"
check "zero filter width exits 2" run 2 render --display "$tmp/small.json" --filter-width 0 \
  -o "$tmp/x"
check "zero filter width names the option" one_line_naming "--filter-width"

# Adaptive sampling: fewer rays, recorded, and the same picture for any thread count.
for threads in 1 2; do
  check "render --adaptive --threads $threads" run 0 render --display "$tmp/small.json" \
    --adaptive --spp 16 --threads "$threads" -o "$tmp/adaptive$threads"
done
check "render.json records adaptive sampling" grep -q '"adaptive": true' "$tmp/adaptive1/render.json"
cp "$tmp/adaptive1/render.json" "$tmp/out"
mean_spp=$(json_number '"mean_spp":[-0-9.e]*')
check "adaptive sampling spends between 4 and 16 rays per pixel ($mean_spp)" \
  awk -v m="$mean_spp" 'BEGIN { exit !(m >= 4 && m < 16) }'
check "adaptive sampling gives the same picture for 1 and 2 threads" \
  cmp -s "$tmp/adaptive1/image.png" "$tmp/adaptive2/image.png"
check "negative --adaptive-threshold exits 2" run 2 render --display "$tmp/small.json" \
  --adaptive --adaptive-threshold -1 -o "$tmp/x"
check "negative --adaptive-threshold names the option" one_line_naming "--adaptive-threshold"

# The dense measure: 9 views x 2 eyes x 2 distances, plus the 9 design eyes.
check "dense measure runs" run 0 simulate "$tmp/view" --reference --eyes-per-view 2 \
  --distances 0.8,1 --reference-spp 1 --json
check "dense measure scores 45 eyes" \
  test "$(tr -d ' \n' <"$tmp/out" | grep -o '"design_eye":' | wc -l)" -eq 45
check "dense measure has a worst eye" grep -q '"worst_psnr"' "$tmp/out"
check "dense eyes listed by place: distance, then left to right, design eyes among them" \
  python3 -c 'import json, sys
eyes = json.load(open(sys.argv[1]))["eyes"]
places = [(e["eye"][2], e["eye"][0]) for e in eyes]
design = [i for i, e in enumerate(eyes) if e["design_eye"]]
sys.exit(0 if places == sorted(places) and design and design[-1] < len(eyes) - 1 else 1)' "$tmp/out"
check "dense measure has a flicker figure" grep -q '"flicker"' "$tmp/out"
check "dense measure reports each distance" grep -q '"by_distance"' "$tmp/out"
worst=$(json_number '"mean":{[^}]*"worst_psnr":[-0-9.e]*')
mean=$(json_number '"mean":{[^}]*"psnr":[-0-9.e]*')
check "the worst eye is no better than the mean" awk -v w="$worst" -v m="$mean" \
  'BEGIN { exit !(w <= m && m > 10) }'
check "dense text output has the summary rows" run 0 simulate "$tmp/view" --reference \
  --eyes-per-view 1 --distances 1 --reference-spp 1
check "summary rows" bash -c "grep -q 'dense eyes' '$tmp/out' && grep -q 'design eyes' '$tmp/out'"
check "bad --distances exits 2" run 2 simulate "$tmp/view" --reference --distances 0.8,x
check "bad --distances names the option" one_line_naming "--distances"
check "bad --eyes-per-view exits 2" run 2 simulate "$tmp/view" --reference --eyes-per-view 0
check "bad --eyes-per-view names the option" one_line_naming "--eyes-per-view"
cli_summary

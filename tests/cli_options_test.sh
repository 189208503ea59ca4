#!/usr/bin/env bash
# Every numeric option of every command at and beyond its range (docs/inputs.md), absurd sizes
# refused with the memory estimate, the time estimate, --max-memory, CLI11's own errors as one
# line, and output sets that are replaced whole or not at all.
# Usage: cli_options_test.sh PARALLAX_BINARY SOURCE_DIR
# CASES: 286 refusals (each: exit 2, exactly one stderr line "error: ..." naming the option, no
# output written) and 20 further cases (help, limits that let work run, output sets, the
# import record).
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

refusals=0
out=0
# refuse NAME OPTION_TEXT ARGS...: exit 2, one line starting "error:" that names the option, and
# nothing written to the output named by $o (a fresh path for each case).
refuse() {
  local name=$1 naming=$2
  shift 2
  refusals=$((refusals + 1))
  check "$name: exit 2" run 2 "$@"
  check "$name: one line naming $naming" one_line_naming "$naming"
  check "$name: starts with error:" grep -q '^error: ' "$tmp/err"
  check "$name: no output" test ! -e "$o"
  out=$((out + 1))
  o="$tmp/out-$out"
}
o="$tmp/out-0"

# A render output folder and a small lenticular calibration for the commands that read them.
check "render a set for the other commands" run 0 render --spp 1 -o "$tmp/set"
cp "$src/tests/fixtures/displays/small-lenticular-96x128.json" "$tmp/small.json"
# A display of 65536 x 65536 pixels on each layer.
sed -e 's/1920/65536/; s/1080/65536/' "$tmp/set/display.json" |
  awk '/resolution/ {r=1} r && /1920/ {sub(/1920/, "65536")} r && /1080/ {sub(/1080/, "65536"); r=0} {print}' \
    >"$tmp/huge.json"

# ---- The sampling options shared by render, view, bench and lenticular render ----------------
for cmd in render view bench "lenticular render $tmp/small.json"; do
  # shellcheck disable=SC2086
  set -- $cmd
  for bad in 0 -1 1.5 abc nan inf "" 99999999999; do
    refuse "$cmd --spp '$bad'" --spp "$@" --spp "$bad" -o "$o"
  done
  for bad in -1 100000 abc 2.5; do
    refuse "$cmd --threads '$bad'" --threads "$@" --threads "$bad" -o "$o"
  done
  for bad in -1 abc 1e3 99999999999999999999999; do
    refuse "$cmd --seed '$bad'" --seed "$@" --seed "$bad" -o "$o"
  done
  refuse "$cmd --jitter" --jitter "$@" --jitter sideways -o "$o"
  for bad in -1 65 abc 2.5; do
    refuse "$cmd --bounces '$bad'" --bounces "$@" --bounces "$bad" -o "$o"
  done
  # The import options come with the sampling options (docs/import.md).
  for bad in -1 180.5 abc nan; do
    refuse "$cmd --crease '$bad'" --crease "$@" --crease "$bad" -o "$o"
  done
  # (CLI11 names it --up where that is its first name, --mesh-up on view)
  refuse "$cmd --mesh-up" "up: x not in" "$@" --mesh-up x -o "$o"
done
# The time estimate: a billion samples per pixel, and a small --max-time.
refuse "view --spp 1e9" "--spp 1000000000" view --spp 1000000000 -o "$o"
check "view --spp 1e9: the estimate and the limit" grep -q "days.*limit" "$tmp/err"
refuse "view --max-time 1" "--spp 64" view --max-time 1 --size 4000x4000 --spp 64 -o "$o"
refuse "view --max-time 0" --max-time view --max-time 0 -o "$o"
refuse "view --max-time nan" --max-time view --max-time nan -o "$o"

# ---- view ------------------------------------------------------------------------------------
for bad in 0 180 -5 200 nan inf abc; do
  refuse "view --fov '$bad'" --fov view --fov "$bad" -o "$o.png"
done
for bad in 0x10 10x0 -5x5 10by10 axb 10x 1.5x2 99999999999x2; do
  refuse "view --size '$bad'" --size view --size "$bad" -o "$o.png"
done
refuse "view --size 65536x65536" "--size 65536x65536" view --size 65536x65536 -o "$o.png"
check "view --size 65536x65536: says GiB and limit" grep -q "GiB for the scene.s BVH and the film (limit .* GiB)" "$tmp/err"
refuse "view --size 20000x20000 under 1 GiB" "--size 20000x20000" \
  view --size 20000x20000 --max-memory 1 -o "$o.png"
check "20000x20000: GiB and limit" grep -q "GiB.*limit" "$tmp/err"
refuse "view --eye garbage" --eye view --eye 1,2,nan -o "$o.png"
refuse "view --display-eye behind" --display-eye view --display-eye 0,0,-5 -o "$o.png"
# The pinhole camera and the ideal window view do not mix; eye on look-at names --look-at.
refuse "view --fov with --display-eye" "--fov: places the pinhole camera: not with --display-eye" \
  view --display-eye 0,0,600 --fov 40 -o "$o.png"
refuse "view --eye with --display-eye" "--eye: places the pinhole camera" \
  view --display-eye 0,0,600 --eye 0,0,5 -o "$o.png"
refuse "view --display without --display-eye" "--display: is the display of --display-eye" \
  view --display "$tmp/small.json" -o "$o.png"
refuse "view --focus without --display-eye" "frames the scene for --display-eye" \
  view --focus 5 -o "$o.png"
refuse "view --eye on --look-at" "--look-at: the camera would look at its own position" \
  view --eye 0,0,5 --look-at 0,0,5 -o "$o.png"

# ---- render ----------------------------------------------------------------------------------
for bad in 0x4 ax4 4 -1x2; do
  refuse "render --quilt '$bad'" --quilt render --quilt "$bad" -o "$o"
done
refuse "render --quilt 8x8 --size 8192x8192" "--quilt 8x8 --size 8192x8192" \
  render --quilt 8x8 --size 8192x8192 -o "$o"
check "quilt: GiB and limit" grep -q "GiB for the quilt (limit" "$tmp/err"
refuse "render --quilt --size 0x0" --size render --quilt 2x2 --size 0x0 -o "$o"
refuse "render a 65536^2 display" huge.json render --display "$tmp/huge.json" -o "$o"
check "huge display: GiB and limit" grep -q "GiB for the layers.*limit" "$tmp/err"
refuse "render under --max-memory 0.01" "GiB" render --max-memory 0.01 -o "$o"
check "small limit: the estimate" grep -q "needs about .* GiB.*(limit 0.01 GiB)" "$tmp/err"
refuse "global --max-memory 0.01" "limit 0.01 GiB" --max-memory 0.01 render -o "$o"
for bad in 0 -1 nan inf abc 1e9; do
  refuse "render --max-memory '$bad'" --max-memory render --max-memory "$bad" -o "$o"
done
# Solver options: 0 iterations is no default, and without a solver they would be ignored.
for bad in 0 -1 1001 abc 2.5; do
  refuse "render --layers nmf --iterations '$bad'" --iterations \
    render --layers nmf --iterations "$bad" -o "$o"
done
refuse "render --layers optimized-image --iterations 0" --iterations \
  render --layers optimized-image --iterations 0 -o "$o"
refuse "render --iterations with slits" "--iterations: applies to --layers optimized-image or nmf" \
  render --iterations 5 -o "$o"
refuse "render --brightness with slits" "--brightness: applies to --layers" render --brightness 2 -o "$o"
refuse "render --layer-error with slits" "--layer-error: applies to --layers" \
  render --layer-error linear -o "$o"
# Settings of an option that is not given: refused (CLI11's "requires"), not ignored.
refuse "render --adaptive-threshold without --adaptive" "--adaptive-threshold requires --adaptive" \
  render --adaptive-threshold 5 -o "$o"
refuse "render --video-quality without --video" "--video-quality requires --video" \
  render --video-quality 10 -o "$o"
refuse "render --video-codec without --video" "--video-codec requires --video" \
  render --video-codec h265 -o "$o"
refuse "simulate --fps without --video" "--fps requires --video" \
  simulate "$tmp/set" --sweep 3 --fps 10 -o "$o"
for opt in "--depth-range 1:2" "--depth-convention depth" "--rgbd-edges layered" "--rgbd-fov 60"; do
  # shellcheck disable=SC2086
  refuse "render $opt without --rgbd" "${opt%% *} requires --rgbd" render $opt -o "$o"
done

# ---- simulate --------------------------------------------------------------------------------
for bad in 2 -4 abc nan; do
  refuse "simulate --spp '$bad'" --spp simulate "$tmp/set" --spp "$bad" -o "$o.png"
done
check "simulate --spp 0 (the exact integral, the default) runs" run 0 simulate "$tmp/set" \
  --spp 0 -o "$tmp/spp0.png"
check "simulate --spp 0 is the default" run 0 simulate "$tmp/set" -o "$tmp/sppdefault.png"
check "simulate --spp 0 and the default write the same picture" \
  cmp -s "$tmp/spp0.png" "$tmp/sppdefault.png"
for bad in -1 101 nan inf abc; do
  refuse "simulate --pupil '$bad'" --pupil simulate "$tmp/set" --pupil "$bad" -o "$o.png"
done
for bad in 0 -1 abc; do
  refuse "simulate --pupil-samples '$bad'" --pupil-samples \
    simulate "$tmp/set" --pupil-samples "$bad" -o "$o.png"
done
for bad in -1 nan inf 100000; do
  refuse "simulate --diffuser '$bad'" --diffuser simulate "$tmp/set" --diffuser "$bad" -o "$o.png"
done
for bad in -1 abc 2.5; do
  refuse "simulate --sweep '$bad'" --sweep simulate "$tmp/set" --sweep "$bad" -o "$o"
done
refuse "simulate --sweep 100000" "--sweep 100000" simulate "$tmp/set" --sweep 100000 -o "$o"
check "sweep 100000: GiB and limit" grep -q "GiB.*limit" "$tmp/err"
for bad in 0 -1 11 1e9 nan; do
  refuse "simulate --sweep-range '$bad'" --sweep-range \
    simulate "$tmp/set" --sweep 3 --sweep-range "$bad" -o "$o"
done
for bad in 0 -5 nan inf; do
  refuse "simulate --sweep-distance '$bad'" --sweep-distance \
    simulate "$tmp/set" --sweep 3 --sweep-distance "$bad" -o "$o"
done
refuse "simulate --sweep-distance 1e9" --sweep-distance \
  simulate "$tmp/set" --sweep 3 --sweep-distance 1e9 -o "$o"
for bad in 0 -1 abc; do
  refuse "simulate --reference-spp '$bad'" --reference-spp \
    simulate "$tmp/set" --reference --eye 0,0,600 --reference-spp "$bad" -o "$o.png"
done
for bad in -1 100000; do
  refuse "simulate --threads '$bad'" --threads simulate "$tmp/set" --threads "$bad" -o "$o.png"
done
refuse "simulate --size 65536x65536" "--size 65536x65536" \
  simulate "$tmp/set" --size 65536x65536 -o "$o.png"
refuse "simulate --eye behind" --eye simulate "$tmp/set" --eye 0,0,-1 -o "$o.png"
# --reference reads the scene before it writes a picture.
refuse "simulate --reference with a missing scene" nope.json \
  simulate "$tmp/set" --reference --eye 0,0,600 --scene "$tmp/nope.json" -o "$o.png"
# The dense measure's inputs without it: refused, not ignored.
refuse "simulate --compare without --reference" \
  "--compare: scores other renders in the dense measure: needs --reference" \
  simulate "$tmp/set" --compare "$tmp/set" -o "$o.png"
refuse "simulate --compare with --eye" --compare \
  simulate "$tmp/set" --reference --eye 0,0,600 --compare "$tmp/set" -o "$o.png"
refuse "simulate --compare with --sweep" --compare \
  simulate "$tmp/set" --reference --sweep 3 --compare "$tmp/set" -o "$o"
# A compared render of another size is named as the compared one, not blamed on the first.
check "render a set for another display" run 0 render --spp 1 --display "$src/displays/small.json" \
  -o "$tmp/small-set"
refuse "simulate --compare of another size" \
  "--compare $tmp/small-set: its image layer is 320x180 pixels, $tmp/set's is 1920x1080" \
  simulate "$tmp/set" --reference --eyes-per-view 1 --distances 1 --compare "$tmp/small-set" \
  -o "$o.png"
refuse "simulate --scene without --reference" "--scene: is the scene --reference" \
  simulate "$tmp/set" --scene "$tmp/nope.json" -o "$o.png"
for opt in "--reference-spp 4" "--eyes-per-view 3" "--distances 1"; do
  # shellcheck disable=SC2086
  refuse "simulate $opt without --reference" "${opt%% *} requires --reference" \
    simulate "$tmp/set" $opt -o "$o.png"
done
refuse "simulate --pupil-samples without --pupil" "--pupil-samples requires --pupil" \
  simulate "$tmp/set" --pupil-samples 4 -o "$o.png"
refuse "simulate --sweep-range without --sweep" "--sweep-range requires --sweep" \
  simulate "$tmp/set" --sweep-range 2 -o "$o.png"
refuse "simulate --sweep-distance without --sweep" "--sweep-distance requires --sweep" \
  simulate "$tmp/set" --sweep-distance 500 -o "$o.png"

# ---- lightfield ------------------------------------------------------------------------------
for bad in nan inf abc; do
  refuse "lightfield --from '$bad'" --from lightfield --from "$bad" -o "$o.svg"
  refuse "lightfield --to '$bad'" --to lightfield --to "$bad" -o "$o.svg"
done
refuse "lightfield --to below --from" --to lightfield --from 5 --to 1 -o "$o.svg"
for bad in -2 abc 100000; do
  refuse "lightfield --row '$bad'" --row lightfield --row "$bad" -o "$o.svg"
done
for bad in 3 -1 abc; do
  refuse "lightfield --spp '$bad'" --spp lightfield --spp "$bad" -o "$o.svg"
done
refuse "lightfield --spp huge" "--spp 1000000" lightfield --from -200 --to 200 --spp 1000000 -o "$o.svg"

# ---- calibrate -------------------------------------------------------------------------------
for opt in --screen-period --steps --label-scale; do
  for bad in -1 abc 2.5; do
    refuse "calibrate patterns $opt '$bad'" "$opt" calibrate patterns "$opt" "$bad" -o "$o"
  done
done
refuse "calibrate patterns --steps 0" --steps calibrate patterns --steps 0 -o "$o"
refuse "calibrate patterns --steps 1e9" "--steps 1000000000" calibrate patterns --steps 1000000000 -o "$o"
refuse "calibrate patterns --label-scale huge" --label-scale calibrate patterns --label-scale 100000 -o "$o"
for opt in --slit-period --from --to --phase-step; do
  refuse "calibrate patterns $opt -1" "$opt" calibrate patterns "$opt" -1 -o "$o"
  refuse "calibrate patterns $opt nan" "$opt" calibrate patterns "$opt" nan -o "$o"
done
for bad in 0 1.5 nan; do
  refuse "calibrate patterns --duty '$bad'" --duty calibrate patterns --duty "$bad" -o "$o"
done
refuse "calibrate patterns --phase inf" --phase calibrate patterns --phase inf -o "$o"
for bad in 0 -1 abc; do
  refuse "calibrate predict --samples '$bad'" --samples calibrate predict --samples "$bad"
done
refuse "calibrate predict --samples 1e9" "--samples 1000000000" calibrate predict --samples 1000000000
refuse "calibrate predict --duty 2" --duty calibrate predict --duty 2
refuse "calibrate predict --from -1" --from calibrate predict --from -1
for opt in --screen-period --slit-period --gap; do
  for bad in 0 -3 nan; do
    refuse "calibrate apply $opt '$bad'" "$opt" calibrate apply --screen-period 9 --slit-period 8.95 \
      "$opt" "$bad" -o "$o.json"
  done
done
refuse "calibrate apply --phase inf" --phase \
  calibrate apply --screen-period 9 --slit-period 8.95 --phase inf -o "$o.json"

# ---- lenticular, bench, design ---------------------------------------------------------------
for bad in 0 -1 nan; do
  refuse "lenticular render --distance '$bad'" --distance \
    lenticular render "$tmp/small.json" --distance "$bad" -o "$o"
  refuse "lenticular simulate --distance '$bad'" --distance \
    lenticular simulate "$tmp/set" "$tmp/small.json" --distance "$bad" -o "$o.png"
done
for bad in 0 -1 abc; do
  refuse "bench --repeats '$bad'" --repeats bench --repeats "$bad"
done
refuse "bench --simulate -1" --simulate bench --simulate -1
refuse "bench --size 65536x65536" "--size 65536x65536" bench --size 65536x65536
for bad in nan inf abc 100000; do
  refuse "design --depth '$bad'" --depth design --depth "$bad"
done

# ---- CLI11's own errors: one line, "error:" ---------------------------------------------------
refuse "unknown option" --no-such-option view --no-such-option -o "$o.png"
refuse "missing value" --fov view --fov
refuse "unknown command" frobnicate frobnicate
refuse "no command" "subcommand" --max-memory 1
refuse "calibrate apply without required" --screen-period calibrate apply -o "$o.json"
check "--help still works" run 0 --help
check "--help prints usage" grep -q "render" "$tmp/out"
check "render --help still works" run 0 render --help
check "render --help lists --max-memory" grep -q -- "--max-memory" "$tmp/out"

# ---- Limits that let work run -----------------------------------------------------------------
check "a generous --max-memory lets a view run" run 0 view --max-memory 4 --size 32x18 --spp 1 -o "$tmp/ok.png"
check "the view was written" is_png "$tmp/ok.png"

# ---- Output sets ------------------------------------------------------------------------------
cp -r "$tmp/set" "$tmp/before"
echo keep >"$tmp/set/notes.txt"
check "a failing render leaves the set" run 2 render "$tmp/nope.json" -o "$tmp/set"
check "the old image is intact" cmp -s "$tmp/set/image.png" "$tmp/before/image.png"
check "the old render.json is intact" cmp -s "$tmp/set/render.json" "$tmp/before/render.json"
check "a refused render leaves the set" run 2 render --max-memory 0.01 -o "$tmp/set"
check "still intact" cmp -s "$tmp/set/mask.png" "$tmp/before/mask.png"
mkdir -p "$tmp/.set.tmp-999999999" "$tmp/.set.old-999999999"
check "a render replaces the set" run 0 render --spp 1 --seed 7 -o "$tmp/set"
check "the new render.json says seed 7" grep -q '"seed": 7' "$tmp/set/render.json"
check "other files in the folder stay" grep -q keep "$tmp/set/notes.txt"
check "temporaries of killed runs are gone" test ! -e "$tmp/.set.tmp-999999999" -a ! -e "$tmp/.set.old-999999999"
check "no temporaries left anywhere" bash -c "! find '$tmp' -name '*.tmp*' | grep -q ."

# ---- What the import did, in render.json (docs/import.md) -------------------------------------
spider="$src/data/assimp/STL/Spider_binary.stl"
if [ -f "$spider" ]; then
  check "render an STL with --up y --crease 0" run 0 render "$spider" --spp 1 --up y --crease 0 -o "$tmp/stl"
  check "render.json names the reader" grep -q '"reader": "parallax-stl"' "$tmp/stl/render.json"
  check "render.json says up y and faceted" \
    bash -c "grep -q '\"up\": \"y\"' '$tmp/stl/render.json' && grep -q '\"normals\": \"faceted\"' '$tmp/stl/render.json'"
fi
check "the built-in scene imports nothing" grep -q '"import": \[\]' "$tmp/set/render.json"

echo "$refusals refusal cases"
cli_summary

#!/usr/bin/env bash
# Reproduces the paper's experiments with parallax: renders each configuration, simulates what
# eyes across the view zone see, measures it against the ideal view, and writes a gallery page
# with the pictures and a table of figures.
#
#   examples/paper/run.sh [--full | --size WxH | --display FILE] [--bin PATH] [--out DIR]
#                         [--page FILE]
#
# Default: reduced size (a 480x270 panel with the default display's pitch and gap: a crop of
# the full display), which CI runs as a test. --full: the built-in 1920x1080 display.
# --display FILE: your own barrier display file, each experiment's one change (mask, D')
# merged into it, at its own size and with the full measure. The
# gallery in docs/ is made at half size, to keep the repository small:
#   examples/paper/run.sh --size 960x540 --out docs/gallery --page docs/gallery.md
# Each experiment also leaves an animation (NAME-anim.png) and a slider page (NAME.html) in the
# output folder; docs/gallery keeps only the contact sheets.
set -euo pipefail

root=$(cd "$(dirname "$0")/../.." && pwd)
bin="$root/build/parallax"
out="$root/out/paper"
page=""
user_display=""
full=0
size=""
while [ $# -gt 0 ]; do
  case "$1" in
    --full) full=1 ;;
    --size) size=$2; shift ;;
    --bin) bin=$2; shift ;;
    --out) out=$2; shift ;;
    --page) page=$2; shift ;;
    --display) user_display=$2; shift ;;
    *) echo "usage: $0 [--full | --size WxH | --display FILE] [--bin PATH] [--out DIR] [--page FILE]" >&2; exit 2 ;;
  esac
  shift
done
[ -n "$page" ] || page="$out/gallery.md"
mkdir -p "$out"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT

if [ $full -eq 1 ]; then width=1920; height=1080; sweep=9; refspp=16; else width=480; height=270; sweep=5; refspp=4; fi
if [ -n "$size" ]; then width=${size%x*}; height=${size#*x}; sweep=9; refspp=16; fi
if [ -n "$user_display" ]; then
  # The user's display: checked (and its size read) by parallax itself, so that a bad file
  # stops here with parallax's own message naming the file and the key.
  [ -r "$user_display" ] || { echo "$0: --display $user_display: no such file" >&2; exit 2; }
  "$bin" design "$user_display" --json >"$work/user-design.json" || exit 2
  read -r width height < <(python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
if "image_resolution" not in d:
    sys.exit(sys.argv[2] + ": the experiments of the paper need a barrier display (two layers)")
print(*d["image_resolution"])' "$work/user-design.json" "$user_display") || exit 2
  sweep=9; refspp=16; full=1
fi
# The dense measure (docs/simulator.md): K eyes inside every view's window at 0.8, 1 and 1.25 D.
eyes_per_view=4
[ $full -eq 1 ] || [ -n "$size" ] || eyes_per_view=2
# A display file per experiment: the built-in display at this size, with one change each.
display() {  # display NAME EXTRA_JSON
  if [ -n "$user_display" ]; then
    # The user's file with the experiment's keys merged over it (JSON with // comments, as
    # parallax reads them).
    python3 - "$user_display" "{${2#, }}" "$work/$1.json" <<'PY'
import json, re, sys
text = re.sub(r'^\s*//.*$', '', open(sys.argv[1]).read(), flags=re.M)
base, extra = json.loads(text), json.loads(sys.argv[2])
base.update(extra)
json.dump(base, open(sys.argv[3], "w"))
PY
  else
    printf '{"image_layer": {"resolution": [%d, %d], "pixel_pitch_mm": 0.2745}, "gap_mm": 3, "view_distance_mm": 600, "views": 9%s}\n' \
      "$width" "$height" "$2" >"$work/$1.json"
  fi
  echo "$work/$1.json"
}
# The scenes are scaled with the panel so that the reduced size shows the same picture.
scale=$(awk -v w="$width" 'BEGIN { printf "%.4f", 4 * w / 1920 }')
[ -z "$user_display" ] || scale=4  # your panel shows the whole scene
scene() {  # scene SOURCE NAME: a copy whose display width matches this panel size
  sed "s/\"width\": 4}/\"width\": $scale}/" "$1" >"$work/$2.json"
  echo "$work/$2.json"
}
box=$(scene "$root/scenes/checker-box.json" box)
shadows=$(scene "$root/scenes/paper-shadows.json" shadows)

rows=()
# experiment NAME TITLE SCENE DISPLAY SPP [render options...]
experiment() {
  local name=$1 title=$2 scene=$3 disp=$4 spp=$5
  shift 5
  "$bin" render "$scene" --display "$disp" --spp "$spp" "$@" -o "$work/$name" >/dev/null
  "$bin" simulate "$work/$name" --sweep "$sweep" -o "$out/$name" >/dev/null
  local json
  json=$("$bin" simulate "$work/$name" --sweep "$sweep" -o "$work/$name-q" --reference \
    --reference-spp "$refspp" --json)
  # Brightness and cross-talk: means over the sweep (one value per line in its "mean" object).
  local mean
  mean=$(printf '%s\n' "$json" | awk '/"mean"/ {m=1} m && /"(brightness|crosstalk)"/ {gsub(/[",:]/, ""); printf "%s=%s ", $1, $2}')
  # PSNR, SSIM, worst eye and flicker: the dense measure; the design eyes as their own column.
  json=$("$bin" simulate "$work/$name" --reference --eyes-per-view "$eyes_per_view" \
    --reference-spp "$refspp" --json)
  mean+=$(printf '%s\n' "$json" | awk '
    /^  "[a-z_]+": [{[]/ { section = $1; gsub(/[":]/, "", section) }
    /^    "(psnr|ssim|worst_psnr|flicker)"/ && (section == "mean" || section == "design_eyes") {
      key = $1; value = $2; gsub(/[",:]/, "", key); gsub(/,/, "", value)
      printf "%s%s=%s ", (section == "mean" ? "" : "design_"), key, value }')
  rows+=("$name|$title|$spp|$mean")
  echo "$name: $mean"
}

default=$(display default "")
experiment box-1spp "Box over checkerboard, 1 ray per pixel (Fig. 10)" "$box" "$default" 1
experiment box-16spp "Box over checkerboard, 16 rays per pixel (Fig. 11)" "$box" "$default" 16
experiment shadows-1spp "Shadows, 1 ray per pixel: ghost shadows (Fig. 12)" "$shadows" "$default" 1
experiment shadows-16spp "Shadows, 16 rays per pixel: blurred (Fig. 13)" "$shadows" "$default" 16
ortho=$(display ortho ', "virtual": {"distance_mm": "infinity"}')
experiment ortho-1spp "D' = infinity, orthographic views, 1 ray (Fig. 14)" "$box" "$ortho" 1
experiment ortho-16spp "D' = infinity, orthographic views, 16 rays (Fig. 14)" "$box" "$ortho" 16
slanted=$(display slanted ', "mask": {"type": "slanted", "angle_deg": 18.4, "duty_cycle": 0.1111}')
experiment slanted "Slanted mask (Fig. 15)" "$box" "$slanted" 16
wiggling=$(display wiggling ', "mask": {"type": "wiggling", "amplitude_mm": 0.6, "wavelength_mm": 7, "duty_cycle": 0.1111}')
experiment wiggling "Wiggling mask (Fig. 16)" "$box" "$wiggling" 16
jittered=$(display jittered ', "mask": {"type": "jittered", "jitter": 0.2, "seed": 3, "duty_cycle": 0.1111}')
experiment jittered "Randomly jittered mask (section 4.3)" "$box" "$jittered" 16
experiment direct "Direct mapping of 9 camera views (Fig. 2), the usual practice" "$box" "$default" 16 --direct-mapping
# Beyond the paper: content-adaptive layers (docs/content-adaptive.md). The quick default run
# (CI's) trains on one eye per view for a few iterations; the gallery's runs use the defaults.
solver=()
[ $full -eq 1 ] || [ -n "$size" ] || solver=(--train-eyes 1 --iterations 3)
experiment optimized-image "Content-adaptive: the image layer solved for eyes across the zone, same slits" "$box" "$default" 16 --layers optimized-image "${solver[@]}"
experiment nmf-1 "Content-adaptive: both layers by weighted NMF, rank 1, 2.1x the slits' brightness" "$box" "$default" 16 --layers nmf "${solver[@]}"
experiment nmf-3 "Content-adaptive: 3 time-multiplexed frame pairs by weighted NMF, 3.15x brightness" "$box" "$default" 16 --layers nmf --rank 3 "${solver[@]}"

# Leaving the view zone: the periodic mask wraps around, the jittered one loses parallax.
"$bin" render "$box" --display "$default" --spp 16 -o "$work/wrap" >/dev/null
"$bin" simulate "$work/wrap" --sweep "$sweep" --sweep-range 2.5 -o "$out/leaving-zone" >/dev/null
"$bin" render "$box" --display "$jittered" --spp 16 -o "$work/wrap-jittered" >/dev/null
"$bin" simulate "$work/wrap-jittered" --sweep "$sweep" --sweep-range 2.5 -o "$out/leaving-zone-jittered" >/dev/null
# The display from several angles (Fig. 1): eyes to the left, centre and right, and nearer.
"$bin" simulate "$work/box-16spp" --eye -200,0,600 --eye 0,0,600 --eye 200,0,600 --eye 0,0,400 \
  -o "$out/angles.png" >/dev/null
"$bin" lightfield "$default" --from -3 --to 3 --spp 16 -o "$out/lightfield.svg" >/dev/null

rel=$(realpath --relative-to="$(dirname "$page")" "$out")
{
  echo "# The paper's experiments, reproduced"
  echo
  echo "Made by \`examples/paper/run.sh --size ${width}x${height}\`: a ${width}x${height} panel"
  echo "(0.2745 mm pixels, 3 mm gap, 9 views, D = 600 mm, mask behind the image unless noted; the"
  echo "scenes are scaled so that this panel shows the centre of the full 1920x1080 display's picture)."
  echo "Each row renders the scene for the display (rays over each pixel's own view window,"
  echo "\`--filter view\`) and scores what viewers see with the dense measure"
  echo "(\`parallax simulate --reference\`, docs/simulator.md): $eyes_per_view eyes evenly inside every"
  echo "view's window, at 0.8, 1 and 1.25 times the design distance, each simulated view compared"
  echo "with the ideal view of that eye filtered to the display's resolution. PSNR and SSIM are means"
  echo "over those eyes, *worst* is the lowest eye's PSNR, *flicker* the RMS departure of the"
  echo "frame-to-frame change along each row of eyes from the ideal's (sRGB values; angular aliasing"
  echo "shows there). Brightness is the mean transmittance; cross-talk is the share of light from"
  echo "other views, measured with view-coded layers. Pictures are what $sweep eyes across the zone see"
  echo "(\`simulate --sweep\`), integrated over one screen period as a viewer at 600 mm perceives"
  echo "them; the script also writes an animation and a page with a slider for every row (not kept"
  echo "in docs/, to keep the repository small)."
  echo
  echo "Reading the figures: the column *design eyes* scores only the 9 eyes the display was"
  echo "designed for. There one ray per pixel is exact by construction (each seen pixel is exactly"
  echo "the ideal ray), so that column is biased in favour of 1-ray renders and cannot tell a good"
  echo "prefilter from none; between the design eyes a 1-ray render shows two views at once"
  echo "(ghosts). Judge by the dense columns."
  echo
  echo "| experiment | spp | PSNR (dB) | worst eye (dB) | SSIM | flicker | design eyes (dB, biased) | brightness | cross-talk |"
  echo "|---|---|---|---|---|---|---|---|---|"
  for row in "${rows[@]}"; do
    IFS='|' read -r name title spp mean <<<"$row"
    get() { printf '%s\n' "$mean" | tr ' ' '\n' | awk -F= -v k="$1" '$1 == k { printf "%.3f", $2 }'; }
    echo "| [$title](#$name) | $spp | $(get psnr) | $(get worst_psnr) | $(get ssim) | $(get flicker) | $(get design_psnr) | $(get brightness) | $(get crosstalk) |"
  done
  echo
  for row in "${rows[@]}"; do
    IFS='|' read -r name title spp mean <<<"$row"
    echo "<a id=\"$name\"></a>"
    echo
    echo "### $title"
    echo
    echo "![$title]($rel/$name-sheet.png)"
    echo
  done
  echo "### Leaving the view zone"
  echo
  echo "Eyes from 1.25 view-zone widths left to 1.25 right. The periodic mask repeats its views;"
  echo "the jittered mask's parallax is lost outside the zone."
  echo
  echo "![periodic mask]($rel/leaving-zone-sheet.png)"
  echo
  echo "![jittered mask]($rel/leaving-zone-jittered-sheet.png)"
  echo
  echo "### The display from several angles (Fig. 1)"
  echo
  for i in 0 1 2 3; do echo "![angle $i]($rel/angles-$i.png)"; done
  echo
  echo "### Ray space (Figs. 7, 8)"
  echo
  echo "![ray space]($rel/lightfield.svg)"
} >"$page"
echo "wrote $page"

#!/usr/bin/env bash
# Content-adaptive layers from the command line: render --layers optimized-image | nmf on a
# small display, simulate reading time-multiplexed frames, the dense measure telling the
# optimised image layer from the slits' one, and refusals naming their option.
# Usage: cli_layers_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

# A small display: 240 x 60 pixels of the built-in pitch, 9 views.
cp "$src/tests/fixtures/displays/small-9-views.json" "$tmp/small.json"
record_number() {  # record_number FILE KEY: a number of render.json's /layers
  python3 -c 'import json, sys; print(json.load(open(sys.argv[1]))["layers"][sys.argv[2]])' "$1" "$2"
}

check "render --layers slits" run 0 render --display "$tmp/small.json" --spp 4 -o "$tmp/slits"
check "slits are recorded" grep -q '"method": "slits"' "$tmp/slits/render.json"
check "render --layers optimized-image" run 0 render --display "$tmp/small.json" --spp 4 \
  --layers optimized-image --iterations 6 --train-eyes 2 -o "$tmp/oi"
check "the summary line says how long the solve took" grep -q "; layers optimized-image solved in" "$tmp/out"
check "optimized-image writes both layers" bash -c "test -s '$tmp/oi/image.png' && test -s '$tmp/oi/mask.png'"
check "optimized-image keeps the slit mask" cmp "$tmp/slits/mask.png" "$tmp/oi/mask.png"
first=$(record_number "$tmp/oi/render.json" objective_first)
last=$(record_number "$tmp/oi/render.json" objective_last)
check "optimized-image lowers its objective" awk -v a="$first" -v b="$last" 'BEGIN { exit !(b < a) }'

# bench --layers: the same solve as render's (the same passes over the training targets), its
# pass count from the solver's own steps, and the limit's arithmetic.
check "bench --layers optimized-image" run 0 bench --layers optimized-image --iterations 6 \
  --spp 4 --display "$tmp/small.json" --json
cp "$tmp/out" "$tmp/bench-oi.json"
# The training eyes' distances: two instead of three, two thirds of the eyes, in render and bench.
check "render --train-distances" run 0 render --display "$tmp/small.json" --spp 4 \
  --layers optimized-image --iterations 2 --train-distances 0.85,1.2 -o "$tmp/oi2"
check "bench --train-distances" run 0 bench --layers optimized-image --iterations 2 \
  --spp 4 --display "$tmp/small.json" --train-distances 0.85,1.2 --json
check "two training distances are two thirds of the eyes, in render and bench" python3 -c '
import json, sys
b = json.load(open(sys.argv[1]))["layers"]
r = json.load(open(sys.argv[2]))["layers"]
whole = json.load(open(sys.argv[3]))["layers"]
assert r["training_distances"] == [0.85, 1.2], r
assert 3 * r["training_eyes"] == 2 * whole["training_eyes"] == 3 * b["eyes"], (r, whole, b)
' "$tmp/out" "$tmp/oi2/render.json" "$tmp/oi/render.json"
# The training eyes' samples: --train-spp recorded (2 by default), each eye's jitter drawn from
# --seed, so another seed or sample count solves other layers, and the same ones the same.
check "render two iterations" run 0 render --display "$tmp/small.json" --spp 4 \
  --layers optimized-image --iterations 2 -o "$tmp/plain"
check "render --train-spp 4" run 0 render --display "$tmp/small.json" --spp 4 \
  --layers optimized-image --iterations 2 --train-spp 4 -o "$tmp/spp4"
check "render --seed 3" run 0 render --display "$tmp/small.json" --spp 4 \
  --layers optimized-image --iterations 2 --seed 3 -o "$tmp/seed3"
check "render --seed 3 again" run 0 render --display "$tmp/small.json" --spp 4 \
  --layers optimized-image --iterations 2 --seed 3 -o "$tmp/seed3b"
check "the training samples are recorded" python3 -c '
import json, sys
assert json.load(open(sys.argv[1]))["layers"]["train_spp"] == 4
assert json.load(open(sys.argv[2]))["layers"]["train_spp"] == 2
' "$tmp/spp4/render.json" "$tmp/plain/render.json"
check "another sample count solves another image layer" bash -c "! cmp -s '$tmp/spp4/image.png' \
  '$tmp/plain/image.png'"
check "another seed too" bash -c "! cmp -s '$tmp/seed3/image.png' '$tmp/plain/image.png'"
check "the same seed the same layers" cmp "$tmp/seed3/image.png" "$tmp/seed3b/image.png"
check "--train-spp 0 is refused naming it" run 2 render --display "$tmp/small.json" \
  --layers nmf --train-spp 0 -o "$tmp/bad"
check "the refusal names --train-spp" one_line_naming "--train-spp"
check "--train-spp with the slits is refused" run 2 render --display "$tmp/small.json" \
  --train-spp 4 -o "$tmp/bad"
check "naming it and why" one_line_naming "--train-spp: applies to --layers optimized-image or nmf"
check "a bad --train-distances is refused naming it" run 2 render --display "$tmp/small.json" \
  --layers nmf --train-distances 0.85,far -o "$tmp/bad"
check "the refusal is one line naming the option" one_line_naming "--train-distances"
check "and writes nothing" test ! -e "$tmp/bad"
check "bench --layers is render's solve, pass for pass" python3 -c '
import json, sys
b = json.load(open(sys.argv[1]))["layers"]
r = json.load(open(sys.argv[2]))["layers"]
assert b["passes"] == r["passes"] and b["eyes"] == r["training_eyes"], (b, r)
assert b["iterations"] == r["iterations"] == 6, (b, r)
# One pass per point: the objective, its gradient, the next direction and the curvature along
# it (at the start the preconditioner too); the start, then each point a line search tries
# (one when the first step lowers the objective).
assert b["passes"] >= 1 + b["iterations"], b
assert b["target_bytes"] == b["eyes"] * b["width"] * b["height"] * 3 * 2, b  # 16-bit sRGB
assert abs(b["limit_seconds"] - b["iterations"] * b["streaming_pass_seconds"]) <= 1e-9, b
assert abs(b["ratio"] - b["limit_seconds"] / b["solve_seconds"]) <= 1e-9 * b["ratio"], b
assert abs(b["pass_seconds"] * b["passes"] - b["solve_seconds"]) <= 1e-9 * b["solve_seconds"], b
' "$tmp/bench-oi.json" "$tmp/oi/render.json"
check "bench --layers nmf" run 0 bench --layers nmf --rank 2 --iterations 3 --display "$tmp/small.json" --json
check "nmf passes: per iteration both updates (each image update also evaluates the objective the last left, the first the start's), the last objective" python3 -c '
import json, sys
b = json.load(open(sys.argv[1]))["layers"]
assert b["passes"] == 1 + 2 * 3 and b["rank"] == 2, b
assert b["target_bytes"] == b["eyes"] * b["width"] * b["height"] * 3 * 2, b  # 16-bit linear
' "$tmp/out"
check "bench --layers slits exits 2" run 2 bench --layers slits --display "$tmp/small.json"
check "bench --layers names the option" one_line_naming "--layers"

check "render --layers nmf --rank 2" run 0 render --display "$tmp/small.json" --spp 4 \
  --layers nmf --rank 2 --iterations 3 --train-eyes 1 -o "$tmp/nmf"
for f in image-1.png image-2.png mask-1.png mask-2.png; do
  check "nmf writes $f" test -s "$tmp/nmf/$f"
done
check "nmf lists its frames" python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert [f["image"] for f in d["frames"]] == ["image-1.png", "image-2.png"], d["frames"]
assert d["layers"]["rank"] == 2 and d["layers"]["normalisation"] > 0
' "$tmp/nmf/render.json"
check "simulate reads the frames" run 0 simulate "$tmp/nmf" -o "$tmp/nmf-seen.png"
check "simulate wrote the averaged view" test -s "$tmp/nmf-seen.png"

# The dense measure at eyes the solver never saw (4 per view; it trained at 2 per view).
check "dense measure of slits against optimized-image" run 0 simulate "$tmp/slits" --reference \
  --eyes-per-view 4 --distances 0.8,1.25 --reference-spp 1 --compare "$tmp/oi" --compare "$tmp/nmf" --json
check "optimized-image is seen better than slits" python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
slits, oi = d["renders"][0]["mean"]["psnr"], d["renders"][1]["mean"]["psnr"]
assert oi > slits + 0.1, (slits, oi)
' "$tmp/out"

# A panel with a diffuser foil: layers solved for it (--diffuser, or the display file's own
# diffuser_sigma_mm), recorded, and seen through it by simulate by default.
check "render --layers optimized-image --diffuser 0.4" run 0 render --display "$tmp/small.json" \
  --spp 4 --layers optimized-image --iterations 6 --train-eyes 1 --diffuser 0.4 -o "$tmp/oid"
check "the diffuser is recorded" test "$(record_number "$tmp/oid/render.json" diffuser_sigma_mm)" = 0.4
check "layers solved for the diffuser differ" bash -c "! cmp -s '$tmp/oi/image.png' '$tmp/oid/image.png'"
python3 - "$tmp/small.json" "$tmp/foil.json" <<'PY'
import json, re, sys
d = json.loads(re.sub(r"^\s*//.*$", "", open(sys.argv[1]).read(), flags=re.M))
d["diffuser_sigma_mm"] = 0.4
json.dump(d, open(sys.argv[2], "w"))
PY
check "a display file's diffuser" run 0 render --display "$tmp/foil.json" --spp 4 \
  --layers optimized-image --iterations 6 --train-eyes 1 -o "$tmp/oif"
check "is solved for as --diffuser" cmp "$tmp/oid/image.png" "$tmp/oif/image.png"
check "and written into the render's display" grep -q '"diffuser_sigma_mm": 0.4' "$tmp/oif/display.json"
check "simulate sees the panel through its own diffuser" run 0 simulate "$tmp/oif" --eye 0,0,600 \
  -o "$tmp/foil-seen.png"
check "simulate --diffuser 0.4 of the same layers" run 0 simulate "$tmp/oid" --eye 0,0,600 \
  --diffuser 0.4 -o "$tmp/given-seen.png"
check "is the same picture" cmp "$tmp/foil-seen.png" "$tmp/given-seen.png"
check "simulate --diffuser 0 overrides the panel's" run 0 simulate "$tmp/oif" --eye 0,0,600 \
  --diffuser 0 -o "$tmp/nofoil-seen.png"
check "and sees it sharper" bash -c "! cmp -s '$tmp/foil-seen.png' '$tmp/nofoil-seen.png'"
check "--diffuser with slits exits 2" run 2 render --display "$tmp/small.json" --diffuser 0.4 \
  -o "$tmp/x"
check "names --diffuser" one_line_naming "--diffuser"
sed 's/"diffuser_sigma_mm": 0.4/"diffuser_sigma_mm": -1/' "$tmp/foil.json" >"$tmp/badfoil.json"
check "a negative diffuser in a display file exits 2" run 2 render --display "$tmp/badfoil.json" \
  -o "$tmp/x"
check "names the file and the key" one_line_naming "badfoil.json: /diffuser_sigma_mm"

# Through the panels' colour filters (--color-filters, as simulate's): solved for them, recorded,
# and refused for slits.
check "render --layers optimized-image --color-filters" run 0 render --display "$tmp/small.json" \
  --spp 4 --layers optimized-image --iterations 6 --train-eyes 2 --color-filters -o "$tmp/oic"
check "the colour filters are recorded" test "$(record_number "$tmp/oic/render.json" color_filters)" = True
check "and not when off" test "$(record_number "$tmp/oi/render.json" color_filters)" = False
check "layers solved for the colour filters differ" bash -c "! cmp -s '$tmp/oi/image.png' '$tmp/oic/image.png'"
check "simulate --color-filters sees them" run 0 simulate "$tmp/oic" --eye 0,0,600 --color-filters \
  -o "$tmp/filtered-seen.png"
check "--color-filters with slits exits 2" run 2 render --display "$tmp/small.json" --color-filters \
  -o "$tmp/x"
check "names --color-filters" one_line_naming "--color-filters"

# Eyes with a pupil (--pupil, as simulate's): solved for, recorded, refused for slits and out of
# range.
check "render --layers optimized-image --pupil 4" run 0 render --display "$tmp/small.json" \
  --spp 4 --layers optimized-image --iterations 6 --train-eyes 2 --pupil 4 --pupil-samples 3 \
  -o "$tmp/oip"
check "the pupil is recorded" test "$(record_number "$tmp/oip/render.json" pupil_mm)" = 4.0
check "with its samples" test "$(record_number "$tmp/oip/render.json" pupil_samples)" = 3
check "--pupil with slits exits 2" run 2 render --display "$tmp/small.json" --pupil 4 -o "$tmp/x"
check "names --pupil" one_line_naming "--pupil"
check "--pupil-samples 65 exits 2" run 2 render --display "$tmp/small.json" --spp 4 \
  --layers optimized-image --pupil 4 --pupil-samples 65 -o "$tmp/x"
check "names --pupil-samples" one_line_naming "--pupil-samples"
check "--pupil-samples without --pupil exits 2" run 2 render --display "$tmp/small.json" \
  --layers optimized-image --pupil-samples 4 -o "$tmp/x"
check "and no output" test ! -e "$tmp/x"

check "unknown --layers exits 2" run 2 render --display "$tmp/small.json" --layers best -o "$tmp/x"
check "unknown --layers names the option" one_line_naming "--layers"
check "--rank without nmf exits 2" run 2 render --display "$tmp/small.json" \
  --layers optimized-image --rank 2 -o "$tmp/x"
check "--rank without nmf names the option" one_line_naming "--rank"
check "--layer-error srgb with nmf exits 2" run 2 render --display "$tmp/small.json" \
  --layers nmf --layer-error srgb -o "$tmp/x"
check "the --layer-error refusal names it" one_line_naming "--layer-error"
check "--rank 0 exits 2" run 2 render --display "$tmp/small.json" --layers nmf --rank 0 -o "$tmp/x"
check "--layers nmf on a lenticular display exits 2" run 2 render --display lkg:portrait \
  --layers nmf -o "$tmp/x"
check "the lenticular refusal names --layers" one_line_naming "--layers"
check "no output after refusals" test ! -e "$tmp/x"
cli_summary

#!/usr/bin/env bash
# A Blender shot kept (docs/gltf.md, "Framing a shot"): --camera by the node's name, the camera
# fit (the window is what the camera sees at its focus distance, so a point on that plane falls
# where it fell in the camera's own picture: the camera's `view` and the display's ideal view
# are one picture), --focus-on by a node's name, on a barrier and a lenticular display, the
# render record and simulate's reference, and the refusals.
# Usage: cli_shot_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

# A 16:9 barrier display; the shot: a camera 10 units from a checker of 8 x 4 cells that fills
# its 16:9 frame (yfov 0.5 rad), and a small 'Probe' 5 units behind the checker.
python3 - "$src/tests/fixtures/displays/small-9-views.json" "$tmp/d169.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
d["image_layer"]["resolution"] = [192, 108]
json.dump(d, open(sys.argv[2], "w"))
PY
python3 "$src/tests/make_shot_gltf.py" "$tmp/shot.gltf" 10 0.5 1.7777778 8 4

# pfm_agree A B MEAN FAR: the mean absolute difference of the two PFM pictures is below MEAN
# and the share of pixels whose red differs by more than 0.25 below FAR ("<" both), or, with
# MEAN negative, the share above FAR (they disagree).
pfm_agree() {
  python3 - "$@" <<'PY'
import struct, sys
def img(path):
    data = open(path, "rb").read()
    parts = data.split(b"\n", 3)
    w, h = map(int, parts[1].split())
    return w, h, struct.unpack("<%df" % (3 * w * h), parts[3][: 12 * w * h])
wa, ha, a = img(sys.argv[1])
wb, hb, b = img(sys.argv[2])
assert (wa, ha) == (wb, hb), ((wa, ha), (wb, hb))
mean = sum(abs(x - y) for x, y in zip(a, b)) / len(a)
far = sum(1 for t in range(0, len(a), 3) if abs(a[t] - b[t]) > 0.25) / (wa * ha)
limit_mean, limit_far = float(sys.argv[3]), float(sys.argv[4])
print("mean %.4f, far %.4f" % (mean, far))
if limit_mean >= 0:
    assert mean < limit_mean and far < limit_far, (mean, far)
else:
    assert far > limit_far, (mean, far)
PY
}
# pfm_cells FILE COLUMNS ROWS BAND: the picture's middle, BAND of its width wide (centred), holds
# the checker: each cell's centre is light (white, even cells) or dark; outside the band, on
# the middle row, is the background (dark).
pfm_cells() {
  python3 - "$@" <<'PY'
import struct, sys
data = open(sys.argv[1], "rb").read()
parts = data.split(b"\n", 3)
w, h = map(int, parts[1].split())
px = struct.unpack("<%df" % (3 * w * h), parts[3][: 12 * w * h])
columns, rows, band = int(sys.argv[2]), int(sys.argv[3]), float(sys.argv[4])
# The frame's height in the picture: band * width / (16 / 9), centred.
fw, fh = band * w, band * w * 9 / 16
def red(x, y):  # x, y from the top left; PFM rows run bottom to top
    return px[3 * ((h - 1 - int(y)) * w + int(x))]
for j in range(rows):
    for i in range(columns):
        x = w / 2 - fw / 2 + fw * (i + 0.5) / columns
        y = h / 2 + fh / 2 - fh * (j + 0.5) / rows  # glTF row j counts from the bottom
        light = (i + j) % 2 == 0
        v = red(x, y)
        assert (v > 0.3) == light, ("cell", i, j, v)
if band < 0.9:
    for x in (w * (0.5 - band / 2) * 0.5, w - w * (0.5 - band / 2) * 0.5):
        assert red(x, h / 2) < 0.1, ("background", x, red(x, h / 2))
PY
}

# --camera by the camera's name, its node's name (Blender's object name) and its index: one
# picture.
for choice in Camera.001 ShotCam 0; do
  check "view --camera $choice" run 0 view "$tmp/shot.gltf" --camera "$choice" --size 192x108 \
    --spp 4 -o "$tmp/cam-$choice.pfm"
done
check "the node's name picks the camera" cmp -s "$tmp/cam-Camera.001.pfm" "$tmp/cam-ShotCam.pfm"
check "the index picks the camera" cmp -s "$tmp/cam-Camera.001.pfm" "$tmp/cam-0.pfm"
check "info lists the node's name" run 0 info "$tmp/shot.gltf"
check "info: camera and node" grep -qF "0 'Camera.001' (node 'ShotCam')" "$tmp/out"
check "info: the nodes for --focus-on" grep -qE "^  Board +centre \(0, 0, 0\)" "$tmp/out"
check "info: fit camera by default" grep -qF "depth (fit camera)" "$tmp/out"
check "info: the focus where the line of sight meets the checker" \
  grep -qF "the camera's shot 10 units away (where its line of sight meets the content)" "$tmp/out"

# The camera fit: the display's ideal view from the centre eye is the camera's picture (the
# checker is on the focus plane); the depth fit (the content's bounds) is not.
check "view --display-eye (fit camera, the default)" run 0 view "$tmp/shot.gltf" \
  --display "$tmp/d169.json" --display-eye 0,0,600 --spp 4 -o "$tmp/ideal.pfm"
check "the ideal view is the camera's picture" pfm_agree "$tmp/cam-0.pfm" "$tmp/ideal.pfm" 0.004 0.005
check "view --display-eye --fit depth" run 0 view "$tmp/shot.gltf" --fit depth \
  --display "$tmp/d169.json" --display-eye 0,0,600 --spp 4 -o "$tmp/depth.pfm"
check "the depth fit frames otherwise" pfm_agree "$tmp/cam-0.pfm" "$tmp/depth.pfm" -1 0.1
check "and from an eye off the centre, the focus plane stays put" run 0 view "$tmp/shot.gltf" \
  --display "$tmp/d169.json" --display-eye 40,-20,700 --spp 4 -o "$tmp/side.pfm"
check "the checker on the focus plane is where the camera saw it" \
  pfm_agree "$tmp/cam-0.pfm" "$tmp/side.pfm" 0.004 0.005
check "the checker fills the barrier's window" pfm_cells "$tmp/ideal.pfm" 8 4 1

# A portrait Looking Glass panel (3:4): the 16:9 frame spans its width, centred.
check "view --display lkg:portrait --display-eye" run 0 view "$tmp/shot.gltf" \
  --display lkg:portrait --display-eye 0,0,500 --spp 1 -o "$tmp/lkg.pfm"
check "the checker spans the panel's width, centred" pfm_cells "$tmp/lkg.pfm" 8 4 1

# --focus-on Probe: the shot framed 15 units away, so the checker (10 units away) fills 10/15
# of the window's width, centred, with the background beside it.
check "view --focus-on Probe" run 0 view "$tmp/shot.gltf" --focus-on Probe \
  --display "$tmp/d169.json" --display-eye 0,0,600 --spp 4 -o "$tmp/probe.pfm"
check "the checker fills 2/3 of the window" pfm_cells "$tmp/probe.pfm" 8 4 0.6666667

# render records --focus-on and the camera fit; simulate's reference frames the scene again as
# the render did (a lost --focus-on would move everything).
check "render --camera ShotCam --focus-on Probe" run 0 render "$tmp/shot.gltf" --camera ShotCam \
  --focus-on Probe --display "$tmp/d169.json" --spp 4 -o "$tmp/r"
check "render.json records the camera, the object and the fit" python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert d["scene_camera"] == "ShotCam" and d["scene_focus_on"] == "Probe", d
assert d["framing"]["fit"] == "camera", d["framing"]
' "$tmp/r/render.json"
dense="--reference --eyes-per-view 1 --distances 1 --reference-spp 4 --json"
check "simulate --reference" run 0 simulate "$tmp/r" $dense -o "$tmp/s.png"
cp "$tmp/out" "$tmp/kept.json"
python3 - "$tmp/r/render.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
del d["scene_focus_on"]
json.dump(d, open(sys.argv[1], "w"))
PY
check "simulate --reference, the object lost" run 0 simulate "$tmp/r" $dense -o "$tmp/n.png"
cp "$tmp/out" "$tmp/lost.json"
check "the reference frames the scene as recorded" python3 -c '
import json, sys
k, n = (json.load(open(f))["mean"]["psnr"] for f in sys.argv[1:3])
assert k > n + 3, (k, n)
' "$tmp/kept.json" "$tmp/lost.json"

# Refusals: one line naming the option, exit 2, nothing written.
check "--focus-on an unknown object" run 2 view "$tmp/shot.gltf" --focus-on Nope -o "$tmp/x.png"
check "it names --focus-on and lists the objects" one_line_naming "--focus-on: no object 'Nope' (the scene's objects: 'Board', 'Probe'"
check "nothing written" test ! -e "$tmp/x.png"
check "--camera unknown" run 2 view "$tmp/shot.gltf" --camera Nope -o "$tmp/x.png"
check "it lists the camera with its node" one_line_naming "0 'Camera.001' (node 'ShotCam')"
check "--fit bogus" run 2 render "$tmp/shot.gltf" --fit bogus --display "$tmp/d169.json" -o "$tmp/x"
check "it lists camera among the fits" one_line_naming "expected window, depth, camera, none or auto"
check "--focus-on a camera (no geometry)" run 2 view "$tmp/shot.gltf" --focus-on ShotCam -o "$tmp/x.png"
cli_summary

#!/usr/bin/env bash
# The scene's look (docs/look.md): --exposure and --view-transform on render and view, the scene
# file's "look", its record in render.json, and simulate's ideal views taking it from there.
# Usage: cli_look_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

cp "$src/tests/fixtures/displays/small-9-views.json" "$tmp/small.json"
# pfm_gain A B: every float of PFM image B is exactly 2 times A's (little-endian floats), and A
# has light.
pfm_gain() {
  python3 -c '
import struct, sys
def floats(path):
    data = open(path, "rb").read()
    parts = data.split(b"\n", 3)
    w, h = map(int, parts[1].split())
    return struct.unpack("<%df" % (3 * w * h), parts[3][: 12 * w * h])
a, b = floats(sys.argv[1]), floats(sys.argv[2])
assert len(a) == len(b) > 0 and max(a) > 0
assert all(y == 2 * x for x, y in zip(a, b)), max(abs(y - 2 * x) for x, y in zip(a, b))
' "$1" "$2"
}
pfm_values() {
  python3 -c '
import struct, sys
data = open(sys.argv[1], "rb").read()
parts = data.split(b"\n", 3)
w, h = map(int, parts[1].split())
print(" ".join("%.9g" % f for f in struct.unpack("<%df" % (3 * w * h), parts[3][: 12 * w * h])))
' "$1"
}

# Exposure alone is a gain of 2^EV on the render's linear light, exactly (the linear image).
check "view linear" run 0 view --spp 4 --size 64x36 -o "$tmp/plain.pfm"
check "view --exposure 1 linear" run 0 view --spp 4 --size 64x36 --exposure 1 -o "$tmp/bright.pfm"
check "exposure 1 doubles every value" pfm_gain "$tmp/plain.pfm" "$tmp/bright.pfm"
# Filmic: nothing clips, every value in [0, 1], and bright light keeps its order.
check "view --view-transform filmic" run 0 view --spp 4 --size 64x36 --exposure 3 \
  --view-transform filmic -o "$tmp/filmic.pfm"
check "filmic keeps values in [0, 1] below white where standard clips" python3 -c '
import sys
bright = [float(v) for v in sys.argv[1].split()]
filmic = [float(v) for v in sys.argv[2].split()]
assert all(0 <= f <= 1 for f in filmic)
assert any(b * 4 > 1 for b in bright)            # standard at +3 EV would clip these
assert all((f1 < f2) == (b1 < b2) or b1 == b2 or f1 == f2
           for b1, f1, b2, f2 in zip(bright, filmic, bright[1:], filmic[1:]))
' "$(pfm_values "$tmp/bright.pfm")" "$(pfm_values "$tmp/filmic.pfm")"

# The scene file's look, and the options over it.
cat >"$tmp/looked.json" <<'JSON'
{"materials": {"clay": {"color": [0.8, 0.6, 0.4]}},
 "objects": [{"shape": "sphere", "center": [0, 0, 0], "radius": 1, "material": "clay"}],
 "lights": [{"type": "point", "position": [0, 3, 4], "intensity": [40, 40, 40]}],
 "look": {"exposure": 1, "view_transform": "standard"}}
JSON
check "a scene file's look" run 0 view "$tmp/looked.json" --spp 1 --size 48x32 -o "$tmp/s1.pfm"
check "the same scene without it, at --exposure 1" run 0 view "$tmp/looked.json" \
  --spp 1 --size 48x32 --exposure 0 -o "$tmp/s0.pfm"
check "the file's exposure is a gain of 2" pfm_gain "$tmp/s0.pfm" "$tmp/s1.pfm"

# Refusals: one line naming the option or the key, exit 2, nothing written.
check "unknown view transform exits 2" run 2 view --view-transform agx -o "$tmp/x.png"
check "it names --view-transform" one_line_naming "--view-transform"
check "nothing written" test ! -e "$tmp/x.png"
check "absurd exposure exits 2" run 2 render --exposure 99 -o "$tmp/x"
check "it names --exposure" one_line_naming "--exposure"
sed 's/"standard"/"log"/' "$tmp/looked.json" >"$tmp/bad.json"
check "a bad look in the file exits 2" run 2 view "$tmp/bad.json" -o "$tmp/x.png"
check "it names the file and the key" one_line_naming "bad.json: /look/view_transform"
sed 's/"exposure": 1/"exposur": 1/' "$tmp/looked.json" >"$tmp/bad2.json"
check "an unknown key in the look exits 2" run 2 view "$tmp/bad2.json" -o "$tmp/x.png"
check "it names the key" one_line_naming "exposur"

# render records the look; simulate's ideal views take it from the record: the reference score
# of a filmic render is as good as a plain one's, and falls when the record loses the look.
check "render plain" run 0 render --display "$tmp/small.json" --spp 4 -o "$tmp/plain"
check "render filmic +2 EV" run 0 render --display "$tmp/small.json" --spp 4 --exposure 2 \
  --view-transform filmic -o "$tmp/looked"
check "render.json records the look" python3 -c '
import json, sys
d = json.load(open(sys.argv[1]))
assert d["look"] == {"exposure": 2.0, "view_transform": "filmic"}, d.get("look")
assert "look" not in json.load(open(sys.argv[2]))
' "$tmp/looked/render.json" "$tmp/plain/render.json"
dense="--reference --eyes-per-view 1 --distances 1 --reference-spp 4 --json"
check "simulate --reference plain" run 0 simulate "$tmp/plain" $dense -o "$tmp/p.png"
cp "$tmp/out" "$tmp/plain.json"
check "simulate --reference filmic" run 0 simulate "$tmp/looked" $dense -o "$tmp/l.png"
cp "$tmp/out" "$tmp/looked.json"
python3 - "$tmp/looked/render.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
del d["look"]
json.dump(d, open(sys.argv[1], "w"))
PY
check "simulate --reference with the look lost" run 0 simulate "$tmp/looked" $dense \
  -o "$tmp/n.png"
cp "$tmp/out" "$tmp/lost.json"
check "the reference takes the recorded look" python3 -c '
import json, sys
p, l, n = (json.load(open(f))["mean"]["psnr"] for f in sys.argv[1:4])
assert abs(l - p) < 3, (p, l, n)      # judged against its own look: as good as plain
assert n < l - 3, (p, l, n)           # against the plain ideal view: far worse
' "$tmp/plain.json" "$tmp/looked.json" "$tmp/lost.json"

cli_summary

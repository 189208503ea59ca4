#!/usr/bin/env bash
# examples/paper/run.sh --display FILE: the paper's experiments on a user's own barrier display
# (a small one here), each experiment's display that file with its one change merged in; and
# its refusals (a missing file, a lenticular panel, a bad file) with exit code 2.
# Usage: paper_user_display_test.sh PARALLAX_BINARY SOURCE_DIR
set -uo pipefail
bin=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

cat >"$tmp/mine.json" <<'JSON'
// A user's own small panel: a finer pitch and another gap than the built-in display's.
{"image_layer": {"resolution": [200, 120], "pixel_pitch_mm": 0.25}, "gap_mm": 2.5,
 "view_distance_mm": 550, "views": 8}
JSON
run="$src/examples/paper/run.sh"
"$run" --display "$tmp/mine.json" --bin "$bin" --out "$tmp/out" >"$tmp/log" 2>&1 ||
  fail "run.sh --display exited $? ($(tail -3 "$tmp/log"))"
[ -s "$tmp/out/gallery.md" ] || fail "no gallery page"
rows=$(grep -c '^| ' "$tmp/out/gallery.md" || true)
[ "$rows" -ge 14 ] || fail "the gallery has $rows table rows, expected the 13 experiments and a header"
# The experiments ran on the user's panel: the simulated eyes have the panel's size.
size=$(python3 -c '
import struct, sys
with open(sys.argv[1], "rb") as f:
    f.read(16)
    w, h = struct.unpack(">II", f.read(8))
print(f"{w}x{h}")' "$tmp/out/angles-0.png" 2>&1)
[ "$size" = "200x120" ] || fail "the simulated eye is $size, expected the panel's 200x120"

"$run" --display "$tmp/missing.json" --bin "$bin" --out "$tmp/o2" >"$tmp/log" 2>&1
code=$?
[ $code -eq 2 ] || fail "a missing display file exited $code"
grep -q 'missing.json' "$tmp/log" || fail "a missing display file is not named: $(cat "$tmp/log")"
"$run" --display lkg:portrait --bin "$bin" --out "$tmp/o3" >"$tmp/log" 2>&1
code=$?
[ $code -eq 2 ] || fail "a lenticular panel exited $code"
echo '{"gap_mm": -3}' >"$tmp/bad.json"
"$run" --display "$tmp/bad.json" --bin "$bin" --out "$tmp/o4" >"$tmp/log" 2>&1
code=$?
[ $code -eq 2 ] || fail "a bad display file exited $code"
grep -q 'bad.json.*gap_mm' "$tmp/log" || fail "a bad display file's key is not named: $(cat "$tmp/log")"
[ ! -e "$tmp/o4/gallery.md" ] || fail "a gallery after a bad display file"

[ $failures -eq 0 ] && echo "paper_user_display: all checks passed"
exit $((failures > 0))

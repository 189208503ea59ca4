#!/usr/bin/env bash
# The command line as a user meets it. Usage: cli_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
bin=$1
src=$2
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
failures=0
passes=0
check() {  # check NAME CONDITION...
  local name=$1
  shift
  if "$@"; then passes=$((passes + 1)); else echo "FAIL: $name" >&2; failures=$((failures + 1)); fi
}
# run EXPECTED_CODE ARGS...: runs the binary, keeps stdout/stderr in $tmp/out and $tmp/err
run() {
  local expected=$1
  shift
  "$bin" "$@" >"$tmp/out" 2>"$tmp/err"
  local code=$?
  if [ "$code" -ne "$expected" ]; then
    echo "exit $code (expected $expected) for: parallax $*" >&2
    cat "$tmp/err" >&2
    return 1
  fi
}
one_line_naming() {  # stderr is exactly one line and contains the text
  [ "$(wc -l <"$tmp/err")" -eq 1 ] && grep -qF -- "$1" "$tmp/err"
}
is_png() { [ "$(head -c 8 "$1" | od -An -tx1 | tr -d ' \n')" = "89504e470d0a1a0a" ]; }

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
  bash -c "grep -q '\"triangles\": 24' '$tmp/out' && grep -q '\"min\"' '$tmp/out'"
check "info on an example scene" run 0 info "$src/scenes/spheres.json"
check "bench --json" run 0 bench --size 64x64 --spp 4 --repeats 1 --json
for key in rays_per_second limit_rays_per_second ratio peak_rss_mb; do
  check "bench reports $key" grep -q "\"$key\"" "$tmp/out"
done

echo "$passes passed, $failures failed"
[ "$failures" -eq 0 ]

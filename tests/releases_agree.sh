#!/usr/bin/env bash
# The same pictures on both Debian releases: the built-in render (`parallax render`, the
# built-in scene and display, as `make run` makes it) and an ordinary picture of the scene
# (`parallax view`, shaded with soft shadows) by this machine's build (build/) and by the other
# release's inside its root (build-RELEASE/, tools/in-debian), picture by picture.
# Byte for byte equal layers pass at once; layers that differ are decoded and compared as
# PSNR, which must reach MIN_PSNR dB (default 50: a few levels on a few pixels), and the
# figures are printed either way. Then bad input, given to both builds, must get the same
# message and the same exit code from each.
#   tests/releases_agree.sh RELEASE [MIN_PSNR]
set -euo pipefail
release=${1:?usage: tests/releases_agree.sh RELEASE [MIN_PSNR]}
min_psnr=${2:-50}
top=$(cd "$(dirname "$0")/.." && pwd)
cd "$top"
here=build/parallax
there=build-$release/parallax
[ -x "$here" ] || { echo "releases_agree: no $here (make build first)" >&2; exit 2; }
[ -x "$there" ] || { echo "releases_agree: no $there (make test-other-debian builds it)" >&2; exit 2; }

# Inside the checkout, which the other release's root sees at the same path.
work=build-$release/releases-agree
rm -rf "$work"
mkdir -p "$work"
# (Their warnings, the same on both, are kept for a failure.)
for side in this "$release"; do
  program=$here run=()
  [ "$side" = this ] || program=$there run=(tools/in-debian "$release" --)
  { "${run[@]}" "$program" render -o "$work/$side" &&
    "${run[@]}" "$program" view --size 480x270 -o "$work/$side/view.png"; } >"$work/$side.log" 2>&1 ||
    { cat "$work/$side.log" >&2; exit 1; }
done

this_release=$( (. /etc/os-release && echo "$VERSION_CODENAME") )
echo "built-in render: $this_release ($("$here" --version)) against $release ($(tools/in-debian "$release" -- "$there" --version))"
status=0
for layer in image.png mask.png view.png; do
  if cmp -s "$work/this/$layer" "$work/$release/$layer"; then
    echo "  $layer: the same bytes"
    continue
  fi
  python3 tests/png_compare.py "$work/this/$layer" "$work/$release/$layer" "$min_psnr" || status=1
done

# Bad input: the same one line and exit code from both releases' builds.
bad=$work/bad
mkdir -p "$bad"
printf 'v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 -4\n' >"$bad/before.obj"
printf 'v 0 0 0\nv 1 0 0\nv nan 1 0\nf 1 2 3\n' >"$bad/nan.obj"
printf '{"panel": {"width_px": 1920,' >"$bad/cut.json"
printf 'solid x\nfacet normal 0 0 1\nouter loop\nvertex 0 0 0\n' >"$bad/short.stl"
mkfifo "$bad/fifo.obj"
cases=(
  "view $bad/missing.obj --size 8x8 -o $bad/x.png"
  "view $bad/before.obj --size 8x8 -o $bad/x.png"
  "view $bad/nan.obj --size 8x8 -o $bad/x.png"
  "view $bad/short.stl --size 8x8 -o $bad/x.png"
  "view $bad/fifo.obj --size 8x8 -o $bad/x.png"
  "render --display $bad/cut.json -o $bad/out"
  "view --size 100000x100000 -o $bad/x.png"
  "bench --camera sideways"
  "PARALLAX_EMBREE_CONFIG=isa=avx-2 @ view --size 8x8 -o $bad/x.png"
)
same=0
for args in "${cases[@]}"; do
  case "$args" in *@*) ;; *) args="@ $args" ;; esac  # @: the program, after any VARIABLE=value
  # shellcheck disable=SC2086  # the cases are word lists
  here_out=$(env ${args/@/$here} 2>&1) && here_code=0 || here_code=$?
  # shellcheck disable=SC2086
  there_out=$(tools/in-debian "$release" -- env ${args/@/$there} 2>&1) && there_code=0 || there_code=$?
  if [ "$here_out" != "$there_out" ] || [ "$here_code" != "$there_code" ]; then
    echo "  $args: $this_release says ($here_code) '$here_out', $release says ($there_code) '$there_out'"
    status=1
  elif [ "$here_code" -ne 2 ]; then
    echo "  $args: exit code $here_code on both, not 2: '$here_out'"
    status=1
  else
    same=$((same + 1))
  fi
done
for left in "$bad/x.png" "$bad/out"; do
  [ ! -e "$left" ] || { echo "  a refused command left $left"; status=1; }
done
echo "  bad input: $same of ${#cases[@]} cases give the same message and exit code 2 on both"
exit $status

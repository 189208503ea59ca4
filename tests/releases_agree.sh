#!/usr/bin/env bash
# The same pictures on both Debian releases: the built-in render (`parallax render`, the
# built-in scene and display, as `make run` makes it) by this machine's build (build/) and by
# the other release's inside its root (build-RELEASE/, tools/in-debian), layer by layer.
# Byte for byte equal layers pass at once; layers that differ are decoded and compared as
# PSNR, which must reach MIN_PSNR dB (default 50: a few levels on a few pixels), and the
# figures are printed either way.
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
"$here" render -o "$work/this" >/dev/null
tools/in-debian "$release" -- "$there" render -o "$work/$release" >/dev/null

this_release=$( (. /etc/os-release && echo "$VERSION_CODENAME") )
echo "built-in render: $this_release ($("$here" --version)) against $release ($(tools/in-debian "$release" -- "$there" --version))"
status=0
for layer in image.png mask.png; do
  if cmp -s "$work/this/$layer" "$work/$release/$layer"; then
    echo "  $layer: the same bytes"
    continue
  fi
  python3 tests/png_compare.py "$work/this/$layer" "$work/$release/$layer" "$min_psnr" || status=1
done
exit $status

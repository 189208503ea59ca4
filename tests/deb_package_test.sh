#!/usr/bin/env bash
# CPack's Debian package: its dependencies are Debian runtime packages (read off the binaries by
# dpkg-shlibdeps), each one a package this machine has installed, none of them a -dev package;
# it holds the CLI, the library, the CMake and pkg-config files; and the CLI unpacked from it
# runs and renders.
#   deb_package_test.sh BUILD_DIR
set -euo pipefail
build=$(cd "$1" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

(cd "$work" && cpack --config "$build/CPackConfig.cmake" -G DEB -B "$work/out" >"$work/cpack.log" 2>&1) ||
  { cat "$work/cpack.log" >&2; fail "cpack -G DEB failed"; }
deb=$(ls "$work"/out/parallax_*_amd64.deb 2>/dev/null | head -1)
[ -n "$deb" ] || fail "no .deb written"

depends=$(dpkg-deb -f "$deb" Depends)
[ -n "$depends" ] || fail "the package has no Depends"
for needed in libembree3-3 libtbb12 libavcodec libassimp libc6 libstdc++6; do
  grep -q "$needed" <<<"$depends" || fail "Depends lacks $needed: $depends"
done
for entry in $(tr ',' '\n' <<<"$depends" | sed 's/(.*)//; s/ //g'); do
  case "$entry" in *-dev) fail "Depends names a development package: $entry" ;; esac
  dpkg-query -W -f='${Status}' "$entry" 2>/dev/null | grep -q "install ok installed" ||
    fail "Depends names $entry, which is not an installed Debian package"
done

contents=$(dpkg-deb -c "$deb" | awk '{print $6}')
# With the Python module inside, numpy (which it imports) is recommended.
if grep -q "/dist-packages/parallax/__init__.py$" <<<"$contents"; then
  dpkg-deb -f "$deb" Recommends | grep -q python3-numpy ||
    fail "the package holds the Python module but does not recommend python3-numpy"
fi
for file in ./usr/bin/parallax ./usr/lib/libparallax.so.0 ./usr/include/parallax/render/render.h \
            ./usr/lib/cmake/parallax/parallaxConfig.cmake ./usr/lib/pkgconfig/parallax.pc \
            ./usr/share/doc/parallax/README.md ./usr/share/doc/parallax/examples/library/main.cpp; do
  grep -qxF "$file" <<<"$contents" || fail "the package lacks $file"
done

dpkg-deb -x "$deb" "$work/root"
"$work/root/usr/bin/parallax" view --size 32x18 -o "$work/view.png" >/dev/null 2>&1 ||
  fail "the packaged CLI does not render"
[ -s "$work/view.png" ] || fail "the packaged CLI wrote no picture"
echo "deb: $(basename "$deb"), $(wc -w <<<"$contents") files, depends on $(tr ',' '\n' <<<"$depends" | wc -l) runtime packages"

#!/usr/bin/env bash
# CPack's Debian package: its dependencies are Debian runtime packages (read off the binaries by
# dpkg-shlibdeps), each one a package this machine has installed, none of them a -dev package,
# and among them the very packages that hold the libraries the build linked (libembree3-3 or
# libembree4-4, libavcodec59 or libavcodec61, ...: this release's own, asked of dpkg);
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
# The package that holds a shared library the build's libparallax.so loads (ldd), per dpkg.
owner() {
  local path
  path=$(ldd "$build/lib/libparallax.so" | awk -v lib="$1" 'index($1, lib ".so") == 1 {print $3; exit}')
  [ -n "$path" ] || fail "libparallax.so does not load $1"
  # Merged /usr: dpkg knows a file by the path its package ships, /usr/lib/... or /lib/...
  local real
  real=$(readlink -f "$path")
  { dpkg -S "$real" 2>/dev/null || dpkg -S "${real#/usr}" 2>/dev/null; } | head -1 | cut -d: -f1
}
for library in libembree3 libembree4 libtbb libavcodec libassimp libc libstdc++; do
  case "$library" in  # one Embree or the other, whichever the build found
    libembree*) ldd "$build/lib/libparallax.so" | grep -q "^\s*$library[.]so" || continue ;;
  esac
  package=$(owner "$library")
  [ -n "$package" ] || fail "dpkg knows no package holding $library"
  tr ',' '\n' <<<"$depends" | sed 's/(.*)//; s/ //g' | grep -qxF "$package" || fail "Depends lacks $package ($library): $depends"
  echo "depends on $package for $library"
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

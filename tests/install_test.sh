#!/usr/bin/env bash
# `cmake --install` into a temporary prefix as a user would, then the two ways of using it:
# examples/library built with find_package(parallax) and again with pkg-config, each run and its
# picture compared byte for byte with the installed CLI's `parallax view` of the same camera (the
# library and the CLI are one code, two paths to it). Also: the headers compile on their own, the
# installed docs and examples are there, and nothing of the build tree is needed (moved prefix).
#   install_test.sh BUILD_DIR SOURCE_DIR [CONSUMER_FLAGS]
# CONSUMER_FLAGS: compile and link flags of the consumers, e.g. the sanitizers of a sanitized
# build (a program loading an ASan library must itself be built with ASan).
set -euo pipefail
consumer_flags=${3:-}
build=$(cd "$1" && pwd)
source=$(cd "$2" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

cmake --install "$build" --prefix "$work/staging" >/dev/null
# A moved prefix: everything must still be found relative to where it is now.
mv "$work/staging" "$work/prefix"
prefix="$work/prefix"
libdir=$(cd "$prefix" && ls -d lib*/ | head -1); libdir=${libdir%/}
[ -x "$prefix/bin/parallax" ] || fail "bin/parallax not installed"
[ -f "$prefix/$libdir/libparallax.so" ] || fail "libparallax.so not installed"
[ -f "$prefix/include/parallax/render/render.h" ] || fail "headers not installed"
[ -f "$prefix/$libdir/cmake/parallax/parallaxConfig.cmake" ] || fail "CMake package not installed"
[ -f "$prefix/$libdir/pkgconfig/parallax.pc" ] || fail "pkg-config file not installed"
[ -f "$prefix/share/doc/parallax/README.md" ] || fail "README not installed"
[ -f "$prefix/share/doc/parallax/docs/install.md" ] || fail "docs not installed"
[ -f "$prefix/share/doc/parallax/examples/library/main.cpp" ] || fail "examples not installed"
if ls "$prefix/include/parallax"/*/*_test_support.h >/dev/null 2>&1; then
  fail "test-only headers installed"
fi

# Every installed header compiles alone against the installed tree (no third-party header, no
# header of the source tree needed).
check_header() {
  local relative=${1#"$2/include/"}
  printf '#include "%s"\n' "$relative" | c++ -std=c++20 -fsyntax-only -I"$2/include" -x c++ - ||
    { echo "FAIL: $relative does not compile on its own when installed" >&2; return 1; }
}
export -f check_header
printf '%s\n' "$prefix"/include/parallax/*/*.h |
  xargs -P "$(nproc)" -I{} bash -c 'check_header "$1" "$2"' _ {} "$prefix" ||
  fail "installed headers do not compile on their own"

# The CLI's picture, the truth both consumers must give byte for byte.
camera=(48 27 0 0.4 3.2 0 0.3 0 40)
"$prefix/bin/parallax" view --eye 0,0.4,3.2 --look-at 0,0.3,0 --up 0,1,0 --fov 40 --size 48x27 \
  --spp 1 -o "$work/cli.pfm" >/dev/null 2>&1 || fail "installed parallax view failed"

# 1. CMake: find_package(parallax) -> parallax::parallax.
cp -r "$prefix/share/doc/parallax/examples/library" "$work/consumer"
cmake -S "$work/consumer" -B "$work/consumer-build" -G Ninja -DCMAKE_PREFIX_PATH="$prefix" \
  -DCMAKE_CXX_FLAGS="$consumer_flags" -DCMAKE_EXE_LINKER_FLAGS="$consumer_flags" \
  >"$work/cmake.log" 2>&1 || { cat "$work/cmake.log" >&2; fail "find_package(parallax) failed"; }
cmake --build "$work/consumer-build" >"$work/build.log" 2>&1 ||
  { cat "$work/build.log" >&2; fail "the consumer did not build against parallax::parallax"; }
"$work/consumer-build/view" "$work/cmake.pfm" "${camera[@]}" | grep -q "^1296 camera rays$" ||
  fail "the CMake consumer did not trace 48 x 27 rays"
cmp "$work/cli.pfm" "$work/cmake.pfm" || fail "the CMake consumer's picture differs from the CLI's"

# 2. pkg-config.
export PKG_CONFIG_PATH="$prefix/$libdir/pkgconfig"
[ "$(pkg-config --modversion parallax)" = "$(grep -oP 'project\(parallax VERSION \K[0-9.]+' "$source/CMakeLists.txt")" ] ||
  fail "pkg-config version is not the project's"
c++ $consumer_flags "$work/consumer/main.cpp" $(pkg-config --cflags --libs parallax) -o "$work/view-pc" ||
  fail "the consumer did not build with pkg-config"
"$work/view-pc" "$work/pc.pfm" "${camera[@]}" >/dev/null
cmp "$work/cli.pfm" "$work/pc.pfm" || fail "the pkg-config consumer's picture differs from the CLI's"

# The consumer needs none of the library's own dependencies to link (they are private to it).
if grep -q -E "embree|tbb|avcodec|assimp" "$work/consumer-build/build.ninja"; then
  fail "a consumer links the library's third-party dependencies"
fi
echo "install: prefix, find_package, pkg-config and the CLI agree"

#!/usr/bin/env bash
# tools/in-debian refuses what it cannot run, before it makes or enters any root: a usage error
# is exit code 2 and one line naming what is wrong, and nothing is made. (Its real work, a
# Debian 13 root running `make run` and the Release suite, is `make test-other-debian`, which
# .ci/run runs on every stop.)
#   in_debian_usage_test.sh SOURCE_DIR
set -uo pipefail
tool=$1/tools/in-debian
roots=$(mktemp -d)
trap 'rm -rf "$roots"' EXIT
export PARALLAX_DEBIAN_ROOTS=$roots/roots
fail() { echo "FAIL: $*" >&2; exit 1; }
expect_usage_error() {
  local expected=$1
  shift
  local out code
  out=$("$tool" "$@" 2>&1) && code=0 || code=$?
  [ "$code" -eq 2 ] || fail "in-debian $*: exit code $code, not 2 ($out)"
  [ "$(wc -l <<<"$out")" -eq 1 ] || fail "in-debian $*: more than one line: $out"
  grep -qF -- "$expected" <<<"$out" || fail "in-debian $*: '$out' lacks '$expected'"
}
expect_usage_error "usage: tools/in-debian RELEASE"
expect_usage_error "usage: tools/in-debian RELEASE" trixie
expect_usage_error "put -- before the command: tools/in-debian trixie -- make test" trixie make test
expect_usage_error "usage: tools/in-debian RELEASE" trixie --
expect_usage_error "unknown option '--fast'" trixie --fast -- true
expect_usage_error "'13' is not a Debian release name" 13 -- true
help=$("$tool" --help) || fail "in-debian --help failed"
grep -qF "tools/in-debian RELEASE [--fresh] -- COMMAND" <<<"$help" || fail "--help lacks the usage: $help"
[ ! -e "$PARALLAX_DEBIAN_ROOTS" ] || fail "a refused call made $PARALLAX_DEBIAN_ROOTS"
echo "in-debian: --help, and 6 usage errors refused with exit code 2, nothing made"

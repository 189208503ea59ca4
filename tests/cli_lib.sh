# Shared by the command-line test scripts: `source "$(dirname "$0")/cli_lib.sh" BINARY SOURCE_DIR`
# sets bin, src and a temporary folder tmp (removed on exit), and defines the checks below.
# Each script ends with `cli_summary`, which prints "N passed, M failed" and sets the exit code.
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
png_size() {  # WIDTHxHEIGHT from the IHDR chunk
  od -An -tu1 -j16 -N8 "$1" | awk '{printf "%dx%d", $1*16777216+$2*65536+$3*256+$4,
                                                    $5*16777216+$6*65536+$7*256+$8}'
}
cli_summary() {
  echo "$passes passed, $failures failed"
  [ "$failures" -eq 0 ]
}

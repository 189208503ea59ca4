#!/usr/bin/env bash
# tools/compile-launcher and tools/compile-times against figures made by hand: the launcher's log
# line for one compile, the sum and median of a made-up tree, and --check failing on the file
# over the ratio (naming it) and passing below it. (The real tree's check is the compile_times
# test.)
#   compile_times_test.sh SOURCE_DIR
set -uo pipefail
tools=$1/tools
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

# The launcher: runs the command, keeps its exit code, logs "USER SYSTEM OUTPUT" for an output.
echo 'int answer() { return 42; }' >"$work/answer.cpp"
"$tools/compile-launcher" "$work/launcher.log" c++ -c "$work/answer.cpp" -o "$work/answer.o" ||
  fail "the launcher did not compile"
[ -f "$work/answer.o" ] || fail "the launcher wrote no object"
grep -Eq "^[0-9]+m[0-9]+\.[0-9]+s [0-9]+m[0-9]+\.[0-9]+s $work/answer.o\$" "$work/launcher.log" ||
  fail "the launcher's log line: $(cat "$work/launcher.log")"
"$tools/compile-launcher" "$work/launcher.log" false && fail "the launcher hid a failure"
[ "$(wc -l <"$work/launcher.log")" -eq 1 ] || fail "a failed command was logged"

# A tree of five objects: 1, 1, 2, 3 s and one of 1m2.5s (62.5 s); the median is 2 s.
tree=$work/tree
mkdir -p "$tree/src/parallax/io/CMakeFiles/parallax_io.dir"
dir=src/parallax/io/CMakeFiles/parallax_io.dir
for name in a b c d slow; do touch "$tree/$dir/$name.cpp.o"; done
{
  echo "0m0.900s 0m0.100s $dir/a.cpp.o"
  echo "0m1.000s 0m0.000s $dir/b.cpp.o"
  echo "0m1.500s 0m0.500s $dir/c.cpp.o"
  echo "0m3.000s 0m0.000s $dir/d.cpp.o"
  echo "1m2.000s 0m0.500s $dir/slow.cpp.o"
  echo "0m9.000s 0m0.000s $dir/gone.cpp.o"  # no longer in the tree: not counted
} >"$tree/compile_times.log"
out=$("$tools/compile-times" "$tree" --top 1) || fail "compile-times failed: $out"
grep -qF "5 objects and 0 precompiled headers: 70 CPU seconds of compiling (serial), median 2.00 s, slowest 62.5 s" <<<"$out" ||
  fail "the summary: $out"
grep -qE "62\.50 s +31\.2x +io/slow\.cpp" <<<"$out" || fail "the slowest file: $out"
out=$("$tools/compile-times" "$tree" --check 30 2>&1) && fail "--check 30 passed a file 31 times the median"
grep -qF "io/slow.cpp took 62.5 s, 31.2 times the median 2.00 s (at most 30)" <<<"$out" ||
  fail "--check's message: $out"
"$tools/compile-times" "$tree" --check 32 >/dev/null || fail "--check 32 failed a file 31 times the median"
out=$("$tools/compile-times" "$work/none" 2>&1) && fail "a tree with no logs passed"
grep -qF ".ninja_log" <<<"$out" || fail "no log: $out"
echo "compile_times_test: all checks passed"

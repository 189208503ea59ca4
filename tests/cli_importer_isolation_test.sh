#!/usr/bin/env bash
# Files that crash or exhaust assimp (issue 28, fuzz/regressions/fuzz_assimp) end to end: the
# importer runs in a child process (docs/import.md, "Isolation"), so `info` and `render` exit
# 2 with one line on stderr naming the file and what happened, and write nothing.
# Usage: cli_importer_isolation_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

files="$src/fuzz/regressions/fuzz_assimp"
# The Collada file grows without bound: a 1 GiB budget keeps the test small and quick.
limit=(--max-memory 1)
# Debian 12's assimp (5.2) frees twice reading the FBX; 5.4 (Debian 13's 5.4.3) reads it, and
# then it is an ordinary model (`parallax --version` names the assimp it runs).
assimp=$("$bin" --version | sed -n 's/.*assimp \([0-9]*\)\.\([0-9]*\)\..*/\1 \2/p')
check "--version names assimp" test -n "$assimp"
read -r major minor <<<"$assimp"
cases=()
if [ "${major:-0}" -lt 5 ] || { [ "${major:-0}" -eq 5 ] && [ "${minor:-0}" -lt 4 ]; }; then
  cases+=("crash-2c65eb78.fbx|the FBX importer (assimp) crashed reading it (")
else
  check "info crash-2c65eb78.fbx (assimp $major.$minor reads it): exit 0" run 0 info \
    "$files/crash-2c65eb78.fbx"
fi
cases+=("crash-cb1d3a87.x|the X importer (assimp) crashed reading it (signal 11, SIGSEGV)"
        "timeout-25565c.dae|the DAE importer (assimp) ran out of its memory budget reading it (1 GiB, --max-memory)")
for case in "${cases[@]}"; do
  file=${case%%|*}
  message=${case#*|}
  check "info $file: exit 2" run 2 "${limit[@]}" info "$files/$file"
  check "info $file: one line naming the file and what happened" \
    one_line_naming "$files/$file: $message"
  check "render $file: exit 2" run 2 "${limit[@]}" render "$files/$file" --spp 1 \
    -o "$tmp/out-$file"
  check "render $file: one line naming the file" one_line_naming "$files/$file: $message"
  check "render $file: no output folder" test ! -e "$tmp/out-$file"
done
# A file assimp reads still loads (through the child): a DirectX triangle.
printf 'xof 0303txt 0032\nMesh {\n 3;\n 0.0;0.0;0.0;,\n 1.0;0.0;0.0;,\n 0.0;1.0;0.0;;\n 1;\n 3;0,1,2;;\n}\n' \
  >"$tmp/triangle.x"
check "info triangle.x: exit 0" run 0 info "$tmp/triangle.x"
check "info triangle.x: one triangle" grep -q "^triangles 1 in 1 meshes" "$tmp/out"
cli_summary

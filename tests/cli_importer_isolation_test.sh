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
for case in "crash-2c65eb78.fbx|the FBX importer (assimp) crashed reading it (" \
            "crash-cb1d3a87.x|the X importer (assimp) crashed reading it (signal 11, SIGSEGV)" \
            "timeout-25565c.dae|the DAE importer (assimp) ran out of its memory budget reading it (1 GiB, --max-memory)"; do
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

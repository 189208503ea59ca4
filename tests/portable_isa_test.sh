#!/usr/bin/env bash
# A portable build runs on any x86-64 CPU: no function of ours may use an AVX instruction (VEX
# or EVEX encoded: every mnemonic starting with v, every ymm/zmm/k register) except the ISA
# clones of the lane kernels (core/lane_kernel.h: "[clone .arch_x86_64_v3]" and "_v4"), which
# run only where the CPU has them, and the few functions written for AVX-512 alone, named
# ...Avx512..., which their callers run only after asking the CPU (core/lane_kernel.h). Checked
# on the disassembly of the CLI and libparallax.so; also checks that the clones exist, so that
# the dispatch is really there.
#   portable_isa_test.sh BINARY...
set -euo pipefail
status=0
for binary in "$@"; do
  report=$(objdump -d -C --no-show-raw-insn "$binary" | awk '
    /^[0-9a-f]+ <.*>:$/ { name = substr($0, index($0, "<") + 1); sub(/>:$/, "", name); next }
    /^ *[0-9a-f]+:\t/ {
      split($0, parts, "\t"); instruction = parts[2]
      avx = instruction ~ /^v[a-z]/ || instruction ~ /%[yz]mm[0-9]/ || instruction ~ /%k[0-7]/
      if (!avx) next
      if (name ~ /\[clone \.arch_x86_64_v[34]\]/) { clones[name] = 1; next }
      if (name ~ /Avx512[A-Za-z]*[<(]/) next
      if (!(name in bad)) { bad[name] = instruction; order[++n] = name }
    }
    END {
      for (i = 1; i <= n; ++i) printf "AVX outside a clone: %s: %s\n", order[i], bad[order[i]]
      printf "clones %d\n", length(clones)
    }')
  clones=$(grep -oP '^clones \K[0-9]+' <<<"$report")
  if grep -q "^AVX outside a clone" <<<"$report"; then
    grep "^AVX outside a clone" <<<"$report" | head -20 >&2
    echo "FAIL: $binary uses AVX outside the lane kernels' clones" >&2
    status=1
  fi
  if [ "$clones" -lt 10 ]; then
    echo "FAIL: $binary has $clones AVX clones of the lane kernels; the dispatch is missing" >&2
    status=1
  fi
  echo "$(basename "$binary"): no AVX outside $clones lane-kernel clones"
done
exit $status

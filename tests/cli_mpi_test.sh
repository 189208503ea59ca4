#!/usr/bin/env bash
# parallax under mpirun (docs/distributed.md): a sequence's frames shared among 1, 2 and 3 ranks,
# one frame split by bands of rows (the built-in barrier display, a lenticular panel, a quilt,
# an ordinary view), each byte for byte the same as one process's; a rank that fails alone
# fails the run with its one-line message, exit code 2 and no output.
# Usage: cli_mpi_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"

# CI runs as root in a container without a network: Open MPI must be allowed to run as root, and
# kept to shared memory within this machine (no cross-memory attach, which containers forbid).
# Three ranks on two cores is oversubscription. An ASan build: Open MPI's own allocations at
# MPI_Init are never freed, so leak checking is off for the ranks (not for the one-process runs).
export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
export OMPI_MCA_btl=self,vader OMPI_MCA_btl_vader_single_copy_mechanism=none
export OMPI_MCA_rmaps_base_oversubscribe=1 OMPI_MCA_hwloc_base_binding_policy=none
export OMPI_MCA_mpi_yield_when_idle=1  # ranks that wait yield the (shared) cores
# mpi EXPECTED_CODE NP ARGS...: parallax under mpirun -np NP, output in $tmp/out and $tmp/err.
mpi() {
  local expected=$1 np=$2
  shift 2
  ASAN_OPTIONS="${ASAN_OPTIONS:+$ASAN_OPTIONS:}detect_leaks=0" \
    mpirun -np "$np" --oversubscribe "$bin" "$@" >"$tmp/out" 2>"$tmp/err"
  local code=$?
  if [ "$code" -ne "$expected" ]; then
    echo "exit $code (expected $expected) for: mpirun -np $np parallax $*" >&2
    cat "$tmp/err" >&2
    return 1
  fi
}
failing() {  # failing RANK EXPECTED_CODE NP ARGS...: mpi with rank RANK made to fail
  local rank=$1
  shift
  PARALLAX_TEST_FAIL_RANK=$rank mpi "$@"
}
same_files() {  # same_files DIR1 DIR2 FILE...: every FILE byte for byte the same in both
  local a=$1 b=$2
  shift 2
  for f in "$@"; do cmp -s "$a/$f" "$b/$f" || { echo "differs: $f" >&2; return 1; }; done
}

cp "$src/tests/fixtures/displays/small-9-views.json" "$tmp/small.json"

# (a) A sequence: 5 frames over 1, 2 and 3 ranks (3 ranks: 2, 2 and 1 frames).
turn=(render --display "$tmp/small.json" --spp 4 --turntable 90 --duration 0.25 --fps 20)
check "a sequence in one process" run 0 "${turn[@]}" -o "$tmp/seq"
frames=()
for k in 1 2 3 4 5; do frames+=("frame-000$k/image.png" "frame-000$k/mask.png"); done
for np in 1 2 3; do
  check "a sequence on $np ranks" mpi 0 "$np" "${turn[@]}" -o "$tmp/seq$np"
  check "its frames are one process's ($np ranks)" same_files "$tmp/seq" "$tmp/seq$np" "${frames[@]}"
  check "every rank renders its frames ($np ranks)" \
    test "$(grep -c '^frame [0-9]* (rank' "$tmp/out")" -eq "$((np > 1 ? 5 : 0))"
done
# The video is made once, by rank 0, after every rank has written its frames.
check "a sequence and its video on 3 ranks" mpi 0 3 "${turn[@]}" -o "$tmp/seqv" --video "$tmp/seqv.mp4"
check "the video is written" test -s "$tmp/seqv.mp4"
check "frames resumed by ranks: nothing left to render" mpi 0 2 "${turn[@]}" -o "$tmp/seqv"
check "nothing rendered again" grep -q "0 to render" "$tmp/out"

# Farms without MPI: --chunk K/N takes the K-th of N contiguous parts (docs/distributed.md).
for k in 3 1 2; do check "chunk $k/3" run 0 "${turn[@]}" --chunk "$k/3" -o "$tmp/chunks"; done
check "the chunks make one process's frames" same_files "$tmp/seq" "$tmp/chunks" "${frames[@]}"
check "a chunk with no frame (7 parts of 5 frames) does nothing" run 0 "${turn[@]}" --chunk 1/7 -o "$tmp/empty"
check "no frame in an empty chunk" test -z "$(ls "$tmp/empty" 2>/dev/null)"
check "chunks of --frames" run 0 "${turn[@]}" --frames 2:5 --chunk 2/2 -o "$tmp/part"
check "the second half of 2:5 is frames 4 and 5" test "$(ls "$tmp/part" | tr '\n' ' ')" = "frame-0004 frame-0005 "
for bad in 0/3 4/3 3 1/0 x/2; do
  check "--chunk $bad refused" run 2 "${turn[@]}" --chunk "$bad" -o "$tmp/bad"
  check "--chunk $bad: one line naming it" one_line_naming "--chunk"
done
check "no video of a chunk" run 2 "${turn[@]}" --chunk 1/2 --video "$tmp/chunk.mp4" -o "$tmp/bad"
check "--video with --chunk: one line" one_line_naming "--video"
check "no output of refused chunks" test ! -e "$tmp/bad"

# (b) One frame of the built-in display, split by bands of rows (with --adaptive too: a pixel
# stops on its own packet's samples, all in its band).
for variant in "--spp 4" "--spp 9 --adaptive" "--spp 4 --subpixels"; do
  read -ra opts <<<"$variant"
  check "one frame ($variant)" run 0 render "${opts[@]}" -o "$tmp/one"
  for np in 2 3; do
    rm -rf "$tmp/split"
    check "one frame on $np ranks ($variant)" mpi 0 "$np" render "${opts[@]}" -o "$tmp/split"
    check "the same layers ($np ranks, $variant)" same_files "$tmp/one" "$tmp/split" image.png mask.png
    check "the output set once ($np ranks)" test "$(grep -c '^wrote' "$tmp/out")" -eq 1
    check "the depth summary once ($np ranks)" test "$(grep -c '^depth' "$tmp/out")" -eq 1
  done
  rm -rf "$tmp/one"
done
python3 - "$tmp/split/render.json" <<'PY' || check "the rays of all ranks recorded" false
import json, sys
r = json.load(open(sys.argv[1]))
# 1920x1080 subpixel film: 3 columns per pixel, 4 camera rays each, whatever the ranks.
assert r["rays"] >= 3 * 1920 * 1080 * 4, r["rays"]
PY

# The usual practice (N views interleaved) splits too; the layer solvers run on rank 0 alone.
check "direct mapping" run 0 render --display "$tmp/small.json" --direct-mapping --spp 4 -o "$tmp/dm"
check "direct mapping on 3 ranks" mpi 0 3 render --display "$tmp/small.json" --direct-mapping --spp 4 -o "$tmp/dm3"
check "the same interleaved layer" same_files "$tmp/dm" "$tmp/dm3" image.png mask.png
check "optimised layers" run 0 render --display "$tmp/small.json" --layers optimized-image --spp 4 --iterations 2 -o "$tmp/opt"
check "optimised layers on 2 ranks" mpi 0 2 render --display "$tmp/small.json" --layers optimized-image --spp 4 --iterations 2 -o "$tmp/opt2"
check "the same optimised layers" same_files "$tmp/opt" "$tmp/opt2" image.png mask.png
check "a note that rank 0 solves alone" grep -q "not split across ranks" "$tmp/err"

# (c) A lenticular panel's picture and a Looking Glass quilt, split.
check "a lenticular picture" run 0 render --display lkg:go --spp 1 -o "$tmp/lent"
check "a quilt" run 0 render --display lkg:go --quilt auto --spp 1 -o "$tmp/quilt"
quilt=$(cd "$tmp/quilt" && ls quilt_qs*.png)
for np in 2 3; do
  check "a lenticular picture on $np ranks" mpi 0 "$np" render --display lkg:go --spp 1 -o "$tmp/lent$np"
  check "the same picture ($np ranks)" same_files "$tmp/lent" "$tmp/lent$np" image.png
  check "a quilt on $np ranks" mpi 0 "$np" render --display lkg:go --quilt auto --spp 1 -o "$tmp/quilt$np"
  check "the same quilt ($np ranks)" same_files "$tmp/quilt" "$tmp/quilt$np" "$quilt"
done
# An ordinary view, and a non-multiple-of-16 height (the last band is short).
check "a view" run 0 view --size 200x75 --spp 4 -o "$tmp/view.png"
check "a view on 3 ranks" mpi 0 3 view --size 200x75 --spp 4 -o "$tmp/view3.png"
check "the same view" cmp -s "$tmp/view.png" "$tmp/view3.png"

# A rank that fails alone (as one that meets bad input only it sees): the run fails with that
# rank's one line, exit code 2, and no output at all, for one frame and for a sequence.
for np in 2 3; do
  check "rank 1 of $np fails one frame" failing 1 2 "$np" render --spp 4 -o "$tmp/failed"
  check "its message once ($np ranks)" test "$(grep -c '^error: ' "$tmp/err")" -eq 1
  check "naming the failure ($np ranks)" grep -q "^error: PARALLAX_TEST_FAIL_RANK: rank 1 was asked to fail" "$tmp/err"
  check "no output ($np ranks)" test ! -e "$tmp/failed"
  check "rank $((np - 1)) of $np fails a sequence" failing $((np - 1)) 2 "$np" "${turn[@]}" \
    -o "$tmp/failedseq" --video "$tmp/failed.mp4"
  check "its message once (sequence, $np ranks)" test "$(grep -c '^error: ' "$tmp/err")" -eq 1
  check "no frame written ($np ranks)" test ! -e "$tmp/failedseq"
  check "no video ($np ranks)" test ! -e "$tmp/failed.mp4"
done
check "bad input seen by every rank: one line" mpi 2 2 render "$tmp/missing.obj" -o "$tmp/failed"
check "the missing file named once" test "$(grep -c '^error: .*missing.obj' "$tmp/err")" -eq 1
check "no output (missing file)" test ! -e "$tmp/failed"

cli_summary

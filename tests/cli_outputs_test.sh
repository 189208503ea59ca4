#!/usr/bin/env bash
# Outputs from the command line (docs/inputs.md, "Outputs"): a set replaces only the files
# parallax wrote, keeps the folder's mode, group and ACL, and is refused before any work when a
# name is taken by the user's folder or file or the folder cannot be written; --video's folder and
# the encoder's size limits are checked before the frames are rendered; killed runs' temporary
# files go.
# Read-only folders are tested as `nobody` when this runs as root: root's override of the
# permission bits would write them, and the test would prove nothing.
# Usage: cli_outputs_test.sh PARALLAX_BINARY SOURCE_DIR
set -u
source "$(dirname "$0")/cli_lib.sh" "$1" "$2"
chmod 755 "$tmp"  # `nobody` enters it

cp "$src/tests/fixtures/displays/small-9-views.json" "$tmp/small.json"
as_user() {  # as_user EXPECTED_CODE ARGS...: run, as `nobody` when root
  local expected=$1
  shift
  if [ "$(id -u)" -eq 0 ]; then
    setpriv --reuid=65534 --regid=65534 --clear-groups "$bin" "$@" >"$tmp/out" 2>"$tmp/err"
  else
    "$bin" "$@" >"$tmp/out" 2>"$tmp/err"
  fi
  local code=$?
  [ "$code" -eq "$expected" ] || { echo "exit $code (expected $expected): parallax $*" >&2; cat "$tmp/err" >&2; return 1; }
}
listing() { (cd "$1" && find . -printf '%p %s %m %u %g %T@\n' | sort); }
fast=(--display "$tmp/small.json" --spp 1)

# ---- The user's folder or file with an output name: refused before rendering, kept ----------
mkdir -p "$tmp/d/mask.png"
echo mine >"$tmp/d/mask.png/mine.txt"
check "a folder named mask.png is refused" run 2 render "${fast[@]}" -o "$tmp/d"
check "names it and says why" one_line_naming "d/mask.png: is a folder (not written by parallax); parallax replaces only files it wrote"
check "and the option" grep -qF -- "--output" "$tmp/err"
check "the user's folder and file are there" grep -q mine "$tmp/d/mask.png/mine.txt"
check "refused before rendering: nothing written" test "$(ls -A "$tmp/d")" = "mask.png"
check "no depth summary: the scene was not loaded" bash -c "! grep -q 'depth' '$tmp/out'"

mkdir -p "$tmp/e"
echo "my picture" >"$tmp/e/image.png"
check "a file not written by parallax is refused" run 2 render "${fast[@]}" -o "$tmp/e"
check "names it" one_line_naming "e/image.png: is a file not written by parallax"
check "the user's file is unchanged" grep -q "my picture" "$tmp/e/image.png"

# ---- Our own files are replaced; the others and the folder stay as they are -------------------
mkdir -p "$tmp/shared"
chmod 2775 "$tmp/shared"
group=$(id -gn)
if [ "$(id -u)" -eq 0 ]; then chgrp adm "$tmp/shared" && chmod 2775 "$tmp/shared" && group=adm; fi
# An ACL (nobody: rwx) set through the kernel's xattr, as setfacl would.
python3 - "$tmp/shared" <<'PY'
import os, struct, sys
e = [(1, 7, 0xffffffff), (2, 7, 65534), (4, 5, 0xffffffff), (0x10, 7, 0xffffffff), (0x20, 5, 0xffffffff)]
acl = struct.pack('<I', 2) + b''.join(struct.pack('<HHI', *x) for x in e)
os.setxattr(sys.argv[1], 'system.posix_acl_access', acl)
PY
acl() { python3 -c 'import os, sys; print(os.getxattr(sys.argv[1], "system.posix_acl_access").hex())' "$1"; }
acl_before=$(acl "$tmp/shared")
inode=$(stat -c %i "$tmp/shared")
echo notes >"$tmp/shared/notes.txt"
check "render into a shared folder" run 0 render "${fast[@]}" -o "$tmp/shared"
check "render again" run 0 render "${fast[@]}" --seed 5 -o "$tmp/shared"
check "the second set is there" grep -q '"seed": 5' "$tmp/shared/render.json"
check "the folder is the same folder" test "$(stat -c %i "$tmp/shared")" = "$inode"
check "its mode is kept (2775)" test "$(stat -c %a "$tmp/shared")" = 2775
check "its group is kept ($group)" test "$(stat -c %G "$tmp/shared")" = "$group"
check "the new files have its group" test "$(stat -c %G "$tmp/shared/image.png")" = "$group"
check "its ACL is kept" test "$(acl "$tmp/shared")" = "$acl_before"
check "the user's notes stay" grep -q notes "$tmp/shared/notes.txt"
check "no temporaries left" bash -c "! find '$tmp/shared' '$tmp' -mindepth 1 -maxdepth 1 -name '*tmp*' | grep -q ."

# An earlier set's files that the new set lacks (nmf's second frame) go; the user's stay.
check "nmf rank 2" run 0 render "${fast[@]}" --layers nmf --rank 2 --iterations 1 -o "$tmp/nmf"
echo notes >"$tmp/nmf/notes.txt"
check "then one frame" run 0 render "${fast[@]}" -o "$tmp/nmf"
check "image-2.png of the earlier set is gone" test ! -e "$tmp/nmf/image-2.png" -a ! -e "$tmp/nmf/mask-1.png"
check "the new set and the notes are there" test -s "$tmp/nmf/image.png" -a -s "$tmp/nmf/notes.txt"

# ---- A folder that cannot be written: refused before any work, left as it was -----------------
check "a set to make read-only" run 0 render "${fast[@]}" -o "$tmp/ro/set"
chmod 777 "$tmp/ro"
chmod 555 "$tmp/ro/set"
before=$(listing "$tmp/ro")
check "a read-only output folder is refused" as_user 2 render "${fast[@]}" --seed 9 -o "$tmp/ro/set"
check "names it" one_line_naming "ro/set: cannot be written (Permission denied)"
check "the folder and the parent are as they were" test "$(listing "$tmp/ro")" = "$before"
chmod 555 "$tmp/ro"
check "a new folder in a read-only one is refused" as_user 2 render "${fast[@]}" -o "$tmp/ro/new/deeper"
check "names the folder that cannot be written" one_line_naming "ro: cannot be written"
check "a view into a read-only folder is refused" as_user 2 view --size 32x18 --spp 1 -o "$tmp/ro/v.png"
check "calibrate patterns into a read-only folder is refused" as_user 2 calibrate patterns -o "$tmp/ro/set"

# ---- --video: its folder and the encoder's size, before any frame -----------------------------
turn=(render "${fast[@]}" --turntable 90 --duration 0.2 --fps 20)
check "a video into a read-only folder is refused" as_user 2 "${turn[@]}" --video "$tmp/ro/x.mp4" -o "$tmp/frames1"
check "names --video and the folder" one_line_naming "--video"
check "before rendering: no frame" test ! -e "$tmp/frames1"
check "a view sequence's video too" as_user 2 view --size 32x18 --spp 1 --turntable 90 --duration 0.1 --video "$tmp/ro/x.mp4" -o "$tmp/v1/view.png"
check "no view frame" test ! -e "$tmp/v1"
# Sizes the encoders refuse (each opened at the size before any frame): x264 more than 16384
# pixels a side, x265 a 16-pixel-high picture, libvpx's VP9 more than 16384 a side.
check "a frame too wide for x264 is refused" run 2 view --size 20000x16 --spp 1 --turntable 90 --duration 0.1 --video "$tmp/w.mp4" --video-codec h264 -o "$tmp/v2/view.png"
check "names the encoder and the size" one_line_naming "libx264 encoder refuses 20000x16"
check "before rendering: no frame" test ! -e "$tmp/v2"
check "a quilt too wide for x265 is refused" run 2 "${turn[@]}" --quilt 3x1 --size 3000x16 --video "$tmp/q.mp4" -o "$tmp/q"
check "names x265" grep -qF "libx265 encoder refuses 9000x16" "$tmp/err"
check "before rendering: no quilt" test ! -e "$tmp/q"
check "a frame too tall for VP9 is refused" run 2 view --size 16x16385 --spp 1 --turntable 90 --duration 0.1 --video "$tmp/t.webm" -o "$tmp/v3/view.png"
check "names VP9's limit" one_line_naming "at most 16384 pixels a side"
check "before rendering: no frame" test ! -e "$tmp/v3"
check "an odd size is coded even, not refused" run 0 view --size 33x17 --spp 1 --turntable 90 --duration 0.1 --video "$tmp/odd.mp4" -o "$tmp/v4/view.png"
check "the video says coded 34x18" grep -q "coded 34x18" "$tmp/out"

# ---- Single files: a folder is refused; killed runs' temporaries go ---------------------------
mkdir -p "$tmp/f/view.png"
check "view -o a folder is refused" run 2 view --size 32x18 --spp 1 -o "$tmp/f/view.png"
check "names it" one_line_naming "view.png: is a folder"
mkdir -p "$tmp/s"
echo half >"$tmp/s/view.png.partial-999999999"
echo half >"$tmp/s/view.png.tmp-999999998"
echo live >"$tmp/s/view.png.partial-$$"  # this script runs: not stale
check "view over killed runs' files" run 0 view --size 32x18 --spp 1 -o "$tmp/s/view.png"
check "the killed runs' files are gone" test ! -e "$tmp/s/view.png.partial-999999999" -a ! -e "$tmp/s/view.png.tmp-999999998"
check "a running process's file stays" test -e "$tmp/s/view.png.partial-$$"
echo half >"$tmp/s/x.mp4.partial-999999999"
check "a video over a killed run's file" run 0 view --size 32x18 --spp 1 --turntable 90 --duration 0.1 --video "$tmp/s/x.mp4" -o "$tmp/s/v.png"
check "its partial file is gone" test ! -e "$tmp/s/x.mp4.partial-999999999" -a -s "$tmp/s/x.mp4"

cli_summary

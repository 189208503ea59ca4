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
# write_png FILE WIDTH HEIGHT KIND: a small PNG written by hand (zlib, no filters).
#   colour: an RGB gradient; bright: the same, no channel below 60/255 (never black);
#   depth16: a 16-bit grey disc near the camera on a far background.
write_png() {
  python3 - "$@" <<'PY'
import struct, sys, zlib
path, w, h, kind = sys.argv[1], int(sys.argv[2]), int(sys.argv[3]), sys.argv[4]
rows = []
for y in range(h):
    row = bytearray([0])
    for x in range(w):
        if kind in ("colour", "bright"):
            low = 60 if kind == "bright" else 0
            row += bytes([low + int((255 - low) * x / (w - 1)), low + int((255 - low) * y / (h - 1)), 128])
        else:
            near = (x - w / 2) ** 2 + (y - h / 2) ** 2 < (h / 3) ** 2
            row += struct.pack(">H", 60000 if near else 8000)
    rows.append(bytes(row))
depth, ctype = (16, 0) if kind == "depth16" else (8, 2)
def chunk(t, d):
    return struct.pack(">I", len(d)) + t + d + struct.pack(">I", zlib.crc32(t + d) & 0xffffffff)
png = b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", struct.pack(">IIBBBBB", w, h, depth, ctype, 0, 0, 0))
png += chunk(b"IDAT", zlib.compress(b"".join(rows))) + chunk(b"IEND", b"")
open(path, "wb").write(png)
PY
}
json_at() {  # json_at FILE POINTER: the value at a JSON pointer (/framing/depth_scale)
  python3 -c 'import json, sys
v = json.load(open(sys.argv[1]))
for k in sys.argv[2].strip("/").split("/"): v = v[int(k)] if isinstance(v, list) else v[k]
print(v)' "$1" "$2"
}
cli_summary() {
  echo "$passes passed, $failures failed"
  [ "$failures" -eq 0 ]
}

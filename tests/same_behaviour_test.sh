#!/usr/bin/env bash
# tools/same-behaviour, the check a redesign's closing note runs (old binary against new): a
# binary against itself is the same on every run asked for, and a binary whose outputs differ
# (a wrapper that changes one byte of a picture, and one that changes a message) is caught.
#   same_behaviour_test.sh PARALLAX SOURCE_DIR
set -uo pipefail
parallax=$(realpath "$1") tool=$2/tools/same-behaviour
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
fail() { echo "FAIL: $*" >&2; exit 1; }

out=$("$tool" "$parallax" "$parallax" des cp bad-method) || fail "itself: $out"
grep -qx "3 same, none differ" <<<"$out" || fail "itself: $out"

# A picture one byte off: calibrate patterns' first pattern rewritten after the run.
cat > "$work/picture-off" <<SH
#!/usr/bin/env bash
"$parallax" "\$@"; code=\$?
for f in "\${@: -1}"/*.png; do printf 'x' | dd of="\$f" bs=1 seek=100 conv=notrunc 2>/dev/null; break; done
exit \$code
SH
chmod +x "$work/picture-off"
out=$("$tool" "$parallax" "$work/picture-off" cp) && fail "a changed picture passed: $out"
grep -q "^DIFFERS: cp" <<<"$out" || fail "a changed picture: $out"

# A message changed.
cat > "$work/message-off" <<SH
#!/usr/bin/env bash
"$parallax" "\$@"; code=\$?; echo "one line more"; exit \$code
SH
chmod +x "$work/message-off"
out=$("$tool" "$parallax" "$work/message-off" des) && fail "a changed message passed: $out"
grep -q "^DIFFERS: des" <<<"$out" || fail "a changed message: $out"
echo "same-behaviour: itself the same, a changed picture and message caught"

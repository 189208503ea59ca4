#!/usr/bin/env bash
# The eye-sweep slider page (io/html_viewer.h) in a real browser: headless Chromium opens a
# three-frame page with "#frame=K", runs its script and dumps the DOM, which must show frame K.
# Usage: html_viewer_chromium_test.sh MAKE_SLIDER_PAGE_BINARY
# CHROMIUM overrides the browser (default: Debian's /usr/bin/chromium). A missing browser is a
# failure, not a skip.
set -u
make_page=$1
chromium=${CHROMIUM:-/usr/bin/chromium}
if [ ! -x "$chromium" ]; then
  echo "FAIL: $chromium not found: run tools/install-deps (it installs the chromium package)" >&2
  exit 1
fi
# tmp, check and cli_summary (the binary under test is make_slider_page).
source "$(dirname "$0")/cli_lib.sh" "$make_page" ""

if ! "$make_page" "$tmp/page.html"; then
  echo "FAIL: make_slider_page could not write the page" >&2
  exit 1
fi

# dump FRAGMENT: loads page.html#FRAGMENT with a fresh profile, DOM to $tmp/dom-FRAGMENT.html
dump() {
  local profile
  profile=$(mktemp -d -p "$tmp")
  timeout 120 "$chromium" --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$profile" --virtual-time-budget=2000 \
    --dump-dom "file://$tmp/page.html#$1" >"$tmp/dom-$1.html" 2>"$tmp/chromium-$1.log"
  local code=$?
  if [ "$code" -ne 0 ] || [ ! -s "$tmp/dom-$1.html" ]; then
    echo "chromium exited with $code for #$1; its log ends:" >&2
    tail -5 "$tmp/chromium-$1.log" >&2
    return 1
  fi
}
# element FILE TAG ID: the opening tag of the element with that id
element() { grep -o "<$2 [^>]*id=\"$3\"[^>]*>" "$1" | head -1; }
# attribute NAME TAG: the value of attribute NAME in an opening tag
attribute() { grep -o " $1=\"[^\"]*\"" <<<"$2" | head -1 | sed 's/^[^"]*"//; s/"$//'; }
# frame_source FILE K: data-src of item K (0-based) of the page's frame list
frame_source() { grep -o '<li data-src="[^"]*"' "$1" | sed -n "$(($2 + 1))p" | sed 's/^[^"]*"//; s/"$//'; }
label_text() { grep -o '<span id="label">[^<]*</span>' "$1" | sed 's/<[^>]*>//g'; }

# expect_frame FRAGMENT K LABEL: the dumped DOM shows frame K with its label
expect_frame() {
  local dom="$tmp/dom-$1.html" slider image
  slider=$(element "$dom" input slider)
  image=$(element "$dom" img frame)
  check "#$1: slider value is $2" [ "$(attribute value "$slider")" = "$2" ]
  check "#$1: img data-frame is $2" [ "$(attribute data-frame "$image")" = "$2" ]
  check "#$1: img shows frame $2's PNG" \
    [ "$(attribute src "$image")" = "$(frame_source "$dom" "$2")" ]
  check "#$1: label is '$3'" [ "$(label_text "$dom")" = "$3" ]
}

for fragment in frame=0 frame=1 frame=2 frame=9; do
  check "chromium dumps the DOM for #$fragment" dump "$fragment"
done
expect_frame frame=0 0 "eye -10 mm"
expect_frame frame=1 1 "eye 0 mm"
expect_frame frame=2 2 "eye +10 mm"
expect_frame frame=9 2 "eye +10 mm"  # a range input clamps to its maximum

# The frames are distinct, so frame 2's image must not be frame 0's.
src0=$(attribute src "$(element "$tmp/dom-frame=0.html" img frame)")
src2=$(attribute src "$(element "$tmp/dom-frame=2.html" img frame)")
check "frame 0's image is a PNG data URI" grep -q '^data:image/png;base64,iVBORw0KGgo' <<<"$src0"
check "frame 2 shows a different image than frame 0" [ "$src0" != "$src2" ]

cli_summary

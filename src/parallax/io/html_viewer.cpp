#include "parallax/io/html_viewer.h"

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace parallax {
namespace {

// Escapes the five characters with meaning in HTML text and quoted attribute values.
std::string htmlEscape(std::string_view text) {
  std::string out;
  for (const char c : text) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&#39;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

constexpr std::string_view kStyle = R"(<style>
body { font-family: sans-serif; background: #1e1e1e; color: #e8e8e8; margin: 1em; }
h1 { font-size: 1.2em; font-weight: normal; }
#controls { display: flex; align-items: center; gap: 1em; margin: 0.5em 0; }
#slider { flex: 1; max-width: 40em; }
#counter { font-variant-numeric: tabular-nums; }
#frame { display: block; max-width: 100%; }
</style>
)";

// Reads the frames from the hidden list; the slider's 'input' event is the one path that
// changes the frame, whether a user drags it or the URL fragment asks for "#frame=K".
constexpr std::string_view kScript = R"(<script>
(function () {
  const slider = document.getElementById('slider');
  const image = document.getElementById('frame');
  const label = document.getElementById('label');
  const counter = document.getElementById('counter');
  const frames = Array.from(document.querySelectorAll('#frames li'));
  slider.addEventListener('input', function () {
    const k = Number(slider.value);
    image.src = frames[k].dataset.src;
    image.alt = 'frame ' + k;
    image.dataset.frame = String(k);
    label.textContent = frames[k].dataset.label;
    counter.textContent = (k + 1) + ' / ' + frames.length;
    slider.setAttribute('value', String(k));  // so a saved or dumped DOM shows the frame
  });
  function followFragment() {
    const match = /^#frame=(\d+)$/.exec(window.location.hash);
    if (!match) return;
    slider.value = match[1];  // a range input clamps out-of-range values to min..max
    slider.dispatchEvent(new Event('input'));
  }
  window.addEventListener('hashchange', followFragment);
  followFragment();
})();
</script>
)";

}  // namespace

std::string base64Encode(std::string_view bytes) {
  static constexpr char kAlphabet[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  // Each group of 3 bytes (24 bits) becomes 4 characters of 6 bits; a final group of 1 or 2
  // bytes is zero-filled and padded with "==" or "=".
  for (size_t i = 0; i < bytes.size(); i += 3) {
    const size_t n = std::min<size_t>(3, bytes.size() - i);
    uint32_t group = 0;
    for (size_t k = 0; k < 3; ++k) group = group << 8 | (k < n ? uint8_t(bytes[i + k]) : 0u);
    for (size_t k = 0; k < 4; ++k) out += k <= n ? kAlphabet[(group >> (18 - 6 * k)) & 0x3F] : '=';
  }
  return out;
}

std::string sliderPage(const std::string& title, const std::vector<std::string>& pngFrames,
                       const std::vector<std::string>& labels) {
  if (pngFrames.empty()) throw std::invalid_argument("sliderPage: no frames");
  if (!labels.empty() && labels.size() != pngFrames.size())
    throw std::invalid_argument("sliderPage: need one label per frame (or none)");
  const size_t count = pngFrames.size();
  // The data URIs are written into the page one at a time, which is reserved at its size: the
  // page is the only copy of the frames in base64 (a sweep's memory estimate counts on it).
  const std::string uriPrefix = "data:image/png;base64,";
  const auto uri = [&](size_t k) { return uriPrefix + base64Encode(pngFrames[k]); };
  std::vector<std::string> texts;
  size_t reserved = std::string_view(kStyle).size() + std::string_view(kScript).size() + 4096;
  for (size_t k = 0; k < count; ++k) {
    texts.push_back(htmlEscape(labels.empty() ? "frame " + std::to_string(k) : labels[k]));
    reserved += uriPrefix.size() + (pngFrames[k].size() + 2) / 3 * 4 + texts[k].size() + 64;
  }
  reserved += uriPrefix.size() + (pngFrames[0].size() + 2) / 3 * 4 + title.size() * 12;
  const std::string heading = htmlEscape(title);
  std::string page;
  page.reserve(reserved);
  page += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n";
  page += "<title>" + heading + "</title>\n";
  page += kStyle;
  page += "</head>\n<body>\n<h1>" + heading + "</h1>\n<div id=\"controls\">\n";
  page += "<input type=\"range\" id=\"slider\" min=\"0\" max=\"" + std::to_string(count - 1) +
          "\" step=\"1\" value=\"0\" aria-label=\"frame\" autofocus>\n";
  page += "<span id=\"counter\">1 / " + std::to_string(count) + "</span>\n";
  page += "<span id=\"label\">" + texts[0] + "</span>\n</div>\n";
  page += "<img id=\"frame\" alt=\"frame 0\" data-frame=\"0\" src=\"" + uri(0) + "\">\n";
  page += "<ol id=\"frames\" hidden>\n";
  for (size_t k = 0; k < count; ++k)
    page += "<li data-src=\"" + uri(k) + "\" data-label=\"" + texts[k] + "\"></li>\n";
  page += "</ol>\n";
  page += kScript;
  page += "</body>\n</html>\n";
  return page;
}

}  // namespace parallax

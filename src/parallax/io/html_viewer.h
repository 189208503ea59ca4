// A self-contained HTML page for flipping through frames (e.g. the views of an eye sweep) with
// a slider. The frames are embedded as data: URIs, so the page needs no other file or network.
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace parallax {

// Base64 with the standard alphabet and '=' padding (RFC 4648, section 4).
std::string base64Encode(std::string_view bytes);

// The page: a heading with `title`, an <input type="range" id="slider"> over the frames, a
// <span id="label"> with the current frame's label (labels[k], or "frame k" if `labels` is
// empty) and an <img id="frame" data-frame="k"> showing PNG frame k (`pngFrames` hold PNG file
// bytes). Its 'input' event shows the slider's frame and mirrors the slider value into its
// value attribute. On load and on hash changes, a fragment "#frame=K" sets the slider to K and
// dispatches 'input' on it, the same path as a user moving it. Title and labels are
// HTML-escaped. Throws std::invalid_argument for no frames or labels that are neither empty
// nor one per frame.
std::string sliderPage(const std::string& title, const std::vector<std::string>& pngFrames,
                       const std::vector<std::string>& labels);

}  // namespace parallax

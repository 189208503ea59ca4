// The interlace request (docs/quilts.md): N view files or one quilt, the display they are
// mapped onto and how; its runner is interlace_job.h, the views it reads interlace_views.h.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "parallax/jobs/display_request.h"
#include "parallax/render/quilt.h"

namespace parallax::jobs {

struct InterlaceRequest {
  std::vector<std::string> views;  // view files, leftmost camera first, all of one size
  std::string quilt;               // or one quilt file (NAME_qs{C}x{R}a{aspect}.png)
  // quilt_layout: the quilt's tiles when its name does not say (the aspect: the display's).
  std::optional<QuiltLayout> quiltLayout;
  // "" the built-in barrier, a display file of any kind, lkg:NAME; subpixels: views per R, G, B
  // subpixel column (barriers); the lens reading: the quilt views each subpixel's light reaches
  // (docs/lenticular.md, "The optics").
  DisplayRequest display;
  // view_resampling: nearest or linear, when the views given are not the barrier's count.
  std::string viewResampling = "linear";
  bool linear = false;  // also image.pfm
  std::string output = "out";
};

}  // namespace parallax::jobs

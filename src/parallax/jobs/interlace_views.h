// The views an interlace maps onto a display (interlace_request.h), internal to jobs: N view files
// or one quilt file, or the same in memory; checked (one of the two, all of one size), their
// layout, and what the record says of them.
#pragma once

#include <string>
#include <vector>

#include "parallax/display/display_model.h"
#include "parallax/image/image.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/interlace_request.h"
#include "parallax/jobs/reporter.h"
#include "parallax/render/quilt.h"

namespace parallax::jobs {

// The views as given: leftmost camera first, and the quilt's layout if they came as one.
struct Views {
  std::vector<Image> images;
  QuiltLayout layout;
  bool quilt = false;              // cut from one quilt
  std::vector<std::string> names;  // otherwise the views' files, or their places in memory
};

// view_resampling: nearest or linear; RequestError naming it otherwise.
ViewResampling viewResampling(const std::string& text);
// The quilt as messages name it: its file, or "quilt" in memory.
std::string quiltName(const InterlaceRequest& r);
// The request's view files, or its quilt file cut by its name's layout (or quilt_layout).
Views readViews(const InterlaceRequest& r);
// The same for views or a quilt in memory (the quilt cut by quilt_layout).
Views givenViews(const InterlaceRequest& r, const std::vector<Image>& views, const Image& quilt);
// /inputs of the record: the quilt and its layout, or the view files; their count and size.
void recordInputs(JsonWriter& record, const InterlaceRequest& r, const Views& given);
// A quilt named for a display of another shape: a note that its views are stretched to this one.
void noteQuiltAspect(const Views& given, const DisplayModel& display, Reporter& reporter);

}  // namespace parallax::jobs

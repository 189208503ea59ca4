// The views an interlace maps (interlace_views.h): read from files or given in memory, checked,
// and recorded.
#include "parallax/jobs/interlace_views.h"

#include <cmath>
#include <cstdio>

#include "parallax/core/error.h"
#include "parallax/io/image_file.h"

namespace parallax::jobs {

ViewResampling viewResampling(const std::string& text) {
  if (text == "nearest") return ViewResampling::Nearest;
  if (text == "linear") return ViewResampling::Linear;
  throw RequestError("view_resampling", "expected nearest or linear, got '" + text + "'");
}

namespace {

QuiltLayout givenLayout(const QuiltLayout& layout) {
  if (layout.columns < 1 || layout.rows < 1 || layout.columns > 1024 || layout.rows > 1024)
    throw RequestError("quilt_layout", "expected columns and rows from 1 to 1024, got " +
                                           std::to_string(layout.columns) + "x" +
                                           std::to_string(layout.rows));
  return {layout.columns, layout.rows, 0.0};  // the aspect: the display's
}

std::string viewName(const InterlaceRequest& r, size_t k) {
  return k < r.views.size() ? r.views[k] : "views[" + std::to_string(k) + "]";
}

// All of the first view's size.
void checkViewSizes(const InterlaceRequest& r, const std::vector<Image>& views) {
  for (size_t k = 1; k < views.size(); ++k)
    if (views[k].width() != views[0].width() || views[k].height() != views[0].height())
      throw InputError(viewName(r, k), "",
                       "is " + std::to_string(views[k].width()) + "x" +
                           std::to_string(views[k].height()) + ", the first view " +
                           std::to_string(views[0].width()) + "x" +
                           std::to_string(views[0].height()));
}

// One of the two: views, or one quilt.
void checkOneInput(bool views, bool quilt) {
  if (views && quilt) throw RequestError("quilt", "give either the {views} or one quilt");
  if (!views && !quilt)
    throw RequestError("views", "expected the views (leftmost camera first) or one {quilt}");
}

}  // namespace

std::string quiltName(const InterlaceRequest& r) {
  return r.quilt.empty() ? "quilt" : r.quilt;
}

Views readViews(const InterlaceRequest& r) {
  checkOneInput(!r.views.empty(), !r.quilt.empty());
  if (!r.quilt.empty()) {
    const QuiltLayout layout =
        r.quiltLayout ? givenLayout(*r.quiltLayout) : parseQuiltName(r.quilt);
    return {splitQuilt(readImage(r.quilt), layout, r.quilt), layout, true, {}};
  }
  if (r.quiltLayout) throw RequestError("quilt_layout", "applies to a single quilt file");
  Views given;
  given.names = r.views;
  for (const std::string& path : r.views) {
    given.images.push_back(readImage(path));
    checkViewSizes(r, given.images);
  }
  return given;
}

Views givenViews(const InterlaceRequest& r, const std::vector<Image>& views, const Image& quilt) {
  checkOneInput(!views.empty(), !quilt.empty());
  if (!quilt.empty()) {
    if (!r.quiltLayout)
      throw RequestError("quilt_layout", "is needed to cut a quilt picture into its views");
    const QuiltLayout layout = givenLayout(*r.quiltLayout);
    return {splitQuilt(quilt, layout, quiltName(r)), layout, true, {}};
  }
  if (r.quiltLayout) throw RequestError("quilt_layout", "applies to a single quilt");
  checkViewSizes(r, views);
  Views given{views, {}, false, {}};
  for (size_t k = 0; k < views.size(); ++k) given.names.push_back(viewName(r, k));
  return given;
}

void recordInputs(JsonWriter& record, const InterlaceRequest& r, const Views& given) {
  if (given.quilt) {
    record.set("/inputs/quilt", quiltName(r));
    record.set("/inputs/columns", given.layout.columns);
    record.set("/inputs/rows", given.layout.rows);
    if (given.layout.aspect > 0) record.set("/inputs/aspect", given.layout.aspect);  // its name's
  } else {
    record.set("/inputs/views", given.names);
  }
  const Image& first = given.images[0];
  record.set("/inputs/view_count", int(given.images.size()));
  record.set("/inputs/view_size",
             std::to_string(first.width()) + "x" + std::to_string(first.height()));
}

// A quilt named for a display of another shape: its views are stretched to this one's.
void noteQuiltAspect(const Views& given, const DisplayModel& display, Reporter& reporter) {
  const DisplayWindow window = display.window();
  const double aspect = window.widthMm / window.heightMm;
  if (!given.quilt || !(given.layout.aspect > 0) ||
      std::abs(given.layout.aspect / aspect - 1.0) <= 0.01)
    return;
  reporter.note(
      printed("the quilt is named for a display of aspect %s, this one's is %s: its "
              "views are stretched to the display",
              formatQuiltAspect(given.layout.aspect).c_str(), formatQuiltAspect(aspect).c_str()));
}

}  // namespace parallax::jobs

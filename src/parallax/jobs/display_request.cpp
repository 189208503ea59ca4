#include "parallax/jobs/display_request.h"

namespace parallax::jobs {

DisplayRequest DisplayRequest::of(const DisplayDescription& description) {
  DisplayRequest request;
  request.loaded = description;
  // The built-in display's source names no file: the request names it as one given by no path.
  if (description.source() != "<built-in>") request.path = description.source();
  return request;
}

DisplayDescription DisplayRequest::describe(Reporter& reporter,
                                            const std::string& whenEmpty) const {
  if (loaded) return *loaded;
  if (madeInCode) {
    DisplayDescription made;
    made.kind = DisplayKind::Other;
    return made;
  }
  return loadDisplay(path.empty() ? whenEmpty : path, reporter);
}

DisplayCameraRequest DisplayRequest::camera(const ViewFilter& filter) const {
  DisplayCameraRequest camera;
  camera.subpixels = subpixels;
  camera.filter = filter;
  camera.viewDistanceMm = distance;
  camera.lens = lens;
  return camera;
}

DisplayDescription loadDisplay(const std::string& pathOrPreset, Reporter& reporter) {
  DisplayDescription description = loadDisplayDescription(pathOrPreset);
  for (const std::string& warning : description.lenticular.warnings) reporter.warning(warning);
  return description;
}

}  // namespace parallax::jobs

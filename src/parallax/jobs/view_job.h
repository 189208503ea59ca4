// The view runner (docs/architecture.md, "Requests"): an ordinary pinhole picture of a scene, or
// the ideal picture through a display's window from an eye (what a render means that eye to
// see: the scene framed as the render frames it). One picture, or a sequence of numbered
// pictures with a video. `parallax view` and Python's view/ideal_view are two spellings of it.
#pragma once

#include <memory>
#include <optional>
#include <string>

#include "parallax/camera/camera.h"
#include "parallax/core/math.h"
#include "parallax/image/image.h"
#include "parallax/jobs/display_request.h"
#include "parallax/jobs/reporter.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/scene_request.h"
#include "parallax/jobs/sequence.h"

namespace parallax::jobs {

struct ViewRequest {
  SceneRequest scene;
  // The pinhole camera: the scene's own (or one framing it) unless given (scene units).
  std::optional<Vec3f> eye, lookAt, up;
  std::optional<float> fov;   // vertical, degrees, in (0, 180)
  int width = 0, height = 0;  // size; 0: 960x540, or the display's front panel (display_eye)
  // display_eye: the ideal view through `display`'s window from this eye (display mm).
  std::optional<Vec3d> displayEye;
  DisplayRequest display;
  FramingRequest framing;  // with display_eye: framed as render frames it
  SamplingRequest sampling;
  std::string output = "out/view.png";
  SequenceRequest sequence;  // numbered pictures OUTPUT-NNNN.png
};

// The request's camera for `scene` (posed, for a sequence's frame). Throws RequestError naming
// up (parallel to the view direction), fov or display_eye (not in front of the display).
std::unique_ptr<Camera> viewCamera(const ViewRequest& request, const Scene& scene,
                                   Reporter& reporter);

// Renders the picture (or the sequence) into request.output.
void runView(const ViewRequest& request, Reporter& reporter);

// The picture of `scene` (loaded by the caller), in memory.
Image viewInMemory(const ViewRequest& request, const Scene& scene, Reporter& reporter);

}  // namespace parallax::jobs

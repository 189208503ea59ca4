// The design runner: a display's derived design (a barrier's G1-G4, a lenticular panel's lens
// figures), and with a scene its framing: the content's depth against the depth of field.
// `parallax design` prints it as text or JSON; Python's design() returns the JSON.
#pragma once

#include <optional>
#include <string>

#include "parallax/jobs/display_request.h"
#include "parallax/jobs/reporter.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/scene_request.h"
#include "parallax/scene/scene.h"

namespace parallax::jobs {

struct DesignRequest {
  DisplayRequest display;  // "" the built-in, a file, lkg:NAME
  double depth =
      0;  // depth (mm, + toward the viewer) of the disparity figure; 0: the depth of field
  std::optional<SceneRequest> scene;  // scene: framed for the display as render frames it
  FramingRequest framing;             // with scene
};

struct DesignReport {
  std::string text;  // the lines `parallax design` prints
  std::string json;  // the object `parallax design --json` prints
};

// `scene`, when given, is the scene already loaded (else request.scene is loaded).
DesignReport designReport(const DesignRequest& request, Reporter& reporter,
                          const Scene* scene = nullptr);

}  // namespace parallax::jobs

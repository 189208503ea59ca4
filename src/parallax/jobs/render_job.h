// The render runner (docs/architecture.md, "Requests"): a display's pictures of a scene, of any
// display kind: a barrier's image and mask layers (the display camera, the usual practice of
// direct mapping as a baseline, or content-adaptive layers solved from them), a lenticular
// panel's picture, or a quilt of off-axis views; one picture set or a sequence of frames with a
// video. `parallax render` and Python's render functions are two spellings of one RenderRequest.
#pragma once

#include "parallax/jobs/render_request.h"
#include "parallax/jobs/reporter.h"
#include "parallax/scene/scene.h"

namespace parallax::jobs {

// Renders to request.output: the picture set with the display's file and render.json, or a
// sequence's frame-NNNN folders and its video. Every check and estimate runs before the scene
// is loaded or anything is written.
void runRender(const RenderRequest& request, Reporter& reporter);

// The same picture set of `scene` (loaded by the caller; request.scene only names it in the
// record), kept in memory: no files, no sequence.
RenderResult renderInMemory(const RenderRequest& request, const Scene& scene, Reporter& reporter);

}  // namespace parallax::jobs

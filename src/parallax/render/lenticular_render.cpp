#include "parallax/render/lenticular_render.h"

#include "parallax/camera/lenticular_camera.h"

namespace parallax {

LenticularRender renderLenticular(const Scene& scene, const Accelerator& accelerator,
                                  const LenticularDesign& design, const RenderSettings& settings,
                                  const ProgressCallback& progress, const ViewFilter& filter) {
  const LenticularCamera camera(design, scene.display, filter);
  LenticularRender out;
  const Image film = render(scene, accelerator, camera, settings, &out.stats, progress);
  // Film column 3x + c is channel c of pixel x, as in the subpixel mode of renderDisplay.
  out.image = panelFromSubpixelFilm(film, LenticularCamera::channelOfColumn);
  return out;
}

}  // namespace parallax

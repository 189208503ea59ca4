#include "parallax/render/lenticular_render.h"

#include "parallax/camera/lenticular_camera.h"

namespace parallax {

LenticularRender renderLenticular(const Scene& scene, const Accelerator& accelerator,
                                  const LenticularDesign& design, const RenderSettings& settings,
                                  const ProgressCallback& progress) {
  const LenticularCamera camera(design, scene.display);
  LenticularRender out;
  const Image film = render(scene, accelerator, camera, settings, &out.stats, progress);
  // Film column 3x + c is channel c of pixel x; like the subpixel mode of renderDisplay, each
  // subpixel keeps only its own colour.
  out.image = Image(design.calibration.screenW, design.calibration.screenH);
  for (int y = 0; y < film.height(); ++y)
    for (int column = 0; column < film.width(); ++column) {
      const int channel = LenticularCamera::channelOfColumn(column);
      out.image.at(column / 3, y)[channel] = film.at(column, y)[channel];
    }
  return out;
}

}  // namespace parallax

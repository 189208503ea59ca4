// A picture of the built-in scene through the installed library: the same pinhole picture as
// `parallax view --eye X,Y,Z --look-at X,Y,Z --up 0,1,0 --fov DEG --size WxH --spp 1 -o FILE`.
//   view OUTPUT.pfm|png WIDTH HEIGHT EYE_X EYE_Y EYE_Z AT_X AT_Y AT_Z FOV
#include <cstdio>
#include <cstdlib>
#include <exception>

#include "parallax/accel/accelerator.h"
#include "parallax/camera/camera.h"
#include "parallax/io/image_file.h"
#include "parallax/render/render.h"
#include "parallax/scene/scene.h"

int main(int argc, char** argv) {
  if (argc != 11) {
    std::fprintf(stderr, "usage: %s OUTPUT WIDTH HEIGHT EYE_X EYE_Y EYE_Z AT_X AT_Y AT_Z FOV\n",
                 argv[0]);
    return 2;
  }
  const auto number = [&](int i) { return static_cast<float>(std::atof(argv[i])); };
  try {
    const parallax::Scene scene = parallax::defaultScene();
    const parallax::Accelerator accelerator(scene);
    const parallax::PinholeCamera camera({number(4), number(5), number(6)},
                                         {number(7), number(8), number(9)}, {0, 1, 0}, number(10),
                                         std::atoi(argv[2]), std::atoi(argv[3]));
    parallax::RenderStats stats;
    const parallax::Image picture =
        parallax::render(scene, accelerator, camera, parallax::RenderSettings{}, &stats);
    parallax::writeImage(argv[1], picture);
    std::printf("%llu camera rays\n", static_cast<unsigned long long>(stats.cameraRays));
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
  return 0;
}

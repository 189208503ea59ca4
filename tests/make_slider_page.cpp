// Test helper for html_viewer_chromium_test.sh: writes a slider page of three solid-colour
// frames (red, green, blue) labelled "eye -10 mm", "eye 0 mm", "eye +10 mm".
// Usage: make_slider_page OUTPUT.html
#include <exception>
#include <iostream>

#include "parallax/image/image.h"
#include "parallax/io/animation.h"
#include "parallax/io/html_viewer.h"
#include "parallax/io/image_file.h"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::cerr << "usage: make_slider_page OUTPUT.html\n";
    return 2;
  }
  using parallax::Image;
  using parallax::Vec3f;
  try {
    const std::vector<std::string> frames = {
        parallax::pngBytes(Image(16, 12, Vec3f(1.0f, 0.0f, 0.0f))),
        parallax::pngBytes(Image(16, 12, Vec3f(0.0f, 1.0f, 0.0f))),
        parallax::pngBytes(Image(16, 12, Vec3f(0.0f, 0.0f, 1.0f)))};
    parallax::writeFileAtomically(
        argv[1],
        parallax::sliderPage("eye sweep", frames, {"eye -10 mm", "eye 0 mm", "eye +10 mm"}));
  } catch (const std::exception& error) {
    std::cerr << "make_slider_page: " << error.what() << "\n";
    return 1;
  }
  return 0;
}

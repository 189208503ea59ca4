// parallax: renders 3-D scenes into the layer images of two-LCD parallax-barrier displays. The
// command line itself is app/command_line.h, compiled once into the app library.
#include "parallax/app/command_line.h"

int main(int argc, char** argv) {
  return parallax::app::runCommandLine(argc, argv);
}

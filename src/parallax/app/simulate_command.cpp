// `parallax simulate`: what an eye in front of the display sees, without the hardware; eye
// sweeps (contact sheet, animation, slider page), and quality figures against the ideal view.
// The options spell a jobs::SimulateRequest (jobs/simulate_job.h).
#include <array>
#include <climits>
#include <memory>

#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/jobs/simulate_job.h"

namespace parallax::app {

namespace {

// The request, and the options the command line spells as text (X,Y,Z and WxH).
struct SimulateOptions {
  SimulateRequest request;
  std::vector<std::string> eyes;
  std::string size;
};

void runSimulate(SimulateOptions o) {
  SimulateRequest& r = o.request;
  if (!o.size.empty()) {
    std::array<int, 2> size{};
    parseSize("--size", o.size, size[0], size[1]);
    r.simulator.size = size;
  }
  for (const std::string& text : o.eyes) {
    const Vec3f e = parseVec3("--eye", text);
    r.eyes.push_back({e.x, e.y, e.z});
  }
  jobs::runSimulate(r, cliReporter());
}

}  // namespace

void registerSimulateCommand(Command& cli) {
  auto options = std::make_shared<SimulateOptions>();
  SimulateRequest& r = options->request;
  Command* cmd = cli.addSubcommand(
      "simulate", "See the display without hardware: what an eye in front of it sees");
  cmd->addOption("dir", r.dir,
                 "Output folder of `parallax render` (image.png, mask.png, "
                 "display.json, render.json)")
      ->captureDefault();
  cmd->addOption("--image", r.image, "Image layer (instead of DIR/image.png)");
  cmd->addOption("--mask", r.mask, "Mask layer (instead of DIR/mask.png)");
  addDisplayOption(*cmd, r.display,
                   "Display file of any kind, or lkg:NAME (instead of DIR/display.json or "
                   "DIR/visual.json)");
  cmd->addOption("--frames", r.frames,
                 "DIR is a sequence of render --frames: what the eye sees in frames FIRST:LAST "
                 "(or all), as OUTPUT-NNNN.png (and --video)")
      ->typeName("FIRST:LAST|all");
  cmd->addOption("--eye", options->eyes,
                 "Eye position X,Y,Z in display mm (origin: front layer centre, z toward the "
                 "viewer); repeatable. Default: the view-zone centre");
  cmd->addOption("-o,--output", r.output,
                 "Output image (several eyes: FILE-K), or the prefix of the sweep's files; default "
                 "out/simulated.png and out/sweep in the working folder, not in DIR");
  cmd->addOption("--size", options->size, "Output size WIDTHxHEIGHT (default: the front layer's)");
  cmd->addOption("--spp", r.simulator.spp,
                 "0: integrate each output pixel's area exactly (the default); n*n: point "
                 "samples per output pixel instead (1: the centre, which aliases against the "
                 "mask between design eyes)")
      ->captureDefault()
      ->check(squareCount(true));
  Option* pupil =
      cmd->addOption("--pupil", r.simulator.pupil, "Pupil diameter in mm, 0 (a pinhole eye) to 100")
          ->check(realIn(0, 100));
  // Settings of an option that is not given: refused (CLI11's "requires"), not ignored.
  cmd->addOption("--pupil-samples", r.simulator.pupilSamples, "Points averaged over the pupil")
      ->captureDefault()
      ->check(integerIn(1, INT_MAX))
      ->needs(pupil);
  cmd->addOption("--diffuser", r.simulator.diffuser,
                 "Blur of the rear layer by a diffuser foil, Gaussian sigma in mm (0 to the "
                 "display's width)")
      ->check(realIn(0, kInfinity));
  cmd->addFlag("--color-filters", r.simulator.colorFilters,
               "Model the R, G, B colour-filter stripes of both layers (rainbow fringes)");
  cmd->addFlag("--raw", r.simulator.raw,
               "Raw brightness (default: normalised by the aperture ratio)");
  cmd->addFlag("--raw-pixels", r.simulator.rawPixels,
               "Write the pinhole eye's samples unfiltered (default: integrated over one "
               "screen period, as a viewer at the design distance perceives them)");
  Option* sweep =
      cmd->addOption("--sweep", r.sweep.count,
                     "Move the eye across the view zone in N steps: contact sheet, APNG, HTML")
          ->check(integerIn(0, INT_MAX));
  cmd->addOption("--sweep-range", r.sweep.range,
                 "Sweep width in view-zone widths, above 0 and at most 10 (> 1 goes beyond the "
                 "zone)")
      ->captureDefault()
      ->check(realIn(0, 10, Bound::Open))
      ->needs(sweep);
  cmd->addOption("--sweep-distance", r.sweep.distance,
                 "Eye distance of the sweep in mm, above 0 and at most 100 D (default D)")
      ->check(realIn(0, kInfinity, Bound::Open))
      ->needs(sweep);
  Option* reference =
      cmd->addFlag("--reference", r.reference,
                   "Quality figures against the ideal view: PSNR, SSIM, brightness, cross-talk at "
                   "the --eye positions (cross-talk: the share of the light reaching the eye "
                   "from other views than its own, 1 - own / all; even at a design eye the "
                   "mask's pixel raster lets about a third through on the built-in display, "
                   "docs/simulator.md); without --eye, the dense measure over the view zone "
                   "(--eyes-per-view, --distances): mean, worst eye, flicker");
  cmd->addOption("--scene", r.scene, "Scene for --reference (default: from render.json)");
  cmd->addOption("--reference-spp", r.referenceSpp, "Samples per pixel of the ideal view")
      ->captureDefault()
      ->check(integerIn(1, INT_MAX))
      ->needs(reference);
  cmd->addOption("--eyes-per-view", r.eyesPerView,
                 "With --reference and no --eye: eyes evenly inside every view's window "
                 "(the dense measure)")
      ->captureDefault()
      ->needs(reference);
  cmd->addOption("--compare", r.compare,
                 "With the dense measure: another render folder of the same scene and display, "
                 "scored at the same eyes against the same ideal views; repeatable")
      ->typeName("DIR");
  cmd->addOption("--distances", r.distances,
                 "With --reference and no --eye: eye distances of the dense measure, in units "
                 "of the design distance D")
      ->captureDefault()
      ->needs(reference);
  addLensReadingOptions(*cmd, r.simulator.lens);
  cmd->addFlag("--all-readings", r.allReadings,
               "With the dense measure on a lenticular display: score every render under each "
               "reading of the optics (ideal and pixel-wide spot, parallel and converging "
               "bundles, and the display's own), against the same ideal views");
  cmd->addOption("--threads", r.simulator.threads, "Worker threads (0: all cores)")
      ->check(threadCount());
  // As many frames a second as the sweep's APNG (250 ms a frame).
  r.video.fps = 4;
  addVideoOptions(*cmd, r.video, "the sweep's pictures (with --sweep)");
  addLimitOptions(*cmd);
  cmd->addFlag("--json", r.json, "Print one JSON object");
  cmd->callback([options] { runSimulate(*options); });
}

}  // namespace parallax::app

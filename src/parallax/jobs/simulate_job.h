// The simulate runner (docs/architecture.md, "Requests"): what an eye in front of a display sees,
// without the hardware, from a render folder or given layers; eye sweeps (contact sheet, APNG,
// slider page, video), a sequence's frames, and the quality figures against the ideal views
// (at given eyes, or the dense measure over the view zone). `parallax simulate` and Python's
// simulate, sweep_eyes and quality are spellings of one SimulateRequest and its pieces.
#pragma once

#include <array>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "parallax/accel/accelerator.h"
#include "parallax/core/math.h"
#include "parallax/display/display_model.h"
#include "parallax/image/image.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/display_request.h"
#include "parallax/jobs/reporter.h"
#include "parallax/jobs/requests.h"
#include "parallax/jobs/video_output.h"
#include "parallax/quality/viewer_quality.h"
#include "parallax/scene/scene.h"
#include "parallax/sim/simulated_display.h"
#include "parallax/sim/simulator.h"

namespace parallax::jobs {

// size, spp, pupil, pupil_samples, diffuser, color_filters, raw, raw_pixels, threads: how the
// simulator sees the layers (sim/simulator.h); all but raw_pixels and threads are the two-layer
// simulator's own.
struct SimulatorRequest {
  std::optional<std::array<int, 2>> size;  // width, height; none: the front layer's
  int spp = 0;         // 0: each output pixel's area exactly; n*n: point samples (for comparison)
  double pupil = 0.0;  // mm; 0: a pinhole eye
  int pupilSamples = 16;
  // The rear layer's blur, Gaussian sigma in mm; none: the display's own diffuser_sigma_mm.
  std::optional<double> diffuser;
  bool colorFilters = false;
  bool raw = false;        // raw brightness (not normalised by the aperture ratio)
  bool rawPixels = false;  // the eye's samples as they are (not at the display's resolution)
  int threads = 0;
  // Lenticular panels: the optics to read the panel under (docs/lenticular.md, "The optics").
  LensReadingRequest lens;
};

// The simulator's options for `display`. Throws RequestError naming spp (not 0 or a square),
// pupil, pupil_samples, diffuser (also one wider than the display) or size, and refuses the
// two-layer simulator's options for other kinds by their fields.
SimulationOptions simulationOptions(const SimulatorRequest& request, const DisplayModel& display);

// Refuses a mask layer for a display without one (field mask).
void checkMaskLayer(const DisplayModel& display, bool maskGiven);

// sweep, sweep_range, sweep_distance: the eye moved across the view zone in `count` steps.
struct SweepRequest {
  int count = 0;        // 0: no sweep
  double range = 1.0;   // in view-zone widths, (0, 10]
  double distance = 0;  // mm; 0: the design distance D
};

// The sweep's eyes, left to right: across the view zone (scaled by range) at the distance, x
// scaled so that a farther sweep covers the same views. Throws RequestError naming sweep (no
// eye), sweep_range or sweep_distance (more than 100 D).
std::vector<Vec3d> sweepEyes(const DisplayModel& display, const SweepRequest& sweep);

// The eyes given (each in front: field eye), then the sweep's; none: the view zone's centre.
std::vector<Vec3d> simulatedEyes(const DisplayModel& display, const std::vector<Vec3d>& given,
                                 const SweepRequest& sweep = {});

// Refuses layers no panel shows, naming the first bad pixel: NaN, infinite or negative values
// (field image or mask), and a mask's transmittance above 1. The image layer may exceed 1
// (a render's linear layer keeps the scene's highlights).
void checkLayerValues(const LayerImages& layers);

// Before the simulator allocates: memory for one eye's view and picture, each eye's encoded
// copy and two copies of the layers; the time of every sample (spp x pupil samples per output
// pixel, and referenceSpp per pixel of the ideal views; 0: none). The refusals name {sweep}
// (sweep > 0), {size} or {eye}. Eyes alone (no sweep, no reference): the whole estimate
// (checkPeakMemory), with `keptCopies` copies of every eye's picture kept to the end (Python's
// simulate: the pictures and their arrays).
// Also checks the layers' values (checkLayerValues).
void checkSimulationWork(const DisplayModel& display, const LayerImages& layers,
                         const SimulatorRequest& request, size_t eyes, int sweep = 0,
                         int referenceSpp = 0, int keptCopies = 0);

// The size of the pictures an eye sees: the request's size, else the barrier's front panel or the
// lenticular panel.
std::pair<double, double> seenPictureSize(const DisplayModel& display,
                                          const SimulatorRequest& request);

// The picture an eye sees in `view`: at the display's resolution (one screen period, one lens
// around each output pixel, as a viewer at the design distance perceives it), or raw.
Image seenPicture(const SimulatedDisplay& simulator, const Image& view, bool rawPixels);

// What the eyes see of the layers (Python's simulate): the pictures, in order.
std::vector<Image> simulatedPictures(const DisplayModel& display, LayerImages layers,
                                     const SimulatorRequest& request,
                                     const std::vector<Vec3d>& eyes);

// The scene the layers were rendered from as they framed it, and the display as its camera saw
// it: the display frames the scene for itself (camera/framing.h) with `framing` set first
// (Python's fit, focus, depth_budget; a render folder's scene has the render's already). A
// lenticular panel's camera compressed depth by the framing's depth scale: `display` is then a
// view of the given display with that scale (display/depth_scaled_display.h), whose ideal views
// are those the render meant; otherwise the given display itself.
struct RenderedReference {
  Scene scene;
  const DisplayModel* display = nullptr;
  std::unique_ptr<DisplayModel> scaled;  // what `display` points to when it is not the given
};
RenderedReference referenceScene(Scene scene, const DisplayModel& display,
                                 const FramingRequest& framing = {});

// The quality figures at one eye: PSNR and SSIM against the ideal view, and (barriers) the raw
// brightness and cross-talk, averaged over time-multiplexed frames.
struct EyeFigures {
  double psnr = 0, ssim = 0, brightness = 0, crosstalk = 0;
  int ownView = -1;  // the view that sends the eye the most light (-1: no barrier)
};

// What the figures are measured against and with.
struct QualityReference {
  const Scene& scene;  // as rendered (referenceScene)
  const Accelerator& accelerator;
  const DisplayModel& display;
  const SimulatedDisplay& simulator;
  const std::vector<LayerImages>& frames;  // the layers (the masks' cross-talk)
  SimulationOptions options;
  int referenceSpp = kDefaultReferenceSpp;
};

// The figures at `eye`, whose view the simulator made; `seen`: that view at the display's
// resolution (seenPicture without raw pixels).
EyeFigures eyeFigures(const QualityReference& reference, const Vec3d& eye, const Image& view,
                      const Image& seen);

// Refuses reference_spp below 1.
void checkReferenceSpp(int referenceSpp);

// The figures of `layers` at each eye against the ideal views of `scene` (as rendered), as
// `simulate --reference --eye ...` measures them (Python's quality).
std::vector<EyeFigures> qualityFigures(const Scene& scene, const DisplayModel& display,
                                       LayerImages layers, const SimulatorRequest& request,
                                       const std::vector<Vec3d>& eyes, int referenceSpp);

// /eyes/K/eye of each eye, with its figures when measured (psnr, ssim, brightness, crosstalk,
// own_view), and their /mean.
void recordEyeFigures(JsonWriter& json, const std::vector<Vec3d>& eyes,
                      const std::vector<EyeFigures>& figures);

// Python's quality, one call: the scene framed as the render framed it (referenceScene with
// `framing`), the figures of `layers` at each eye (qualityFigures), as `simulate --reference
// --eye ... --json` writes them: /display, /display_kind, /eyes and /mean.
std::string qualityReport(const Scene& scene, const DisplayModel& display, LayerImages layers,
                          const SimulatorRequest& request, const std::vector<Vec3d>& eyes,
                          int referenceSpp, const FramingRequest& framing);

struct SimulateRequest {
  // The inputs: a render folder (its layers, display and render.json), or given layers.
  std::string dir = "out";
  std::string frames;       // FIRST:LAST or all: dir is a sequence of render --frames
  std::string image, mask;  // instead of dir's image.png and mask.png
  DisplayRequest display;   // any kind (or lkg:NAME); "": dir's display.json or visual.json
  std::string scene;        // for reference; "": the one render.json names
  // The eyes (display mm), and a sweep after them; none: the view zone's centre.
  std::vector<Vec3d> eyes;
  SweepRequest sweep;
  SimulatorRequest simulator;
  // reference: the figures at the eyes; without eyes or a sweep, the dense measure.
  bool reference = false;
  int referenceSpp = kDefaultReferenceSpp;
  int eyesPerView = 4;                   // the dense measure's eyes inside each view's window
  std::string distances = "0.8,1,1.25";  // its distances in units of D
  std::vector<std::string> compare;      // more render folders scored at the same eyes
  // The dense measure on a lenticular display: every render under each reading of the optics
  // (lensReadings), against the same ideal views.
  bool allReadings = false;
  // The outputs: a picture (several eyes: FILE-K; "": out/simulated.png), or the prefix of a
  // sweep's files ("": out/sweep); a sweep's video; one JSON object instead of the lines.
  std::string output;
  VideoRequest video;
  bool json = false;
};

// Does what `parallax simulate` does: reads the inputs, checks the request and its estimates
// before anything is allocated or written, writes the pictures (or the sweep's sheet,
// animation, page and video) and says what it wrote, the figures and any JSON as results.
void runSimulate(const SimulateRequest& request, Reporter& reporter);

}  // namespace parallax::jobs

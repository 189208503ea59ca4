// `parallax simulate`: what an eye in front of the display sees, without the hardware; eye
// sweeps (contact sheet, animation, slider page), and quality figures against the ideal view.
#include <CLI/CLI.hpp>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "parallax/accel/accelerator.h"
#include "parallax/app/cli_support.h"
#include "parallax/app/commands.h"
#include "parallax/camera/display_camera.h"
#include "parallax/core/error.h"
#include "parallax/image/contact_sheet.h"
#include "parallax/image/metrics.h"
#include "parallax/io/animation.h"
#include "parallax/io/display_file.h"
#include "parallax/io/html_viewer.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_reader.h"
#include "parallax/io/json_writer.h"
#include "parallax/render/render.h"
#include "parallax/sim/crosstalk.h"
#include "parallax/sim/simulator.h"

namespace parallax::app {

namespace {

namespace fs = std::filesystem;

struct SimulateOptions {
  std::string dir = "out";
  std::string image, mask, display, scene;
  std::vector<std::string> eyes;
  std::string output;
  std::string size;
  int spp = 1;
  double pupil = 0.0;
  int pupilSamples = 16;
  double diffuser = 0.0;
  bool colourFilters = false;
  bool raw = false;
  int sweep = 0;
  double sweepRange = 1.0;
  double sweepDistance = 0.0;
  bool reference = false;
  int referenceSpp = 16;
  bool json = false;
  int threads = 0;
  bool rawPixels = false;
};

// The inputs: a `render` output folder, or an image and mask with a display file.
struct Inputs {
  DisplayDesign design;
  LayerImages layers;
  std::string scene;  // for --reference: the scene the layers were rendered from
};

Inputs loadInputs(const SimulateOptions& o) {
  const fs::path dir(o.dir);
  const auto inDir = [&dir](const char* name) { return (dir / name).string(); };
  std::string displayPath = o.display;
  if (displayPath.empty() && fs::exists(inDir("display.json"))) displayPath = inDir("display.json");
  Inputs in{loadDesignOrDefault(displayPath), {}, o.scene};
  in.layers.image = readImage(o.image.empty() ? inDir("image.png") : o.image);
  in.layers.mask = readImage(o.mask.empty() ? inDir("mask.png") : o.mask);
  if (in.scene.empty() && fs::exists(inDir("render.json"))) {
    const JsonDocument record = JsonDocument::parseFile(inDir("render.json"));
    in.scene = record.root().string("scene", "<built-in>");
  }
  if (in.scene == "<built-in>") in.scene.clear();
  return in;
}

std::vector<Vec3d> eyePositions(const SimulateOptions& o, const DisplayDesign& d) {
  std::vector<Vec3d> eyes;
  for (const std::string& text : o.eyes) {
    const Vec3f e = parseVec3("--eye", text);
    if (!(e.z > 0)) throw InputError("command line", "--eye", "the eye must be in front (z > 0)");
    eyes.push_back({e.x, e.y, e.z});
  }
  const double centre = d.spec.viewZoneCenterXMm, y = d.spec.viewZoneHeightMm;
  if (o.sweep > 0) {
    const double z = o.sweepDistance > 0 ? o.sweepDistance : d.viewDistanceMm;
    // Across the view zone (scaled by --sweep-range), scaled to the distance so that a
    // farther sweep covers the same views.
    const double width = o.sweepRange * d.viewZoneWidthMm * z / d.viewDistanceMm;
    for (int i = 0; i < o.sweep; ++i) {
      const double t = o.sweep == 1 ? 0.5 : double(i) / double(o.sweep - 1);
      eyes.push_back({centre + width * (t - 0.5), y, z});
    }
  }
  if (eyes.empty()) eyes.push_back({centre, y, d.viewDistanceMm});
  return eyes;
}

// FILE for one output, FILE-K for the K-th of several.
std::string numbered(const std::string& path, size_t index, size_t count) {
  if (count == 1) return path;
  const fs::path p(path);
  return (p.parent_path() /
          (p.stem().string() + "-" + std::to_string(index) + p.extension().string()))
      .string();
}

std::string eyeLabel(const Vec3d& e) {
  char text[64];
  std::snprintf(text, sizeof text, "x=%.0f z=%.0f", e.x, e.z);
  return text;
}

struct Quality {
  double psnr = 0, ssim = 0, brightness = 0, crosstalk = 0;
  int ownView = 0;
};

// One screen period in output pixels: the display's spatial resolution, at which both the
// simulated and the ideal view are compared (a pinhole eye sees one lit pixel per group).
double periodInPixels(const DisplayDesign& d, int width) {
  return d.screenPeriodMm / (d.frontWidthMm() / double(width));
}

// An image at the display's spatial resolution: integrated over one group, across (and, for
// pinhole grids, also down: one vertical pinhole period seen on the image layer).
Image atDisplayResolution(const DisplayDesign& d, const Image& image) {
  Image out = boxFilterX(image, periodInPixels(d, image.width()));
  if (d.spec.mask.kind == MaskKind::Pinholes) {
    const double rowPeriodMm = d.spec.mask.verticalPeriodPx * d.spec.maskPanel.pitchMm *
                               (d.viewDistanceMm - d.imageLayerZ()) /
                               (d.viewDistanceMm - d.maskLayerZ());
    out = boxFilterY(out, rowPeriodMm / (d.frontHeightMm() / double(image.height())));
  }
  return out;
}

// The ideal view of the scene from the eye (one-axis perspective for slit displays), brought
// to the display's spatial resolution by a box filter one screen period wide.
Image referenceView(const Scene& scene, const Accelerator& accelerator, const DisplayDesign& d,
                    const Vec3d& eye, int width, int height, int spp, int threads) {
  const bool horizontalOnly = d.spec.mask.kind != MaskKind::Pinholes;
  const WindowCamera camera(eye, d, scene.display, width, height, horizontalOnly);
  RenderSettings settings;
  settings.samplesPerPixel = spp;
  settings.threads = threads;
  return atDisplayResolution(d, render(scene, accelerator, camera, settings));
}

void runSimulate(const SimulateOptions& o) {
  const Inputs in = loadInputs(o);
  const DisplayDesign& d = in.design;
  SimulationOptions sim;
  if (!o.size.empty()) parseSize("--size", o.size, sim.width, sim.height);
  sim.samplesPerPixel = o.spp;
  sim.pupilDiameterMm = o.pupil;
  sim.pupilSamples = o.pupilSamples;
  sim.diffuserSigmaMm = o.diffuser;
  sim.colourFilters = o.colourFilters;
  sim.normalise = !o.raw;
  sim.threads = o.threads;
  const Image maskLayer = in.layers.mask;
  const DisplaySimulator simulator(d, in.layers, sim);
  const std::vector<Vec3d> eyes = eyePositions(o, d);

  std::vector<Image> views;
  for (const Vec3d& eye : eyes) views.push_back(simulator.view(eye));
  // Pictures as perceived: a viewer at the design distance does not resolve single pixels
  // (0.27 mm at 600 mm is about 1.5 arc minutes), so each output pixel shows the light of one
  // screen period around it; --raw-pixels keeps the pinhole eye's samples as they are.
  std::vector<Image> pictures;
  for (const Image& view : views)
    pictures.push_back(o.rawPixels ? view : atDisplayResolution(d, view));

  std::vector<std::string> written;
  if (o.sweep > 0) {
    // The sweep's files share a prefix: a given extension is dropped (-o out/sweep.png).
    const fs::path out(o.output.empty() ? "out/sweep" : o.output);
    const std::string prefix = (out.parent_path() / out.stem()).string();
    std::vector<std::string> labels, pngs;
    for (const Vec3d& eye : eyes) labels.push_back(eyeLabel(eye));
    for (const Image& picture : pictures) pngs.push_back(pngBytes(picture));
    const int thumbnail = std::min(480, pictures.front().width());
    writeImage(prefix + "-sheet.png",
               contactSheet(pictures, std::min<int>(int(pictures.size()), 3), thumbnail, labels));
    writeFileAtomically(prefix + "-anim.png", encodeApng(pictures, 250));
    writeFileAtomically(prefix + ".html",
                        sliderPage("parallax: eye sweep across " + d.spec.source, pngs, labels));
    written = {prefix + "-sheet.png", prefix + "-anim.png", prefix + ".html"};
  } else {
    const std::string path = o.output.empty() ? "out/simulated.png" : o.output;
    for (size_t i = 0; i < views.size(); ++i) {
      writeImage(numbered(path, i, views.size()), pictures[i]);
      written.push_back(numbered(path, i, views.size()));
    }
  }

  std::vector<Quality> quality;
  if (o.reference) {
    const Scene scene = loadSceneOrDefault(in.scene);
    const Accelerator accelerator(scene);
    for (size_t i = 0; i < eyes.size(); ++i) {
      const Image reference = referenceView(scene, accelerator, d, eyes[i], views[i].width(),
                                            views[i].height(), o.referenceSpp, o.threads);
      Quality q;
      const Image seen = o.rawPixels ? atDisplayResolution(d, views[i]) : pictures[i];
      q.psnr = psnr(seen, reference);
      q.ssim = ssim(seen, reference);
      // Brightness is the raw mean transmittance, whatever --raw says for the pictures.
      SimulationOptions raw = sim;
      raw.normalise = false;
      const CrosstalkResult c = measureCrosstalk(d, maskLayer, raw, eyes[i]);
      q.brightness = c.brightness;
      q.crosstalk = c.crosstalk;
      q.ownView = c.ownView;
      quality.push_back(q);
    }
  }

  if (o.json) {
    JsonWriter json;
    json.set("/display", d.spec.source);
    for (size_t i = 0; i < written.size(); ++i)
      json.set("/outputs/" + std::to_string(i), written[i]);
    Quality mean;
    for (size_t i = 0; i < eyes.size(); ++i) {
      const std::string at = "/eyes/" + std::to_string(i);
      json.set(at + "/eye", Vec3f{float(eyes[i].x), float(eyes[i].y), float(eyes[i].z)});
      if (quality.empty()) continue;
      const Quality& q = quality[i];
      json.set(at + "/psnr", q.psnr);
      json.set(at + "/ssim", q.ssim);
      json.set(at + "/brightness", q.brightness);
      json.set(at + "/crosstalk", q.crosstalk);
      json.set(at + "/own_view", q.ownView);
      mean.psnr += q.psnr / double(eyes.size());
      mean.ssim += q.ssim / double(eyes.size());
      mean.brightness += q.brightness / double(eyes.size());
      mean.crosstalk += q.crosstalk / double(eyes.size());
    }
    if (!quality.empty()) {
      json.set("/mean/psnr", mean.psnr);
      json.set("/mean/ssim", mean.ssim);
      json.set("/mean/brightness", mean.brightness);
      json.set("/mean/crosstalk", mean.crosstalk);
    }
    std::printf("%s\n", json.dump().c_str());
    return;
  }
  for (const std::string& path : written) std::printf("wrote %s\n", path.c_str());
  if (quality.empty()) return;
  std::printf("%-24s %8s %7s %10s %9s %4s\n", "eye (mm)", "PSNR dB", "SSIM", "brightness",
              "crosstalk", "view");
  for (size_t i = 0; i < eyes.size(); ++i) {
    char eye[48];
    std::snprintf(eye, sizeof eye, "%.1f,%.1f,%.1f", eyes[i].x, eyes[i].y, eyes[i].z);
    const Quality& q = quality[i];
    std::printf("%-24s %8.2f %7.4f %10.4f %9.4f %4d\n", eye, q.psnr, q.ssim, q.brightness,
                q.crosstalk, q.ownView);
  }
}

}  // namespace

void registerSimulateCommand(CLI::App& cli) {
  auto o = std::make_shared<SimulateOptions>();
  CLI::App* cmd = cli.add_subcommand(
      "simulate", "See the display without hardware: what an eye in front of it sees");
  cmd->add_option("dir", o->dir,
                  "Output folder of `parallax render` (image.png, mask.png, "
                  "display.json, render.json)")
      ->capture_default_str();
  cmd->add_option("--image", o->image, "Image layer (instead of DIR/image.png)");
  cmd->add_option("--mask", o->mask, "Mask layer (instead of DIR/mask.png)");
  cmd->add_option("--display", o->display, "Display file (instead of DIR/display.json)");
  cmd->add_option("--eye", o->eyes,
                  "Eye position X,Y,Z in display mm (origin: front layer centre, z toward the "
                  "viewer); repeatable. Default: the view-zone centre");
  cmd->add_option("-o,--output", o->output,
                  "Output image (several eyes: FILE-K), or the prefix of the sweep's files");
  cmd->add_option("--size", o->size, "Output size WIDTHxHEIGHT (default: the front layer's)");
  cmd->add_option("--spp", o->spp, "Samples per output pixel (n*n)")->capture_default_str();
  cmd->add_option("--pupil", o->pupil, "Pupil diameter in mm (0: a pinhole eye)");
  cmd->add_option("--pupil-samples", o->pupilSamples, "Points averaged over the pupil")
      ->capture_default_str();
  cmd->add_option("--diffuser", o->diffuser,
                  "Blur of the rear layer by a diffuser foil, Gaussian sigma in mm");
  cmd->add_flag("--color-filters", o->colourFilters,
                "Model the R, G, B colour-filter stripes of both layers (rainbow fringes)");
  cmd->add_flag("--raw", o->raw, "Raw brightness (default: normalised by the aperture ratio)");
  cmd->add_flag("--raw-pixels", o->rawPixels,
                "Write the pinhole eye's samples unfiltered (default: integrated over one "
                "screen period, as a viewer at the design distance perceives them)");
  cmd->add_option("--sweep", o->sweep,
                  "Move the eye across the view zone in N steps: contact sheet, APNG, HTML");
  cmd->add_option("--sweep-range", o->sweepRange,
                  "Sweep width in view-zone widths (> 1 goes beyond the zone)")
      ->capture_default_str();
  cmd->add_option("--sweep-distance", o->sweepDistance, "Eye distance of the sweep (default D)");
  cmd->add_flag("--reference", o->reference,
                "Quality figures against the ideal view: PSNR, SSIM, brightness, cross-talk");
  cmd->add_option("--scene", o->scene, "Scene for --reference (default: from render.json)");
  cmd->add_option("--reference-spp", o->referenceSpp, "Samples per pixel of the ideal view")
      ->capture_default_str();
  cmd->add_option("--threads", o->threads, "Worker threads (0: all cores)");
  cmd->add_flag("--json", o->json, "Print one JSON object");
  cmd->callback([o] { runSimulate(*o); });
}

}  // namespace parallax::app

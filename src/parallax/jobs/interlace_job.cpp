// The interlace runner: the display, checked and estimated; the views, read or given; their
// mapping onto the display (the views themselves: interlace_views.h); the picture set written or
// kept.
#include "parallax/jobs/interlace_job.h"
#include "parallax/jobs/interlace_views.h"

#include <cmath>
#include <cstdio>
#include <memory>

#include "parallax/core/error.h"
#include "parallax/core/memory.h"
#include "parallax/io/image_file.h"
#include "parallax/io/json_writer.h"
#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/layer_output.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/simulate_job.h"

namespace parallax::jobs {

namespace {

// "9 views (round(views), views = 9)": what the display takes, for notes.
std::string viewsNeeded(const DisplayDesign& design) {
  return printed("%d views (%s, views = %g)", interlacedViewCount(design),
                 design.camera.subpixelRays ? "round(3 views) with subpixel rays" : "round(views)",
                 design.views);
}

// A lenticular panel: every subpixel takes the views its view fraction lies between, blended,
// as Looking Glass's interlacing shader does (render/quilt.h, interlaceQuiltLenticular).
Image interlaceLenticular(const InterlaceRequest& r, const LenticularDesign& design,
                          const Views& given, JsonWriter& record) {
  const ViewResampling resampling = viewResampling(r.viewResampling);
  Image panel = interlaceQuiltLenticular(design, given.images, resampling);
  startRenderRecord(record, "interlace", r.display.path, {}, {});
  record.set("/display_kind", "lenticular");
  recordInputs(record, r, given);
  record.set("/inputs/view_resampling", r.viewResampling);
  record.set("/inputs/view_mapping",
             resampling == ViewResampling::Nearest
                 ? "each subpixel's view fraction f picks view floor(f N), the nearest"
                 : "each subpixel's view fraction f between views f N - 1/2, blended linearly");
  return panel;
}

// A barrier: the views resampled to its count if need be, then interleaved by direct mapping.
Image interlaceBarrier(const InterlaceRequest& r, const DisplayModel& display,
                       const DisplayDesign& design, Views given, JsonWriter& record,
                       Reporter& reporter) {
  const int count = int(given.images.size()), needed = interlacedViewCount(design);
  if (count != needed) {
    // A standard quilt (48 views) on a 9-view barrier, or the reverse: resampled across views.
    reporter.note(printed("%d views given, the display takes %s: resampled across views (%s)",
                          count, viewsNeeded(design).c_str(), r.viewResampling.c_str()));
    given.images = resampleViews(given.images, needed, viewResampling(r.viewResampling));
  }
  const Panel& panel = design.spec.imagePanel;
  const Image& first = given.images[0];
  if (first.width() != panel.width || first.height() != panel.height)
    reporter.note(printed("resampling the views by area from %dx%d to the image layer's %dx%d",
                          first.width(), first.height(), panel.width, panel.height));
  Image image = interlaceCameraViews(design, given.images);

  startRenderRecord(record, "interlace", r.display.path, {}, {});
  recordInputs(record, r, given);
  record.set("/inputs/view_count", count);
  if (count != needed) record.set("/inputs/view_resampling", r.viewResampling);
  // Camera k (k-th from the left) feeds the design view seen from the k-th eye from the left.
  const std::vector<int> designView = designViewsLeftToRight(design);
  for (size_t k = 0; k < designView.size(); ++k) {
    const std::string at = "/cameras/" + std::to_string(k);
    const Vec3d eye = display.viewPosition(designView[k]);
    record.set(at + "/design_view", designView[k]);
    record.set(at + "/eye_mm", Vec3f(float(eye.x), float(eye.y), float(eye.z)));
  }
  return image;
}

// The picture set of either kind: the image (a panel picture) and the mask (barriers).
struct Interlaced {
  Image image, mask;
  JsonWriter record;
};

// Each kind's own way from views to its pictures, chosen once (interlacerFor): the display
// checked for it before the views are read, the views mapped, the set written.

std::string writeLenticularSet(const InterlaceRequest& r, const BuiltDisplay& display,
                               Interlaced& made, size_t views) {
  JsonWriter& record = made.record;
  record.set("/outputs/image", "image.png");
  record.set("/outputs/calibration", "visual.json");
  display.recordDesign(record, "/design");
  OutputSet set(r.output);
  writeImage(set.path("image.png"), made.image);
  if (r.linear) writeImage(set.path("image.pfm"), made.image);
  writeFileAtomically(set.path("visual.json"), display.file.text);
  writeFileAtomically(set.path("render.json"), record.dump() + "\n");
  set.commit();
  const char* dir = set.dir().c_str();
  return printed("wrote %s/image.png (%dx%d) from %zu views, %s/visual.json, %s/render.json", dir,
                 made.image.width(), made.image.height(), views, dir, dir);
}

class Interlacer {
 public:
  virtual ~Interlacer() = default;
  // The display as the views are interlaced for it (`built`: as the request's optics built
  // it), its pictures known to fit in memory; refusals of what does not apply to the kind.
  virtual BuiltDisplay prepare(const InterlaceRequest& r, const DisplayDescription& description,
                               BuiltDisplay built) const = 0;
  virtual bool writesMask() const = 0;
  virtual void interlace(const InterlaceRequest& r, const DisplayModel& display, Views given,
                         Interlaced& out, Reporter& reporter) const = 0;
  // Writes the set into r.output; returns the result line.
  virtual std::string write(const InterlaceRequest& r, const BuiltDisplay& display,
                            Interlaced& made, size_t views) const = 0;
};

class LenticularInterlacer final : public Interlacer {
 public:
  explicit LenticularInterlacer(const LenticularDesign& design) : design_(design) {}
  BuiltDisplay prepare(const InterlaceRequest& r, const DisplayDescription&,
                       BuiltDisplay built) const override {
    if (r.display.subpixels)
      throw RequestError("subpixels",
                         "applies to barrier displays; a lenticular panel is interlaced per "
                         "subpixel");
    const double w = design_.calibration.screenW, h = design_.calibration.screenH;
    checkMemoryEstimate(
        imageBytes(w, h, kFloatRgbPixelBytes, 2) + imageBytes(w, h, kRgba8PixelBytes),
        design_.calibration.source, "the panel image", "use a smaller panel");
    return built;
  }
  bool writesMask() const override { return false; }
  void interlace(const InterlaceRequest& r, const DisplayModel&, Views given, Interlaced& out,
                 Reporter&) const override {
    out.image = interlaceLenticular(r, design_, given, out.record);
  }
  std::string write(const InterlaceRequest& r, const BuiltDisplay& display, Interlaced& made,
                    size_t views) const override {
    return writeLenticularSet(r, display, made, views);
  }

 private:
  const LenticularDesign& design_;
};

class BarrierInterlacer final : public Interlacer {
 public:
  explicit BarrierInterlacer(const DisplayDesign& design) : design_(design) {}
  BuiltDisplay prepare(const InterlaceRequest& r, const DisplayDescription& description,
                       BuiltDisplay built) const override {
    if (r.display.subpixels) {
      DisplayCameraRequest camera;
      camera.subpixels = true;
      built = makeDisplay(description, camera);
    }
    const DisplayDesign& design = *built->barrierDesign();
    checkLayerMemory(design, design.spec.imagePanel.width, 1, r.display.named());
    return built;
  }
  bool writesMask() const override { return true; }
  void interlace(const InterlaceRequest& r, const DisplayModel& display, Views given,
                 Interlaced& out, Reporter& reporter) const override {
    out.image = interlaceBarrier(r, display, design_, std::move(given), out.record, reporter);
    out.mask = maskLayerImage(design_);
  }
  std::string write(const InterlaceRequest& r, const BuiltDisplay&, Interlaced& made,
                    size_t) const override {
    return writeDisplayLayers(r.output, made.image, made.mask, design_, r.linear, made.record);
  }

 private:
  const DisplayDesign& design_;
};

// The one place interlacing asks which kind a display is.
std::unique_ptr<Interlacer> interlacerFor(const DisplayModel& display) {
  if (const LenticularDesign* lenticular = display.lenticularDesign())
    return std::make_unique<LenticularInterlacer>(*lenticular);
  if (const DisplayDesign* barrier = display.barrierDesign())
    return std::make_unique<BarrierInterlacer>(*barrier);
  throw RequestError("display", "cannot be interlaced: a display of kind " +
                                    std::string(displayKindName(display.kind())) +
                                    " has no interlacer");
}

// The display, built for interlacing, once its pictures are known to fit in memory; and its
// interlacer.
struct InterlaceTarget {
  BuiltDisplay display;
  std::unique_ptr<Interlacer> interlacer;
};
InterlaceTarget interlaceDisplay(const InterlaceRequest& r, Reporter& reporter) {
  const DisplayDescription description = r.display.describe(reporter);
  DisplayCameraRequest optics;  // subpixels: the interlacer's to refuse or build (prepare)
  optics.lens = r.display.lens;
  BuiltDisplay built = makeDisplay(description, optics);  // a barrier refuses lens optics
  std::unique_ptr<Interlacer> interlacer = interlacerFor(*built);
  BuiltDisplay display = interlacer->prepare(r, description, std::move(built));
  // The interlacer holds its kind's design: made again for the display it prepared.
  interlacer = interlacerFor(*display);
  return {std::move(display), std::move(interlacer)};
}

void interlace(const InterlaceTarget& target, const InterlaceRequest& r, Views given,
               Interlaced& out, Reporter& reporter) {
  noteQuiltAspect(given, *target.display, reporter);
  target.interlacer->interlace(r, *target.display, std::move(given), out, reporter);
}

}  // namespace

void runInterlace(const InterlaceRequest& r, Reporter& reporter) {
  viewResampling(r.viewResampling);
  const InterlaceTarget target = interlaceDisplay(r, reporter);
  // Before the views are read: where the set goes can take it (docs/inputs.md, "Outputs").
  OutputSet::check(r.output, pictureSetNames(1, target.interlacer->writesMask(), r.linear,
                                             target.display.file.name));
  Views given = readViews(r);
  const size_t count = given.images.size();
  Interlaced made;
  interlace(target, r, std::move(given), made, reporter);
  reporter.result(target.interlacer->write(r, target.display, made, count));
}

InterlaceResult interlaceInMemory(const InterlaceRequest& r, const std::vector<Image>& views,
                                  const Image& quilt, Reporter& reporter) {
  viewResampling(r.viewResampling);
  const InterlaceTarget target = interlaceDisplay(r, reporter);
  Interlaced made;
  interlace(target, r, givenViews(r, views, quilt), made, reporter);
  target.display.recordDesign(made.record, "/design");
  return {std::move(made.image), std::move(made.mask), made.record.dump()};
}

}  // namespace parallax::jobs

#include "parallax/sim/simulated_display.h"

#include "parallax/core/error.h"
#include "parallax/sim/lenticular_sim.h"

namespace parallax {

namespace {

class SimulatedBarrier final : public SimulatedDisplay {
 public:
  SimulatedBarrier(const DisplayDesign& design, LayerImages layers,
                   const SimulationOptions& options)
      : design_(design), simulator_(design, std::move(layers), options) {}
  Image view(const Vec3d& eyeMm) const override { return simulator_.view(eyeMm); }
  Image atDisplayResolution(const Image& image) const override {
    return parallax::atDisplayResolution(design_, image);
  }
  Image seen(const Vec3d& eyeMm) const override { return simulator_.seen(eyeMm); }

 private:
  DisplayDesign design_;
  DisplaySimulator simulator_;
};

class SimulatedLenticular final : public SimulatedDisplay {
 public:
  SimulatedLenticular(const LenticularDesign& design, Image panel)
      : design_(design), panel_(std::move(panel)), subpixels_(lenticularSubpixels(design_)) {}
  Image view(const Vec3d& eyeMm) const override {
    return simulateLenticularView(design_, panel_, eyeMm, &subpixels_);
  }
  // One lens along a pixel row, one colour cycle of the slanted lenses along a column.
  Image atDisplayResolution(const Image& image) const override {
    return lenticularAtDisplayResolution(design_, image);
  }

 private:
  LenticularDesign design_;
  Image panel_;
  LenticularSubpixels subpixels_;  // made once: the same for every eye
};

// Frames seen in turn: the average of their views.
class SimulatedFrames final : public SimulatedDisplay {
 public:
  explicit SimulatedFrames(std::vector<std::unique_ptr<SimulatedDisplay>> frames)
      : frames_(std::move(frames)) {}
  Image view(const Vec3d& eyeMm) const override {
    return mean([&](const SimulatedDisplay& frame) { return frame.view(eyeMm); });
  }
  Image atDisplayResolution(const Image& image) const override {
    return frames_.front()->atDisplayResolution(image);
  }
  // The box is linear: the mean of the frames' pictures at the display's resolution.
  Image seen(const Vec3d& eyeMm) const override {
    return mean([&](const SimulatedDisplay& frame) { return frame.seen(eyeMm); });
  }

 private:
  std::vector<std::unique_ptr<SimulatedDisplay>> frames_;
  // The mean over the frames of picture(frame).
  template <class Picture>
  Image mean(const Picture& picture) const {
    Image sum = picture(*frames_.front());
    for (size_t k = 1; k < frames_.size(); ++k) {
      const Image next = picture(*frames_[k]);
      for (size_t i = 0; i < sum.pixels().size(); ++i) sum.pixels()[i] += next.pixels()[i];
    }
    const float inv = 1.0f / float(frames_.size());
    for (Vec3f& p : sum.pixels()) p = p * inv;
    return sum;
  }
};

}  // namespace

std::unique_ptr<SimulatedDisplay> simulateDisplay(const DisplayModel& display,
                                                  std::vector<LayerImages> frames,
                                                  const SimulationOptions& options) {
  if (frames.empty()) throw std::invalid_argument("simulateDisplay: no frames");
  if (frames.size() == 1) return simulateDisplay(display, std::move(frames.front()), options);
  std::vector<std::unique_ptr<SimulatedDisplay>> each;
  for (LayerImages& f : frames) each.push_back(simulateDisplay(display, std::move(f), options));
  return std::make_unique<SimulatedFrames>(std::move(each));
}

std::unique_ptr<SimulatedDisplay> simulateDisplay(const DisplayModel& display, LayerImages layers,
                                                  const SimulationOptions& options) {
  if (const DisplayDesign* barrier = display.barrierDesign())
    return std::make_unique<SimulatedBarrier>(*barrier, std::move(layers), options);
  const LenticularDesign* lenticular = display.lenticularDesign();
  if (!lenticular) throw std::invalid_argument("simulateDisplay: an unknown display kind");
  if (!layers.mask.empty())
    throw InputError(display.source(), "", "a lenticular display has no mask layer");
  return std::make_unique<SimulatedLenticular>(
      options.lensOptics ? withOptics(*lenticular, *options.lensOptics) : *lenticular,
      std::move(layers.image));
}

}  // namespace parallax

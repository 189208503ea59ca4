// The lens sheet's readings (lens_readings.h).
#include "parallax/jobs/lens_readings.h"

#include "parallax/jobs/display_factory.h"
#include "parallax/jobs/reporter.h"

namespace parallax::jobs {

std::optional<LensOptics> lensReading(const DisplayModel& display, const LensReadingRequest& lens) {
  if (const LenticularDesign* lenticular = display.lenticularDesign())
    return lensReading(*lenticular, lens);
  refuseLensReading(lens);
  return std::nullopt;
}

std::vector<std::pair<std::string, LensOptics>> lensReadings(const DisplayModel& display) {
  const LenticularDesign* lenticular = display.lenticularDesign();
  if (!lenticular) return {};
  const LenticularDesign& design = *lenticular;
  std::vector<std::pair<std::string, LensOptics>> readings;
  const auto label = [](const LensOptics& o) {
    return printed("spot %g, %s", o.spotWidthSubpixels, lensBundlesName(o.bundles));
  };
  for (const double spot : {0.0, 3.0})
    for (const LensBundles bundles : {LensBundles::Parallel, LensBundles::Converging}) {
      LensOptics o = design.optics;
      o.spotWidthSubpixels = spot, o.bundles = bundles;
      readings.push_back({label(o), o});
    }
  readings.push_back({label(design.optics) + " (the display's)", design.optics});
  return readings;
}

std::string lensReadingLine(const DisplayModel& display, const SimulationOptions& options) {
  const LenticularDesign* lenticular = display.lenticularDesign();
  if (!lenticular) return "";
  const LensOptics o =
      withOptics(*lenticular, options.lensOptics.value_or(lenticular->optics)).optics;
  return printed("seen through lenses with a %g-subpixel focal spot, bundles ",
                 o.spotWidthSubpixels) +
         (o.bundles == LensBundles::Parallel
              ? std::string("parallel")
              : printed("converging at %.0f mm", o.convergenceDistanceMm));
}

}  // namespace parallax::jobs

#include "parallax/io/display_file.h"

#include <optional>
#include <utility>

#include "parallax/display/lenticular_presets.h"
#include "parallax/io/lenticular_file.h"

#include <cmath>

#include "parallax/core/error.h"
#include "parallax/io/json_reader.h"

namespace parallax {

namespace {

const char* subpixelName(SubpixelOrder o) {
  return o == SubpixelOrder::RGB ? "RGB" : (o == SubpixelOrder::BGR ? "BGR" : "none");
}
const char* orderName(LayerOrder o) {
  return o == LayerOrder::BarrierBack ? "barrier-back" : "barrier-front";
}
const char* maskName(MaskKind k) {
  switch (k) {
    case MaskKind::Slits:
      return "slits";
    case MaskKind::Slanted:
      return "slanted";
    case MaskKind::Wiggling:
      return "wiggling";
    case MaskKind::Jittered:
      return "jittered";
    case MaskKind::Pinholes:
      return "pinholes";
  }
  return "?";
}

Panel readPanel(const JsonReader& node, const Panel& fallback) {
  node.expectObject({"resolution", "pixel_pitch_mm", "subpixels"});
  Panel p = fallback;
  if (auto r = node.find("resolution")) {
    const auto e = r->elements();
    if (e.size() != 2) r->fail("expected [width, height] in pixels");
    p.width = e[0].integer(1, 1 << 16);
    p.height = e[1].integer(1, 1 << 16);
  }
  if (auto pitch = node.find("pixel_pitch_mm")) {
    p.pitchMm = pitch->number();  // double: periods are derived from it to 1e-9 mm
    if (!(p.pitchMm > 0)) pitch->fail("expected a positive number of mm");
  }
  if (auto s = node.find("subpixels")) {
    const std::string name = s->string();
    if (name == "RGB" || name == "rgb")
      p.subpixels = SubpixelOrder::RGB;
    else if (name == "BGR" || name == "bgr")
      p.subpixels = SubpixelOrder::BGR;
    else if (name == "none")
      p.subpixels = SubpixelOrder::None;
    else
      s->fail("expected \"RGB\", \"BGR\" or \"none\", got \"" + name + "\"");
  }
  return p;
}

MaskSpec readMask(const JsonReader& node) {
  node.expectObject({"type", "duty_cycle", "phase_px", "panel_offset_px", "angle_deg",
                     "amplitude_mm", "wavelength_mm", "jitter", "seed", "vertical_period_px"});
  MaskSpec m;
  const std::string type = node.string("type", "slits");
  if (type == "slits")
    m.kind = MaskKind::Slits;
  else if (type == "slanted")
    m.kind = MaskKind::Slanted;
  else if (type == "wiggling")
    m.kind = MaskKind::Wiggling;
  else if (type == "jittered")
    m.kind = MaskKind::Jittered;
  else if (type == "pinholes")
    m.kind = MaskKind::Pinholes;
  else
    node["type"].fail("expected slits, slanted, wiggling, jittered or pinholes, got \"" + type +
                      "\"");
  const auto number = [&node](std::string_view key, double fallback) {
    const auto v = node.find(key);
    return v ? v->number() : fallback;
  };
  m.dutyCycle = number("duty_cycle", m.dutyCycle);
  m.phasePx = number("phase_px", 0.0);
  m.panelOffsetPx = number("panel_offset_px", 0.0);
  m.slantDegrees = number("angle_deg", 0.0);
  m.wiggleAmplitudeMm = number("amplitude_mm", 0.0);
  m.wiggleWavelengthMm = number("wavelength_mm", 0.0);
  m.jitterAmplitude = number("jitter", 0.0);
  m.jitterSeed = uint64_t(node.integer("seed", 1, 0, 1 << 30));
  m.verticalPeriodPx = number("vertical_period_px", 0.0);
  return m;
}

}  // namespace

BarrierDisplayFile loadDisplayFile(const std::string& path) {
  const JsonDocument doc = JsonDocument::parseFile(path);
  return readDisplayFile(doc.root(), path);
}

BarrierDisplayFile readDisplayFile(const JsonReader& root, const std::string& path) {
  root.expectObject({"image_layer", "mask_layer", "layer_order", "gap_mm", "view_distance_mm",
                     "view_zone", "views", "screen_period_px", "slit_period_px", "mask", "virtual",
                     "subpixel_rays", "name", "version", "diffuser_sigma_mm"});
  DisplaySpec s = defaultDisplaySpec();
  s.source = path;
  if (auto n = root.find("image_layer")) s.imagePanel = readPanel(*n, s.imagePanel);
  // The mask layer defaults to a copy of the image layer (two identical panels).
  s.maskPanel = s.imagePanel;
  if (auto n = root.find("mask_layer")) s.maskPanel = readPanel(*n, s.imagePanel);
  if (auto n = root.find("layer_order")) {
    const std::string order = n->string();
    if (order == "barrier-back")
      s.order = LayerOrder::BarrierBack;
    else if (order == "barrier-front")
      s.order = LayerOrder::BarrierFront;
    else
      n->fail("expected \"barrier-back\" or \"barrier-front\", got \"" + order + "\"");
  }
  if (auto n = root.find("gap_mm")) s.gapMm = n->number();
  if (auto n = root.find("diffuser_sigma_mm")) {
    s.diffuserSigmaMm = n->number();
    if (!(s.diffuserSigmaMm >= 0 && s.diffuserSigmaMm <= 100))
      n->fail("must be a blur of 0 to 100 mm (Gaussian sigma)");
  }
  const bool measured = root.has("screen_period_px") || root.has("slit_period_px");
  const bool byZone = root.find("view_zone") && (*root.find("view_zone")).has("width_mm");
  // Defaults that another given quantity replaces: views and D are derived, not assumed.
  if (measured || byZone) s.views.reset();
  if (measured) s.viewDistanceMm.reset();
  if (auto n = root.find("view_distance_mm")) s.viewDistanceMm = n->number();
  if (auto n = root.find("views")) s.views = n->number();
  if (auto n = root.find("screen_period_px")) s.screenPeriodPx = n->number();
  if (auto n = root.find("slit_period_px")) s.slitPeriodPx = n->number();
  if (auto zone = root.find("view_zone")) {
    zone->expectObject({"center_x_mm", "height_mm", "width_mm"});
    if (auto n = zone->find("center_x_mm")) s.viewZoneCenterXMm = n->number();
    if (auto n = zone->find("height_mm")) s.viewZoneHeightMm = n->number();
    if (auto n = zone->find("width_mm")) s.viewZoneWidthMm = n->number();
  }
  if (auto n = root.find("mask")) s.mask = readMask(*n);
  BarrierCameraSettings camera;
  camera.subpixelRays = root.boolean("subpixel_rays", false);
  if (auto v = root.find("virtual")) {
    v->expectObject({"gap_mm", "distance_mm"});
    if (auto n = v->find("gap_mm")) camera.virtualGapMm = n->number();
    if (auto n = v->find("distance_mm")) {
      if (n->isString()) {
        if (n->string() != "infinity") n->fail("expected a number of mm or \"infinity\"");
        camera.virtualDistanceMm = kInfinity;
      } else {
        camera.virtualDistanceMm = n->number();
      }
    }
  }
  return {s, camera};
}

std::string displayFileText(const DisplaySpec& s, const BarrierCameraSettings& camera) {
  JsonWriter json;
  const auto panel = [&json](const std::string& at, const Panel& p) {
    json.set(at + "/resolution/0", p.width);
    json.set(at + "/resolution/1", p.height);
    json.set(at + "/pixel_pitch_mm", p.pitchMm);
    json.set(at + "/subpixels", subpixelName(p.subpixels));
  };
  panel("/image_layer", s.imagePanel);
  panel("/mask_layer", s.maskPanel);
  json.set("/layer_order", orderName(s.order));
  json.set("/gap_mm", s.gapMm);
  if (s.diffuserSigmaMm > 0) json.set("/diffuser_sigma_mm", s.diffuserSigmaMm);
  if (s.viewDistanceMm && !(s.screenPeriodPx && s.slitPeriodPx))
    json.set("/view_distance_mm", *s.viewDistanceMm);
  json.set("/view_zone/center_x_mm", s.viewZoneCenterXMm);
  json.set("/view_zone/height_mm", s.viewZoneHeightMm);
  if (s.viewZoneWidthMm) json.set("/view_zone/width_mm", *s.viewZoneWidthMm);
  if (s.views && !s.viewZoneWidthMm && !s.screenPeriodPx) json.set("/views", *s.views);
  if (s.screenPeriodPx) json.set("/screen_period_px", *s.screenPeriodPx);
  if (s.slitPeriodPx) json.set("/slit_period_px", *s.slitPeriodPx);
  const MaskSpec& m = s.mask;
  json.set("/mask/type", maskName(m.kind));
  json.set("/mask/duty_cycle", m.dutyCycle);
  json.set("/mask/phase_px", m.phasePx);
  if (m.panelOffsetPx != 0.0) json.set("/mask/panel_offset_px", m.panelOffsetPx);
  if (m.kind == MaskKind::Slanted) json.set("/mask/angle_deg", m.slantDegrees);
  if (m.kind == MaskKind::Wiggling) {
    json.set("/mask/amplitude_mm", m.wiggleAmplitudeMm);
    json.set("/mask/wavelength_mm", m.wiggleWavelengthMm);
  }
  if (m.kind == MaskKind::Jittered) {
    json.set("/mask/jitter", m.jitterAmplitude);
    json.set("/mask/seed", uint64_t(m.jitterSeed));
  }
  if (m.kind == MaskKind::Pinholes) json.set("/mask/vertical_period_px", m.verticalPeriodPx);
  json.set("/subpixel_rays", camera.subpixelRays);
  if (camera.virtualGapMm) json.set("/virtual/gap_mm", *camera.virtualGapMm);
  if (camera.virtualDistanceMm) {
    if (std::isinf(*camera.virtualDistanceMm))
      json.set("/virtual/distance_mm", "infinity");
    else
      json.set("/virtual/distance_mm", *camera.virtualDistanceMm);
  }
  return json.dump() + "\n";
}

void writeDisplayDesignJson(JsonWriter& json, const std::string& at, const DisplayModel& display) {
  if (const DisplayDesign* barrier = display.barrierDesign()) writeDesignJson(json, at, *barrier);
  if (const LenticularDesign* lenticular = display.lenticularDesign())
    writeLenticularDesignJson(json, at, *lenticular);
}

void writeDesignJson(JsonWriter& json, const std::string& at, const DisplayDesign& d) {
  const auto finiteOr = [&json, &at](const std::string& key, double v) {
    if (std::isinf(v))
      json.set(at + key, "infinity");
    else
      json.set(at + key, v);
  };
  json.set(at + "/source", d.spec.source);
  json.set(at + "/layer_order", orderName(d.spec.order));
  json.set(at + "/mask_type", maskName(d.spec.mask.kind));
  json.set(at + "/image_resolution/0", d.spec.imagePanel.width);
  json.set(at + "/image_resolution/1", d.spec.imagePanel.height);
  json.set(at + "/mask_resolution/0", d.spec.maskPanel.width);
  json.set(at + "/mask_resolution/1", d.spec.maskPanel.height);
  json.set(at + "/image_pixel_pitch_mm", d.spec.imagePanel.pitchMm);
  json.set(at + "/mask_pixel_pitch_mm", d.spec.maskPanel.pitchMm);
  json.set(at + "/subpixels", subpixelName(d.spec.imagePanel.subpixels));
  json.set(at + "/subpixel_rays", d.camera.subpixelRays);
  json.set(at + "/gap_mm", d.gapMm);
  json.set(at + "/view_distance_mm", d.viewDistanceMm);
  json.set(at + "/view_zone_center_x_mm", d.spec.viewZoneCenterXMm);
  json.set(at + "/view_zone_height_mm", d.spec.viewZoneHeightMm);
  json.set(at + "/screen_period_mm", d.screenPeriodMm);
  json.set(at + "/screen_period_px", d.screenPeriodPx);
  json.set(at + "/slit_period_mm", d.slitPeriodMm);
  json.set(at + "/slit_period_px", d.slitPeriodPx);
  json.set(at + "/views", d.views);
  json.set(at + "/apertures", d.aperturesAcross);
  json.set(at + "/apertures_down", d.aperturesDown);
  json.set(at + "/aperture_span_mm", d.apertureSpanMm);
  json.set(at + "/view_zone_width_mm", d.viewZoneWidthMm);
  json.set(at + "/view_width_mm", d.viewWidthMm);
  json.set(at + "/depth_of_field_mm", d.depthOfFieldMm);
  finiteOr("/farthest_consistent_distance_mm", d.farthestConsistentDistanceMm);
  json.set(at + "/duty_cycle", d.spec.mask.dutyCycle);
  json.set(at + "/phase_px", d.spec.mask.phasePx);
  json.set(at + "/panel_offset_px", d.spec.mask.panelOffsetPx);
  const MaskSpec& m = d.spec.mask;
  if (m.kind == MaskKind::Slanted) json.set(at + "/mask_angle_deg", m.slantDegrees);
  if (m.kind == MaskKind::Wiggling) {
    json.set(at + "/mask_amplitude_mm", m.wiggleAmplitudeMm);
    json.set(at + "/mask_wavelength_mm", m.wiggleWavelengthMm);
  }
  if (m.kind == MaskKind::Jittered) {
    json.set(at + "/mask_jitter", m.jitterAmplitude);
    json.set(at + "/mask_seed", uint64_t(m.jitterSeed));
  }
  if (m.kind == MaskKind::Pinholes) json.set(at + "/mask_vertical_period_px", m.verticalPeriodPx);
  json.set(at + "/virtual_gap_mm", d.virtualGapMm);
  finiteOr("/virtual_distance_mm", d.virtualDistanceMm);
}

DisplayDescription loadDisplayDescription(const std::string& pathOrPreset) {
  DisplayDescription d;
  if (pathOrPreset.empty()) {
    d.barrier = defaultDisplaySpec();
    return d;
  }
  if (pathOrPreset.rfind("lkg:", 0) == 0) {
    const std::optional<LenticularCalibration> preset = lenticularPreset(pathOrPreset.substr(4));
    if (!preset)
      throw InputError(pathOrPreset, "",
                       "no such Looking Glass preset; the presets are " + lenticularPresetNames());
    d.kind = DisplayKind::Lenticular;
    d.lenticular = *preset;
    return d;
  }
  const JsonDocument doc = JsonDocument::parseFile(pathOrPreset);
  const JsonReader root = doc.root();
  if (root.isObject() && (root.has("pitch") || root.has("slope") || root.has("DPI"))) {
    d.kind = DisplayKind::Lenticular;
    d.lenticular = readLenticularCalibration(root);
  } else {
    BarrierDisplayFile file = readDisplayFile(root, pathOrPreset);
    d.barrier = std::move(file.spec);
    d.camera = file.camera;
  }
  return d;
}

}  // namespace parallax

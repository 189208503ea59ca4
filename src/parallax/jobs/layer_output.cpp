#include "parallax/jobs/layer_output.h"

#include <algorithm>
#include <cmath>
#include <ctime>
#include <vector>

#include "parallax/core/memory.h"
#include "parallax/core/parallel.h"
#include "parallax/io/display_file.h"
#include "parallax/io/image_file.h"
#include "parallax/jobs/limits.h"
#include "parallax/jobs/reporter.h"
#include "parallax/jobs/requests.h"

namespace parallax::jobs {

namespace {

std::string utcNow() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

}  // namespace

std::vector<std::string> pictureSetNames(size_t frames, bool mask, bool linear,
                                         const std::string& displayFileName) {
  std::vector<std::string> names;
  if (frames > 1) {
    for (size_t k = 1; k <= frames; ++k)
      names.insert(names.end(),
                   {"image-" + std::to_string(k) + ".png", "mask-" + std::to_string(k) + ".png"});
  } else {
    names.push_back("image.png");
    if (mask) names.push_back("mask.png");
    if (linear) names.push_back("image.pfm");
  }
  if (!displayFileName.empty()) names.push_back(displayFileName);
  names.push_back("render.json");
  return names;
}

void startRenderRecord(JsonWriter& record, const std::string& method,
                       const std::string& displayFile, const ImportOptions& options,
                       const std::vector<Scene::ImportRecord>& imports) {
  record.set("/program", "parallax");
  record.set("/version", PARALLAX_VERSION);
  record.set("/created", utcNow());
  record.set("/method", method);
  record.set("/display_file", displayFile.empty() ? std::string("<built-in>") : displayFile);
  // docs/import.md, "What was done": the command's import options (which simulate's
  // loadSceneAsRendered reuses) and one object per mesh file, in loading order.
  record.set("/import_options/up", upAxisName(options.up));
  record.set("/import_options/crease", double(options.creaseDegrees));
  record.setEmptyArray("/import");
  for (size_t i = 0; i < imports.size(); ++i) {
    const std::string at = "/import/" + std::to_string(i);
    record.set(at + "/file", imports[i].file);
    record.set(at + "/reader", imports[i].reader);
    record.set(at + "/up", imports[i].up);
    record.set(at + "/normals", imports[i].normals);
    record.set(at + "/triangles", uint64_t(imports[i].triangles));
    if (imports[i].splats) record.set(at + "/splats", uint64_t(imports[i].splats));
  }
}

void checkLayerMemory(const DisplayDesign& design, double filmColumns, double views,
                      const std::string& subject) {
  const Panel &image = design.spec.imagePanel, &mask = design.spec.maskPanel;
  const double bytes = imageBytes(filmColumns, image.height, kFloatRgbPixelBytes, views) +
                       imageBytes(image.width, image.height) + imageBytes(mask.width, mask.height) +
                       imageBytes(image.width, image.height, kRgba8PixelBytes) +
                       imageBytes(mask.width, mask.height, kRgba8PixelBytes);
  checkMemoryEstimate(bytes, subject,
                      "the layers (" + std::to_string(image.width) + "x" +
                          std::to_string(image.height) + " image, " + std::to_string(mask.width) +
                          "x" + std::to_string(mask.height) + " mask" +
                          (views > 1 ? ", " + std::to_string(int64_t(views)) + " views" : "") + ")",
                      "use a smaller display");
}

void checkLayerWork(const DisplayDesign& design, bool directMapping, int spp, int threads,
                    const std::string& displayPath) {
  const Panel& panel = design.spec.imagePanel;
  const double subpixel = design.camera.subpixelRays ? 3.0 : 1.0;
  const double views =
      directMapping ? std::max(1.0, std::round(design.screenPeriodPx * subpixel)) : 1.0;
  const double columns = directMapping ? panel.width : panel.width * subpixel;
  const std::string subject = displayPath.empty() ? "<built-in display>" : displayPath;
  checkLayerMemory(design, columns, views, subject);
  checkTimeEstimate(columns * panel.height * views * spp, threads, "spp", std::to_string(spp),
                    "use fewer samples");
}

void checkQuiltWork(int columns, int rows, int width, int height, int spp, int threads,
                    const std::string& sizeText, bool linear) {
  const double views = double(columns) * rows;
  const std::string layout = std::to_string(columns) + "x" + std::to_string(rows) +
                             (sizeText.empty() ? "" : " {size} " + sizeText);
  const std::string subject = "{quilt} " + layout;
  // The quilt's 8-bit codes and its PNG (at most about as large), a float quilt only for
  // --linear, and one view at a time (its film, and its copy in the tile).
  const double bytes = (linear ? imageBytes(width, height, kFloatRgbPixelBytes, views) : 0.0) +
                       imageBytes(width, height, 2 * kRgba8PixelBytes, views) +
                       imageBytes(width, height, kFloatRgbPixelBytes, 2);
  checkMemoryEstimate(bytes, subject, "the quilt", "use fewer views or a smaller {size}");
  checkPixelCount(views * width * height, subject);
  checkTimeEstimate(views * width * height * spp, threads, "quilt", layout,
                    "use fewer views or samples");
}

namespace {

// DIR/image.png, mask.png (image.pfm with `linear`), the display's file and render.json (the
// record, with /outputs added); several frames: image-K.png, mask-K.png.
std::string writeLayerPictures(const std::string& output, const std::vector<LayerFrame>& frames,
                               bool linear, const DisplayFile& file, JsonWriter& record) {
  if (frames.size() > 1) {
    std::vector<std::string> imagePngs(frames.size()), maskPngs(frames.size());
    for (size_t k = 0; k < frames.size(); ++k) {
      const std::string n = std::to_string(k + 1);
      record.set("/frames/" + std::to_string(k) + "/image", "image-" + n + ".png");
      record.set("/frames/" + std::to_string(k) + "/mask", "mask-" + n + ".png");
      parallelInvoke(
          0, [&] { imagePngs[k] = pngBytes(frames[k].image); },
          [&] { maskPngs[k] = pngBytes(frames[k].mask); });
    }
    record.set("/outputs/" + file.recordKey, file.name);
    OutputSet set(output);
    for (size_t k = 0; k < frames.size(); ++k) {
      const std::string n = std::to_string(k + 1);
      writeFileAtomically(set.path("image-" + n + ".png"), imagePngs[k]);
      writeFileAtomically(set.path("mask-" + n + ".png"), maskPngs[k]);
    }
    writeFileAtomically(set.path(file.name), file.text);
    writeFileAtomically(set.path("render.json"), record.dump() + "\n");
    set.commit();
    return printed("wrote %s/image-1..%zu.png, %s/mask-1..%zu.png (%dx%d), %s/render.json",
                   set.dir().c_str(), frames.size(), set.dir().c_str(), frames.size(),
                   frames[0].image.width(), frames[0].image.height(), set.dir().c_str());
  }
  const Image &image = frames[0].image, &mask = frames[0].mask;
  record.set("/outputs/image", "image.png");
  record.set("/outputs/mask", "mask.png");
  record.set("/outputs/" + file.recordKey, file.name);
  if (linear) record.set("/outputs/image_linear", "image.pfm");

  // Both pictures encoded at once (each on every core as well: io/png_encoder.h).
  std::string imagePng, maskPng;
  const auto encodeImage = [&] { imagePng = pngBytes(image); };
  const auto encodeMask = [&] { maskPng = pngBytes(mask); };
  parallelInvoke(0, encodeImage, encodeMask);
  OutputSet set(output);
  writeFileAtomically(set.path("image.png"), imagePng);
  writeFileAtomically(set.path("mask.png"), maskPng);
  if (linear) writeImage(set.path("image.pfm"), image);
  // The display as a display file, so that `simulate DIR` and other tools can read it back.
  writeFileAtomically(set.path(file.name), file.text);
  writeFileAtomically(set.path("render.json"), record.dump() + "\n");
  set.commit();
  const char* dir = set.dir().c_str();
  return printed("wrote %s/image.png (%dx%d), %s/mask.png (%dx%d), %s/render.json", dir,
                 image.width(), image.height(), dir, mask.width(), mask.height(), dir);
}

DisplayFile barrierFile(const DisplayDesign& design) {
  return {"display.json", displayFileText(design.spec, design.camera), "display"};
}

}  // namespace

std::string writeDisplayLayers(const std::string& output, const Image& image, const Image& mask,
                               const DisplayDesign& design, bool linear, JsonWriter& record) {
  writeDesignJson(record, "/design", design);
  return writeLayerPictures(output, {{image, mask}}, linear, barrierFile(design), record);
}

std::string writePictureSet(const std::string& output, const std::vector<LayerFrame>& frames,
                            bool linear, const DisplayFile& file, JsonWriter& record) {
  if (frames.size() > 1 || !frames[0].mask.empty())
    return writeLayerPictures(output, frames, linear, file, record);
  const Image& image = frames[0].image;
  record.set("/outputs/image", "image.png");
  if (file.written()) record.set("/outputs/" + file.recordKey, file.name);
  if (linear) record.set("/outputs/image_linear", "image.pfm");
  OutputSet set(output);
  writeImage(set.path("image.png"), image);
  if (linear) writeImage(set.path("image.pfm"), image);
  // The display's file beside the picture, so that `lenticular simulate DIR` finds it.
  if (file.written()) writeFileAtomically(set.path(file.name), file.text);
  writeFileAtomically(set.path("render.json"), record.dump() + "\n");
  set.commit();
  const char* dir = set.dir().c_str();
  const std::string beside = file.written() ? printed("%s/%s, ", dir, file.name.c_str()) : "";
  return printed("wrote %s/image.png (%dx%d), %s%s/render.json", dir, image.width(), image.height(),
                 beside.c_str(), dir);
}

std::string writeLayerFrames(const std::string& output, const std::vector<LayerFrame>& frames,
                             const DisplayDesign& design, JsonWriter& record) {
  writeDesignJson(record, "/design", design);
  return writeLayerPictures(output, frames, false, barrierFile(design), record);
}

}  // namespace parallax::jobs

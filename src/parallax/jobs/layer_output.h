// The outputs shared by `render`, `render --quilt`, `interlace` and `lenticular render`: the
// display's two layer images with display.json and a render.json record of how they were made,
// written as one set.
#pragma once

#include <string>
#include <vector>

#include "parallax/display/display.h"
#include "parallax/image/image.h"
#include "parallax/io/json_writer.h"
#include "parallax/io/mesh_file.h"
#include "parallax/layers/layer_solver.h"
#include "parallax/scene/scene.h"

namespace parallax::jobs {

// A set of output files written into a folder DIR that may hold other files (docs/inputs.md,
// "Outputs"). The files are written into a hidden temporary folder inside DIR
// (DIR/.parallax-tmp-PID: created there, it takes DIR's group, setgid bit and default ACL, and
// its files are on DIR's file system); commit() then renames each file into DIR, in the order
// path() was first asked for it (the record, render.json, last), so that a reader sees a new
// record only with its files in place. DIR itself is never replaced: its mode, owner, group and
// ACL stay as they are.
//
// Only files parallax wrote are replaced: a name is ours when DIR/.parallax-outputs (the list
// commit() keeps) or DIR's render.json (a record whose /program is "parallax": /outputs and
// /frames) or index.json (calibration patterns) lists it. commit() refuses, before the first
// rename, a name held by a folder, a link, a special file or a file that is not ours
// (check() says the same before any work). Files of ours that the new set does not have (the
// image-2.png of an earlier rank-2 set) are removed: the new record no longer describes them.
//
// A commit is rolled forward: before the first rename, a marker listing the files is written in
// the temporary folder; a later OutputSet for DIR that finds a temporary folder of a process
// that no longer runs finishes its renames when the marker is there, and removes the folder
// when it is not. Without commit (an exception), the temporary folder is removed and DIR is as
// it was. Commits into one folder are serialised (flock on DIR).
//
// Create it only when everything has been read and computed: it makes DIR.
class OutputSet {
 public:
  explicit OutputSet(const std::string& dir);
  ~OutputSet();
  OutputSet(const OutputSet&) = delete;
  OutputSet& operator=(const OutputSet&) = delete;

  // Where to write `name` (a plain file name) now; `name` joins the set.
  std::string path(const std::string& name);
  // The folder as the user named it, for messages.
  const std::string& dir() const { return dir_; }
  void commit();

  // Before any work: refuses (InputError) a DIR that is a file or cannot be written (or whose
  // nearest existing ancestor cannot), and each of `names` that DIR holds as something commit()
  // would not replace.
  static void check(const std::string& dir, const std::vector<std::string>& names);

  // Tests only: called after each file commit() renames into DIR (1, 2, ...), so that a test
  // can stop a commit halfway as a kill would.
  static void setCommitHookForTests(void (*hook)(size_t renamed));

 private:
  std::string dir_, folder_, temporary_;
  std::vector<std::string> names_;
  bool committed_ = false;
};

// The names a picture set of writePictureSet() writes: image.png, mask.png (with `mask`),
// image.pfm (`linear`), image-K.png and mask-K.png for `frames` > 1, the display's file and
// render.json; for OutputSet::check before the work.
std::vector<std::string> pictureSetNames(size_t frames, bool mask, bool linear,
                                         const std::string& displayFileName);

// Program, version, time, method and display file at the top of a render.json record, and
// /import: what loading the command's scenes did with each mesh file (importRecords()).
void startRenderRecord(JsonWriter& record, const std::string& method,
                       const std::string& displayFile, const ImportOptions& options,
                       const std::vector<Scene::ImportRecord>& imports);

// Refuses (naming `subject`) layers that would not fit in memory: the image layer's film
// (`filmColumns` wide: three per pixel with subpixel rays, times `views` for N ordinary views),
// the two layers and their 8-bit copies for the PNG writer.
void checkLayerMemory(const DisplayDesign& design, double filmColumns, double views,
                      const std::string& subject);

// Both estimates of `render` before it allocates: the layers (checkLayerMemory; with
// `directMapping` one ordinary view per interleaved view) and the time of `spp` samples per
// film pixel. `displayPath` names the display ("" = built-in) in the refusal.
void checkLayerWork(const DisplayDesign& design, bool directMapping, int spp, int threads,
                    const std::string& displayPath);

// The quilt of `render --quilt`: its 8-bit codes and PNG, the float quilt with `linear`, one
// view at a time, and the time; refusals name the quilt field ("{quilt} CxR") and the size.
void checkQuiltWork(int columns, int rows, int width, int height, int spp, int threads,
                    const std::string& sizeText, bool linear);

// Writes DIR/image.png, mask.png (image.pfm with `linear`), display.json and render.json (the
// record, with /outputs and /design added) as one set, and says where on stdout.
// Returns the line that says what was written.
std::string writeDisplayLayers(const std::string& output, const Image& image, const Image& mask,
                               const DisplayDesign& design, bool linear, JsonWriter& record);

// The display's own file written beside its pictures: display.json (a barrier) or visual.json
// (a lenticular calibration), and its key under /outputs ("display", "calibration").
struct DisplayFile {
  std::string name, text, recordKey;
};

// A display's pictures as one set in `output`, with its file and render.json (the record, with
// /outputs added; /design is the caller's): one frame with a mask (writeDisplayLayers' files),
// several (writeLayerFrames'), or a panel picture without a mask (image.png). Returns the line
// that says what was written.
std::string writePictureSet(const std::string& output, const std::vector<LayerFrame>& frames,
                            bool linear, const DisplayFile& file, JsonWriter& record);

// Time-multiplexed layers (render --layers nmf --rank T): DIR/image-K.png and mask-K.png for
// K = 1..T, shown in turn, with display.json and render.json (/frames lists the pairs), as one
// set.
std::string writeLayerFrames(const std::string& output, const std::vector<LayerFrame>& frames,
                             const DisplayDesign& design, JsonWriter& record);

}  // namespace parallax::jobs

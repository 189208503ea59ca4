#include "parallax/jobs/sequence.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "parallax/core/error.h"
#include "parallax/io/json_writer.h"

namespace parallax::jobs {
namespace {

// The N parts of a range cover it once, in order, each within one frame of the others' length.
TEST(Chunk, PartsCoverTheFramesOnceAndEvenly) {
  for (const auto& [first, last] : {std::pair{1, 120}, {5, 17}, {3, 3}, {1, 7}}) {
    for (int n = 1; n <= 12; ++n) {
      int next = first, shortest = 1 << 30, longest = 0;
      for (int k = 1; k <= n; ++k) {
        int a = first, b = last;
        narrowToChunk(std::to_string(k) + "/" + std::to_string(n), a, b);
        EXPECT_EQ(a, next) << first << ":" << last << " part " << k << "/" << n;
        EXPECT_GE(b, a - 1);
        shortest = std::min(shortest, b - a + 1);
        longest = std::max(longest, b - a + 1);
        next = b + 1;
      }
      EXPECT_EQ(next, last + 1);
      EXPECT_LE(longest - shortest, 1);
    }
  }
}

TEST(Chunk, RefusesWhatIsNotKOfN) {
  for (const char* bad : {"", "3", "0/4", "5/4", "1/0", "a/2", "1/-2", "1:2", "2/"}) {
    int a = 1, b = 10;
    EXPECT_THROW(narrowToChunk(bad, a, b), InputError) << bad;
  }
}

// A frame's /made_from against a resume's: the same passes; any difference is refused naming
// the setting and both values (or the file that changed), and how to start over.
TEST(MadeFrom, AResumeWithOtherSettingsIsRefusedNamingTheSetting) {
  const std::filesystem::path folder =
      std::filesystem::temp_directory_path() / ("made-from-" + std::to_string(getpid()));
  std::filesystem::create_directories(folder);
  const std::string scene = (folder / "scene.json").string();
  std::ofstream(scene) << "{}";
  MadeFrom made{{"{spp}", "1"}, {"{layers}", "slits"}};
  addFileContent(made, scene);
  addFileContent(made, "");                                  // nothing for no file
  addFileContent(made, (folder / "missing.json").string());  // nor for a preset's name
  ASSERT_EQ(made.size(), 3u);
  EXPECT_EQ(made[2].first, "content of " + scene);
  JsonWriter record;
  record.set("/program", "parallax");
  recordMadeFrom(record, made);
  const std::string file = (folder / "render.json").string();
  std::ofstream(file) << record.dump();
  const auto refusal = [&](const MadeFrom& asked) -> std::string {
    try {
      checkMadeFrom(file, "seq/frame-0003", asked, "seq");
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(refusal(made), "");
  MadeFrom spp = made;
  spp[0].second = "4";
  EXPECT_EQ(refusal(spp),
            "seq/frame-0003: {spp}: it was made with 1, this run asks 4; the frames of one "
            "sequence must match: give another {output}, or remove seq to start over");
  std::ofstream(scene) << "{ }";
  MadeFrom changed{{"{spp}", "1"}, {"{layers}", "slits"}};
  addFileContent(changed, scene);
  EXPECT_NE(refusal(changed).find("was made from another version of " + scene), std::string::npos);
  std::ofstream(scene) << "{}";
  EXPECT_NE(refusal({made[0], made[2]}).find("{layers}: it was made with slits, this run has none"),
            std::string::npos);
  std::ofstream(file) << R"({"program": "parallax"})";  // an earlier version's frame
  EXPECT_NE(refusal(made).find("without a record of its settings"), std::string::npos);
  std::filesystem::remove_all(folder);
}

}  // namespace
}  // namespace parallax::jobs

// The assimp route in a child process (isolated_import.cpp, docs/import.md "Isolation"): the
// crafted files of issue 28 and a child made to abort, crash, allocate without bound, spin or
// sleep are refused with their own message while this process goes on; the answer through the
// child equals the in-process conversion field by field; a damaged answer is refused.
#include <fcntl.h>
#include <signal.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <vector>

#include "parallax/importer/assimp_importer.h"
#include "parallax/importer/isolated_import.h"
#include "parallax/importer/mesh_readers.h"
#include "parallax/importer/mesh_test_support.h"

namespace parallax {
namespace {

using namespace meshtest;
using meshio::FileContents;

std::string regression(const std::string& name) {
  return std::string(PARALLAX_SOURCE_DIR) + "/fuzz/regressions/fuzz_assimp/" + name;
}

// Small budgets, restored after each test; the fault hook cleared.
class Isolated : public ::testing::Test {
 protected:
  void SetUp() override { setImporterLimits({512 * 1024.0 * 1024.0, 2}); }
  void TearDown() override {
    meshio::childFaultForTests = nullptr;
    setImporterLimits({});
  }
  // The InputError of reading `path` through the child (with the fault hook as set).
  static std::string refusal(const std::string& path) {
    try {
      meshio::readAssimp(path);
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      const std::string what = e.what();
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
      return what;
    }
    ADD_FAILURE() << path << ": no InputError";
    return {};
  }
};

#define EXPECT_CONTAINS(text, part) \
  EXPECT_NE(std::string(text).find(part), std::string::npos) << (text) << "\n lacks: " << (part)

// ---- the crafted files of issue 28 (../shared/reliability) ---------------------------------

// Debian 12's assimp (5.2) frees twice reading this FBX; 5.4 (Debian 13's 5.4.3) reads it.
// Where it crashes, the crash is the child's; where it reads, it is an ordinary model.
bool fbxDoubleFreeCrashesThisAssimp() {
  const LibraryVersion v = assimpVersion();
  return v.major < 5 || (v.major == 5 && v.minor < 4);
}

TEST_F(Isolated, DoubleFreeInTheFbxImporterIsACrashOfTheChild) {
  const std::string path = regression("crash-2c65eb78.fbx");
  if (!fbxDoubleFreeCrashesThisAssimp()) {
    size_t triangles = 0;
    for (const auto& part : meshio::readAssimp(path).parts) triangles += part.indices.size() / 3;
    EXPECT_GT(triangles, 0u);
    return;
  }
  const std::string what = refusal(path);
  EXPECT_CONTAINS(what, "crash-2c65eb78.fbx: the FBX importer (assimp) crashed reading it (");
  EXPECT_CONTAINS(what, "the file is damaged or not supported");
}

TEST_F(Isolated, SegfaultInTheXImporterIsACrashOfTheChild) {
  const std::string what = refusal(regression("crash-cb1d3a87.x"));
  EXPECT_CONTAINS(what, "the X importer (assimp) crashed reading it (");
  // The sanitizers' SIGSEGV handler is reset in the child: the signal is named in any build.
  EXPECT_CONTAINS(what, "signal 11, SIGSEGV");
}

// Touching 0.5 GiB costs 2 s of CPU time on a virtual machine with slow page faults (measured:
// 0.9 s user + 1.1 s system), so the tests of the memory budget give the child a CPU budget the
// memory budget is reached well within (the wall-clock limit is then 2 x 8 + 5 = 21 s).
constexpr double kMemoryTestCpuSeconds = 8;

TEST_F(Isolated, ColladaGrowingWithoutBoundRunsOutOfItsBudget) {
  setImporterLimits({512 * 1024.0 * 1024.0, kMemoryTestCpuSeconds});
  const auto start = std::chrono::steady_clock::now();
  const std::string what = refusal(regression("timeout-25565c.dae"));
  EXPECT_CONTAINS(what,
                  "the DAE importer (assimp) ran out of its memory budget reading it "
                  "(0.5 GiB, {max_memory})");
  // Bounded by the memory budget, not by the wall-clock limit (21 s).
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 15);
}

TEST_F(Isolated, CraftedFilesThroughLoadMeshFileLeaveTheSceneUnchanged) {
  for (const char* name : {"crash-2c65eb78.fbx", "crash-cb1d3a87.x", "timeout-25565c.dae"})
    if (std::string(name) != "crash-2c65eb78.fbx" || fbxDoubleFreeCrashesThisAssimp())
      expectInputError(regression(name), "(assimp)");
}

// ---- each kind of failure, made on purpose ---------------------------------------------------

std::string anyModel() {
  return dataDir() + "/assimp/OFF/Cube.off";
}

TEST_F(Isolated, AbortIsNamedBySignal) {
  meshio::childFaultForTests = [] { abort(); };
  EXPECT_CONTAINS(refusal(anyModel()),
                  "Cube.off: the OFF importer (assimp) crashed reading it (signal 6, SIGABRT); "
                  "the file is damaged or not supported");
}

TEST_F(Isolated, SegfaultIsNamedBySignal) {
  meshio::childFaultForTests = [] { raise(SIGSEGV); };
  EXPECT_CONTAINS(refusal(anyModel()), "crashed reading it (signal 11, SIGSEGV)");
}

// Large blocks (the address-space limit; under ASan its secondary allocator) and small ones
// (under ASan its primary allocator, whose regions are reserved up front: the parent's watch
// of the child's private memory stops it).
TEST_F(Isolated, AllocatingWithoutBoundRunsOutOfTheBudget) {
  setImporterLimits({512 * 1024.0 * 1024.0, kMemoryTestCpuSeconds});
  for (size_t block : {size_t(64) << 20, size_t(4) << 10}) {
    static size_t blockSize;
    blockSize = block;
    meshio::childFaultForTests = [] {
      for (;;) {
        char* p = new char[blockSize];
        std::memset(p, 1, blockSize);
      }
    };
    const auto start = std::chrono::steady_clock::now();
    EXPECT_CONTAINS(refusal(anyModel()),
                    "the OFF importer (assimp) ran out of its memory budget reading it (0.5 GiB, "
                    "{max_memory}); the file is damaged or needs a larger {max_memory}");
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 15)
        << block;
  }
}

TEST_F(Isolated, SpinningIsStoppedAtTheCpuBudget) {
  meshio::childFaultForTests = [] {
    volatile unsigned long spins = 0;
    for (;;) spins = spins + 1;
  };
  EXPECT_CONTAINS(refusal(anyModel()),
                  "the OFF importer (assimp) took more than 2 s of CPU time reading it; the file "
                  "is damaged or not supported");
}

TEST_F(Isolated, SleepingIsStoppedAtTheWallClockLimit) {
  setImporterLimits({512 * 1024.0 * 1024.0, 0.5});  // wall clock: 2 x 0.5 + 5 = 6 s
  meshio::childFaultForTests = [] {
    for (;;) pause();
  };
  const auto start = std::chrono::steady_clock::now();
  EXPECT_CONTAINS(refusal(anyModel()),
                  "the OFF importer (assimp) did not answer within 6 s; the file is damaged or "
                  "not supported");
  const double seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_GE(seconds, 6);
  EXPECT_LT(seconds, 8);
}

TEST_F(Isolated, AGarbledAnswerIsRefused) {
  meshio::childFaultForTests = [] {
    const char garbage[] = "not the flat layout at all";
    if (write(3, garbage, sizeof(garbage)) < 0) _exit(1);
    _exit(0);
  };
  EXPECT_CONTAINS(refusal(anyModel()),
                  "the OFF importer (assimp) returned a damaged answer (not an answer)");
}

TEST_F(Isolated, AnExitWithoutAnswerIsRefused) {
  meshio::childFaultForTests = [] { _exit(0); };
  EXPECT_CONTAINS(refusal(anyModel()), "the OFF importer (assimp) ended without an answer");
  meshio::childFaultForTests = [] { _exit(3); };
  EXPECT_CONTAINS(refusal(anyModel()), "ended without an answer (exit code 3)");
}

// What the child inherits: /dev/null for 0-2, the answer's memfd at 3 (and under ASan the
// sanitizer report's at 4), no other descriptor of this process, no core dumps, a CPU limit.
// A violation makes the child abort, which the test sees as a refusal.
TEST_F(Isolated, TheChildKeepsNoDescriptorOfTheParentAndHasItsLimits) {
  const int inherited = open(anyModel().c_str(), O_RDONLY);  // not close-on-exec
  ASSERT_GE(inherited, 0);
  meshio::childFaultForTests = [] {
    for (int fd = 0; fd <= 2; ++fd) {
      char target[64] = {};
      const std::string link = "/proc/self/fd/" + std::to_string(fd);
      if (readlink(link.c_str(), target, sizeof(target) - 1) < 0 ||
          std::string(target) != "/dev/null")
        abort();
    }
    for (int fd = 5; fd < 4096; ++fd)
      if (fcntl(fd, F_GETFD) != -1) abort();
    rlimit limit;
    if (getrlimit(RLIMIT_CORE, &limit) != 0 || limit.rlim_cur != 0) abort();
    if (getrlimit(RLIMIT_CPU, &limit) != 0 || limit.rlim_cur != 2) abort();
    if (getrlimit(RLIMIT_AS, &limit) != 0 || limit.rlim_cur == RLIM_INFINITY) abort();
    // Output goes nowhere near the user's terminal.
    std::printf("from the child\n");
    std::fflush(stdout);
  };
  const FileContents contents = meshio::readAssimp(anyModel());
  EXPECT_EQ(contents.parts.size(), 1u);
  close(inherited);
}

// A SIGCHLD handler that reaps every child (or SIGCHLD ignored, where the kernel reaps them)
// takes the child's status from us: the answer still decides, and the wait ends.
TEST_F(Isolated, ChildrenReapedElsewhereStillGiveTheirAnswer) {
  struct sigaction reaper = {};
  struct sigaction previous = {};
  reaper.sa_handler = [](int) {
    const int saved = errno;
    while (waitpid(-1, nullptr, WNOHANG) > 0) {
    }
    errno = saved;
  };
  for (const bool ignore : {false, true}) {
    SCOPED_TRACE(ignore ? "SIG_IGN" : "a reaping handler");
    struct sigaction action = reaper;
    if (ignore) action.sa_handler = SIG_IGN;
    ASSERT_EQ(sigaction(SIGCHLD, &action, &previous), 0);
    EXPECT_EQ(meshio::readAssimp(anyModel()).parts.size(), 1u);
    meshio::childFaultForTests = [] { abort(); };
    EXPECT_CONTAINS(refusal(anyModel()), "the OFF importer (assimp)");
    meshio::childFaultForTests = nullptr;
    sigaction(SIGCHLD, &previous, nullptr);
  }
}

TEST_F(Isolated, AnImporterRefusalKeepsItsMessage) {
  TempDir dir;
  const std::string path = dir.file("broken.fbx");
  writeFile(path, "this is no FBX at all");
  std::string inProcess;
  try {
    meshio::readAssimpInProcess(path);
  } catch (const InputError& e) {
    inProcess = e.what();
  }
  ASSERT_FALSE(inProcess.empty());
  EXPECT_EQ(refusal(path), inProcess);
}

// ---- the answer: through the child equals in process ----------------------------------------

void expectSameBytes(const void* a, const void* b, size_t bytes, const std::string& what) {
  EXPECT_EQ(std::memcmp(a, b, bytes), 0) << what;
}

template <typename T, typename A>
void expectSameArray(const std::vector<T, A>& a, const std::vector<T, A>& b,
                     const std::string& what) {
  ASSERT_EQ(a.size(), b.size()) << what;
  if (!a.empty()) expectSameBytes(a.data(), b.data(), a.size() * sizeof(T), what);
}

void expectSameMaterial(const Material& a, const Material& b) {
  EXPECT_EQ(a.name, b.name);
  expectSameBytes(&a.diffuse, &b.diffuse, sizeof(Vec3f), "diffuse");
  EXPECT_EQ(a.diffuseTexture, b.diffuseTexture);
  expectSameBytes(&a.mirror, &b.mirror, sizeof(Vec3f), "mirror");
  expectSameBytes(&a.emission, &b.emission, sizeof(Vec3f), "emission");
}

// Every field, bit for bit.
void expectSameContents(const FileContents& a, const FileContents& b) {
  ASSERT_EQ(a.parts.size(), b.parts.size());
  for (size_t i = 0; i < a.parts.size(); ++i) {
    SCOPED_TRACE("part " + std::to_string(i));
    const auto &p = a.parts[i], &q = b.parts[i];
    EXPECT_EQ(p.context, q.context);
    EXPECT_EQ(p.material, q.material);
    EXPECT_EQ(p.fileFromPart.matrix(), q.fileFromPart.matrix());
    EXPECT_EQ(p.fileFromPart.inverseMatrix(), q.fileFromPart.inverseMatrix());
    EXPECT_EQ(p.node, q.node);
    EXPECT_EQ(p.nodeNames, q.nodeNames);
    expectSameArray(p.positions, q.positions, "positions");
    expectSameArray(p.normals, q.normals, "normals");
    expectSameArray(p.uvs, q.uvs, "uvs");
    expectSameArray(p.indices, q.indices, "indices");
    expectSameArray(p.colors, q.colors, "colors");
  }
  ASSERT_EQ(a.materials.size(), b.materials.size());
  for (size_t i = 0; i < a.materials.size(); ++i) {
    SCOPED_TRACE("material " + std::to_string(i));
    expectSameMaterial(a.materials[i].material, b.materials[i].material);
    EXPECT_EQ(a.materials[i].image, b.materials[i].image);
  }
  ASSERT_EQ(a.images.size(), b.images.size());
  for (size_t i = 0; i < a.images.size(); ++i) {
    EXPECT_EQ(a.images[i].width(), b.images[i].width());
    EXPECT_EQ(a.images[i].height(), b.images[i].height());
    expectSameArray(a.images[i].pixels(), b.images[i].pixels(), "image " + std::to_string(i));
  }
  EXPECT_EQ(a.warnings, b.warnings);
  EXPECT_EQ(a.note, b.note);
  EXPECT_EQ(a.droppedDegenerate, b.droppedDegenerate);
  EXPECT_EQ(a.declaredUp, b.declaredUp);
  EXPECT_TRUE(b.cameras.empty() && b.lights.empty() && b.nodeAnimation.nodes.empty());
}

TEST_F(RealModels, AssimpThroughTheChildEqualsInProcess) {
  setImporterLimits({});
  // Between them: textures from a file and embedded, missing textures (warnings), normals,
  // UVs, several parts with node transforms, materials, an FBX's declared up axis.
  size_t images = 0, warnings = 0, parts = 0, declared = 0;
  for (const char* name :
       {"assimp/Collada/duck.dae", "assimp/FBX/spider.fbx",
        "assimp/FBX/embedded_ascii/box_embedded_texture_fragmented.fbx", "assimp/FBX/box.fbx",
        "assimp/OFF/Cube.off", "assimp/3DS/cube_with_diffuse_texture.3DS",
        "assimp/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb"}) {
    SCOPED_TRACE(name);
    const FileContents inProcess = meshio::readAssimpInProcess(model(name));
    const FileContents isolated = meshio::readAssimp(model(name));
    expectSameContents(inProcess, isolated);
    images += isolated.images.size();
    warnings += isolated.warnings.size();
    parts += isolated.parts.size();
    declared += isolated.declaredUp != UpAxis::Auto;
  }
  // The comparison saw each kind of field filled.
  EXPECT_GE(images, 2u);
  EXPECT_GE(warnings, 1u);
  EXPECT_GE(parts, 20u);
  EXPECT_GE(declared, 1u);
}

// A FileContents with every field the layout carries filled, also those assimp leaves empty
// (vertex colours, a note, dropped faces).
FileContents everyField() {
  FileContents c;
  Image image(3, 2);
  for (size_t i = 0; i < image.pixels().size(); ++i)
    image.pixels()[i] = {float(i), 0.25f * float(i), -1.0f / float(i + 1)};
  c.images.push_back(image);
  c.images.emplace_back();  // 0 x 0
  meshio::FileMaterial m;
  m.material.name = "wood \"oak\"\n";
  m.material.diffuse = {0.1f, 0.2f, 0.3f};
  m.material.diffuseTexture = 7;
  m.material.mirror = {0.4f, 0.5f, 0.6f};
  m.material.emission = {1e30f, 0, 2};
  m.image = 0;
  c.materials.push_back(m);
  c.materials.push_back({});
  meshio::FilePart part;
  part.context = "node 'a' mesh 'b'";
  part.nodeNames = {"a", "the parent of a"};
  part.material = 1;
  part.fileFromPart = Transform::rotate(30, {1, 2, 3}) * Transform::translate({4, 5, 6});
  part.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  part.normals = {{0, 0, 1}, {0, 0, 1}, {0, 0, 1}};
  part.uvs = {{0, 0}, {1, 0}, {0, 1}};
  part.indices = {0, 1, 2, 2, 1, 0};
  part.colors = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  c.parts.push_back(part);
  c.parts.emplace_back();  // empty, default material
  c.warnings = {"first", "", "third \xe2\x9c\x93"};
  c.note = "a note";
  c.droppedDegenerate = 12345678901ull;
  c.declaredUp = UpAxis::Z;
  return c;
}

TEST(IsolatedLayout, EveryFieldRoundTrips) {
  const FileContents original = everyField();
  expectSameContents(original,
                     meshio::parseContents(meshio::serializeContents(original), "f", "importer"));
  // And through a child process.
  expectSameContents(original, meshio::readIsolated("f", "importer", [](const std::string&) {
                       return everyField();
                     }));
}

TEST(IsolatedLayout, WhatTheLayoutDoesNotCarryIsNotSilentlyDropped) {
  FileContents contents;
  contents.cameras.emplace_back();
  EXPECT_THROW(meshio::serializeContents(contents), std::logic_error);
}

std::string parseError(std::string_view blob) {
  try {
    meshio::parseContents(blob, "f.fbx", "the FBX importer (assimp)");
  } catch (const InputError& e) {
    return e.what();
  }
  return "(parsed)";
}

TEST(IsolatedLayout, EveryTruncationIsRefused) {
  const std::string blob = meshio::serializeContents(everyField());
  for (size_t size = 0; size < blob.size(); ++size)
    ASSERT_TRUE(parseError(blob.substr(0, size))
                    .starts_with("f.fbx: the FBX importer (assimp) returned a damaged answer ("))
        << size << " of " << blob.size() << " bytes: " << parseError(blob.substr(0, size));
  EXPECT_CONTAINS(parseError(blob + "x"), "bytes after the end");
}

// Any single byte changed: refused or parsed, never beyond the blob (ASan build) and never an
// index out of range for loadMeshFile (material, image, node) or a per-vertex array of another
// size than the positions.
TEST(IsolatedLayout, GarbledBytesAreRefusedOrConsistent) {
  const std::string blob = meshio::serializeContents(everyField());
  size_t refused = 0;
  for (size_t i = 0; i < blob.size(); ++i)
    for (unsigned char value : {0x00, 0x01, 0x7f, 0xff}) {
      std::string garbled = blob;
      garbled[i] = char(value);
      try {
        const FileContents c = meshio::parseContents(garbled, "f.fbx", "the FBX importer");
        for (const auto& m : c.materials) ASSERT_LT(m.image, int(c.images.size()));
        for (const auto& p : c.parts) {
          ASSERT_GE(p.material, -1);
          ASSERT_LT(p.material, int(c.materials.size()));
          ASSERT_EQ(p.node, -1);
          ASSERT_TRUE(p.normals.empty() || p.normals.size() == p.positions.size());
          ASSERT_TRUE(p.uvs.empty() || p.uvs.size() == p.positions.size());
          ASSERT_TRUE(p.colors.empty() || p.colors.size() == p.positions.size());
        }
        for (const auto& image : c.images)
          ASSERT_EQ(image.pixels().size(), size_t(image.width()) * size_t(image.height()));
      } catch (const InputError& e) {
        ++refused;
        ASSERT_TRUE(std::string(e.what()).starts_with("f.fbx: the FBX importer returned a damaged"))
            << e.what();
      }
    }
  // Changed marks (magic and kind at the start, the end mark) are always refused.
  size_t changedMarks = 0;
  for (size_t i = 0; i < blob.size(); ++i)
    for (unsigned char value : {0x00, 0x01, 0x7f, 0xff})
      changedMarks += (i < 12 || i >= blob.size() - 8) && char(value) != blob[i];
  EXPECT_GE(refused, changedMarks);
  EXPECT_GT(changedMarks, 70u);
}

TEST(IsolatedLayout, AHugeCountIsRefusedWithoutAllocatingForIt) {
  std::string blob = meshio::serializeContents(everyField());
  const uint64_t huge = uint64_t(1) << 60;
  std::memcpy(&blob[12], &huge, sizeof(huge));  // the image count, after magic and kind
  EXPECT_CONTAINS(parseError(blob), "image count: count 1152921504606846976 beyond the bytes");
}

// ---- the cost (docs/import.md, "Isolation") --------------------------------------------------
// Run by hand: parallax_io_test --gtest_also_run_disabled_tests --gtest_filter='*IsolationCost*'
// Median of 9 loads of each model: in process (warm: this process has read it before), in a
// child that answers nothing (the conversion in a fresh process, as a command's single load
// is), through the child with the answer (readAssimp), and loadMeshFile's whole load.
TEST_F(RealModels, DISABLED_IsolationCost) {
  setImporterLimits({});
  const auto median = [](auto&& run) {
    std::vector<double> ms;
    for (int i = 0; i < 9; ++i) {
      const auto start = std::chrono::steady_clock::now();
      run();
      ms.push_back(
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count());
    }
    std::sort(ms.begin(), ms.end());
    return ms[ms.size() / 2];
  };
  std::printf("%-28s %11s %11s %11s %11s %11s\n", "model (through assimp)", "in-process",
              "child, mute", "child", "overhead", "full load");
  for (const char* name :
       {"bunny.obj", "assimp/Collada/duck.dae", "assimp/FBX/spider.fbx",
        "assimp/glTF2/2CylinderEngine-glTF-Binary/2CylinderEngine.glb", "assimp/OFF/Cube.off"}) {
    const std::string path = model(name);
    meshio::readAssimpInProcess(path);  // warm the page cache
    const double inProcess = median([&] { meshio::readAssimpInProcess(path); });
    const double mute = median([&] {
      meshio::readIsolated(path, "assimp", [](const std::string& p) {
        meshio::readAssimpInProcess(p);
        return FileContents{};
      });
    });
    const double child = median([&] { meshio::readAssimp(path); });
    MeshLoadOptions forced;
    forced.forceAssimp = true;
    const double full = median([&] { load(path, forced); });
    std::printf("%-28s %8.2f ms %8.2f ms %8.2f ms %8.2f ms %8.2f ms\n",
                fs::path(name).filename().string().c_str(), inProcess, mute, child,
                child - inProcess, full);
  }
}

}  // namespace
}  // namespace parallax

// Malformed and nonsense input: every case must end in one InputError naming the file (and
// the key), never in a crash, a hang, a huge allocation or an exception of another type.
#include <sys/stat.h>

#include "parallax/importer/mesh_test_support.h"
#include "parallax/importer/scene_file.h"
#include "parallax/io/display_file.h"
#include "parallax/io/image_file.h"
#include "parallax/io/input_file.h"
#include "parallax/io/json_reader.h"
#include "parallax/io/lenticular_file.h"

namespace parallax {
namespace {

using namespace meshtest;

// Runs `f`, which must throw an InputError whose text contains every needle and no newline.
template <typename F>
void expectRefused(F f, std::initializer_list<std::string> needles) {
  try {
    f();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    for (const std::string& needle : needles)
      EXPECT_NE(what.find(needle), std::string::npos)
          << "'" << what << "' lacks '" << needle << "'";
  }
}

TEST(MalformedInput, PlyWithASecondVertexElementWithoutProperties) {
  TempDir dir;
  const std::string path = dir.file("two.ply");
  writeFile(path,
            "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
            "property float z\nelement vertex 2\nelement face 1\n"
            "property list uchar int vertex_indices\nend_header\n"
            "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n");
  expectInputError(path, "more than one 'vertex' element");
}

TEST(MalformedInput, PlyHeaderEndingAtTheEndOfTheFile) {
  TempDir dir;
  const std::string path = dir.file("eof.ply");
  writeFile(path,
            "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\n"
            "property float y\nproperty float z\nend_header");
  expectInputError(path, "more than the file can hold");
}

TEST(MalformedInput, JsonNestedTooDeep) {
  const std::string text = std::string(65000, '[') + std::string(65000, ']');
  expectRefused([&] { JsonDocument::parseText(text, "deep.json"); },
                {"deep.json", "nested more than 256 levels"});
  // 256 levels are fine.
  EXPECT_NO_THROW(JsonDocument::parseText(std::string(256, '[') + std::string(256, ']'), "ok"));
}

TEST(MalformedInput, JsonNumberOverflowNamesTheKey) {
  expectRefused([] { JsonDocument::parseText(R"({"objects": [{"radius": 1e400}]})", "o.json"); },
                {"o.json: /objects/0/radius:", "number out of range"});
  expectRefused([] { JsonDocument::parseText(R"({"a": [1, 2, -1e999]})", "o.json"); },
                {"o.json: /a/2:"});
}

TEST(MalformedInput, ControlCharactersInKeysStayOnOneLine) {
  const JsonDocument doc = JsonDocument::parseText("{\"bad\\nkey\": 1}", "k.json");
  expectRefused([&] { doc.root().expectObject({"good"}); }, {"k.json: /bad\\nkey: unknown key"});
  expectRefused([] { JsonDocument::parseText("{\"a\\u001b\": 1, \"a\\u001b\": 2}", "k.json"); },
                {"duplicate key 'a\\x1b'"});
  EXPECT_EQ(escapeControl("a\nb\tc\x01"), "a\\nb\\tc\\x01");
}

TEST(MalformedInput, FloatFieldsMustBeFiniteInFloat) {
  const JsonDocument doc = JsonDocument::parseText(R"({"r": 1e39, "c": [0, 1e39, 0],
      "tiny": 1e-300, "ok": 3e38})",
                                                   "f.json");
  expectRefused([&] { doc.root()["r"].positive(); }, {"/r:", "beyond the float range"});
  expectRefused([&] { doc.root()["c"].vec3(); }, {"/c/1:"});
  expectRefused([&] { doc.root()["tiny"].positive(); }, {"/tiny:", "positive"});
  EXPECT_FLOAT_EQ(doc.root()["ok"].real(), 3e38f);
}

// A scene file with one sphere whose fields are `fields`, plus `extra` top-level members.
std::string sphereScene(const std::string& fields, const std::string& extra = "") {
  return R"({"objects": [{"shape": "sphere", )" + fields + "}]" + extra + "}";
}

TEST(MalformedInput, SceneQuantitiesOutOfRange) {
  TempDir dir;
  const auto refused = [&](const std::string& text, const std::string& key) {
    const std::string path = dir.file("s.json");
    writeFile(path, text);
    expectRefused([&] { loadScene(path); }, {"s.json: " + key + ":"});
  };
  refused(sphereScene(R"("radius": 1e39)"), "/objects/0/radius");
  refused(sphereScene(R"("radius": 1e7)"), "/objects/0/radius");
  refused(sphereScene(R"("radius": 1, "center": [1e39, 0, 0])"), "/objects/0/center/0");
  refused(sphereScene(R"("radius": 1, "center": [1e7, 0, 0])"), "/objects/0/center");
  refused(sphereScene(R"("radius": 1)", R"(, "camera": {"eye": [0,0,5], "look_at": [0,0,0],
      "fov": 1e-30})"),
          "/camera/fov");
  refused(sphereScene(R"("radius": 1)", R"(, "camera": {"eye": [0,0,5], "look_at": [0,0,0],
      "fov": 179.5})"),
          "/camera/fov");
  refused(sphereScene(R"("radius": 1, "transform": [{"scale": 1e30}])"),
          "/objects/0/transform/0/scale");
  refused(sphereScene(R"("radius": 1)", R"(, "ambient": 1e30)"), "/ambient");
  refused(sphereScene(R"("radius": 1, "transform": [{"scale": 1e5}, {"scale": 1e5}, {"scale": 1e5},
      {"scale": 1e5}, {"scale": 1e5}, {"scale": 1e5}, {"scale": 1e5}, {"scale": 1e5}])"),
          "/objects/0/transform/7");
}

TEST(MalformedInput, DisplayQuantitiesOutOfRange) {
  TempDir dir;
  const auto refused = [&](const std::string& text, const std::string& key) {
    const std::string path = dir.file("d.json");
    writeFile(path, text);
    expectRefused(
        [&] {
          const BarrierDisplayFile file = loadDisplayFile(path);
          designDisplay(file.spec, file.camera);
        },
        {"d.json: " + key + ":"});
  };
  refused(R"({"image_layer": {"pixel_pitch_mm": 1e-300}})", "/image_layer/pixel_pitch_mm");
  refused(R"({"mask_layer": {"pixel_pitch_mm": 50}})", "/mask_layer/pixel_pitch_mm");
  refused(R"({"view_distance_mm": 1e300})", "/view_distance_mm");
  refused(R"({"view_distance_mm": 1})", "/view_distance_mm");
  refused(R"({"gap_mm": 1e300})", "/gap_mm");
  refused(R"({"view_zone": {"center_x_mm": 1e300}})", "/view_zone/center_x_mm");
  refused(R"({"virtual": {"distance_mm": 1e300}})", "/virtual/distance_mm");
  refused(R"({"mask": {"phase_px": 1e300}})", "/mask/phase_px");
  refused(R"({"screen_period_px": 9, "slit_period_px": 1e300})", "/slit_period_px");
}

TEST(MalformedInput, NonRegularFilesAreRefusedByKind) {
  TempDir dir;
  expectRefused([] { loadScene("/dev/zero"); }, {"/dev/zero: not a regular file (a character"});
  expectRefused([] { loadDisplayFile("/dev/urandom"); }, {"a character device"});
  const std::string folder = dir.file("scene.json");
  fs::create_directories(folder);
  expectRefused([&] { loadScene(folder); }, {"scene.json: is a folder, not a file"});
  expectRefused([&] { loadLenticularCalibration(folder); }, {"is a folder"});
  expectRefused([&] { readImage(folder); }, {"is a folder"});
  const std::string fifo = dir.file("pipe.ply");
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expectRefused([&] { load(fifo); }, {"pipe.ply: not a regular file (a named pipe (FIFO))"});
  const std::string fifoPng = dir.file("pipe.png");
  ASSERT_EQ(::mkfifo(fifoPng.c_str(), 0600), 0);
  expectRefused([&] { readImage(fifoPng); }, {"named pipe"});
}

TEST(MalformedInput, ObjWhoseMtlIsAFolder) {
  TempDir dir;
  fs::create_directories(dir.file("m.mtl"));
  const std::string path = dir.file("m.obj");
  writeFile(path, "mtllib m.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  expectRefused([&] { load(path); }, {"m.mtl: is a folder"});
}

void appendBigEndian32(std::string& out, uint32_t v) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(char((v >> shift) & 0xFF));
}

// A PNG signature and an IHDR chunk announcing width x height, 8-bit RGBA; no pixel data.
std::string pngHeader(uint32_t width, uint32_t height) {
  std::string out("\x89PNG\r\n\x1a\n", 8);
  appendBigEndian32(out, 13);
  out.append("IHDR");
  appendBigEndian32(out, width);
  appendBigEndian32(out, height);
  out.append("\x08\x06\x00\x00\x00", 5);
  appendBigEndian32(out, 0);
  return out;
}

// A TGA header (it has no signature) announcing 20000x20000 24-bit pixels, and a little data.
std::string tgaHeader() {
  std::string out(18, '\0');
  out[2] = 2;
  out[12] = out[14] = char(0x20);
  out[13] = out[15] = char(0x4e);
  out[16] = 24;
  out.append(96, '\x7f');
  return out;
}

TEST(MalformedInput, ImagesAnnouncingHugeSizesAreRefusedFromTheHeader) {
  TempDir dir;
  const std::string path = dir.file("tex.png");
  std::string png = pngHeader(30000, 30000);
  png.append(260, '\0');
  writeFile(path, png);
  expectRefused([&] { readImage(path); }, {"tex.png: needs about", "30000x30000 pixels (limit"});
  // A TGA header (no signature) announcing 20000x20000 in a file named .png.
  const std::string tga = dir.file("fake.png");
  writeFile(tga, tgaHeader());
  expectRefused([&] { readImage(tga); }, {"fake.png: not a readable image"});
  const std::string named = dir.file("big.tga");
  writeFile(named, tgaHeader());
  expectRefused([&] { readImage(named); }, {"big.tga: needs about"});
  // A real PNG named .jpg.
  const std::string jpg = dir.file("photo.jpg");
  writeFile(jpg, pngBytes(Image(2, 2)));
  expectRefused([&] { readImage(jpg); }, {"the name says JPEG but the contents are PNG"});
}

// Binary PNM is uncompressed: a file shorter than its header's samples is truncated, refused
// before anything is allocated (two fuzzing finds: 23 and 27 bytes announcing 30126x3012 and
// 8103x8708 pixels took over 10 s each, padded with zeros).
TEST(MalformedInput, PnmShorterThanItsHeaderAnnouncesIsTruncated) {
  TempDir dir;
  const std::string grey = dir.file("short.pgm");
  writeFile(grey, "P5\n8103 8708\n255\n" + std::string(1000, '\x7f'));
  expectRefused([&] { readImage(grey); }, {"short.pgm: truncated", "8103x8708 pixels"});
  const std::string wide = dir.file("short16.ppm");
  // 16-bit samples: 2 x 2 pixels x 3 channels x 2 bytes = 24 bytes, one missing.
  writeFile(wide, "P6\n2 2\n65535\n" + std::string(23, '\x01'));
  expectRefused([&] { readImage(wide); }, {"short16.ppm: truncated", "(24 bytes of samples)"});
  // Whole files still read.
  const std::string whole = dir.file("whole.ppm");
  writeFile(whole, "P6\n2 2\n65535\n" + std::string(24, '\x01'));
  EXPECT_EQ(readImage(whole).width(), 2);
}

TEST(MalformedInput, PfmWithNanIsRefused) {
  TempDir dir;
  const std::string path = dir.file("layer.pfm");
  std::string bytes = "PF\n1 1\n-1\n";
  const float values[3] = {0.5f, std::numeric_limits<float>::quiet_NaN(), 0.5f};
  bytes.append(reinterpret_cast<const char*>(values), sizeof values);
  writeFile(path, bytes);
  expectRefused([&] { readImage(path); }, {"layer.pfm:", "NaN or infinite"});
}

TEST(MalformedInput, GltfNodeChainTooDeepAndCycles) {
  TempDir dir;
  std::ostringstream nodes;
  for (int i = 0; i < 10000; ++i) {
    nodes << (i ? "," : "") << "{\"children\": [";
    if (i + 1 < 10000) nodes << i + 1;
    nodes << "]}";
  }
  const std::string deep = dir.file("deep.gltf");
  writeFile(deep, R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [)" +
                      nodes.str() + "]}");
  expectInputError(deep, "levels deep");
  const std::string cycle = dir.file("cycle.gltf");
  writeFile(cycle, R"({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}],
      "nodes": [{"children": [1]}, {"children": [0]}]})");
  expectInputError(cycle, "is its own ancestor");
}

TEST(MalformedInput, GlbImageBufferViewPastItsBuffer) {
  TempDir dir;
  std::string json =
      R"({"asset": {"version": "2.0"}, "buffers": [{"byteLength": 8}],
      "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 100000}],
      "images": [{"bufferView": 0, "mimeType": "image/png"}]})";
  while (json.size() % 4) json += ' ';
  const std::string bin(8, '\0');
  Bytes glb;
  glb.data = "glTF";
  glb.u32(2).u32(uint32_t(12 + 8 + json.size() + 8 + bin.size()));
  glb.u32(uint32_t(json.size())).u32(0x4E4F534A);
  glb.data += json;
  glb.u32(uint32_t(bin.size())).u32(0x004E4942);
  glb.data += bin;
  const std::string path = dir.file("short.glb");
  writeFile(path, glb.data);
  expectInputError(path, "extends past the end of its buffer");
}

TEST(MalformedInput, AssimpFormatsGiveOneLineNamingTheFile) {
  // Broken files in formats only assimp reads: its message, on one line, after the file name.
  TempDir dir;
  std::string fbx = readFile(dataDir() + "/assimp/FBX/box.fbx");
  ASSERT_GT(fbx.size(), 2000u);
  const std::pair<const char*, std::string> cases[] = {
      {"truncated.fbx", fbx.substr(0, 2000)},
      {"header.fbx", std::string("Kaydara FBX Binary  \0\x1a\0\xe8\x1c\0\0garbage", 35)},
      {"cut.dae",
       "<?xml version=\"1.0\"?>\n<COLLADA version=\"1.4.1\"><library_geometries><geometry "
       "id=\"g\"><mesh><source id=\"s\"><float_array count=\"9\">0 0 0 1 0"},
      {"bad.3ds", std::string("MM\x10\0\0\0\x3d\x3d\xff\xff\xff\x7f", 12)},
      {"bad.x", "xof 0303txt 0032\nMesh { 3; 0;0;0;, 1;0;0;, 0;1"},
      {"bad.blend", "no Blender file at all\n"},
  };
  for (const auto& [name, bytes] : cases) {
    SCOPED_TRACE(name);
    const std::string path = dir.file(name);
    writeFile(path, bytes);
    expectRefused(
        [&] {
          Scene scene;
          loadMeshFile(path, {}, scene);
        },
        {path + ": ", "assimp cannot read it: "});
  }
}

}  // namespace
}  // namespace parallax

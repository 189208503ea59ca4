// The long tail of mesh formats through assimp (Debian's libassimp-dev): every extension assimp
// reads that our own readers (OBJ, PLY, STL, glTF) do not. The scene is triangulated and its
// points and lines removed by assimp; each mesh instanced by a node becomes one FilePart with
// the node's accumulated transform as fileFromPart, so loadMeshFile moves it to world space as
// it does glTF nodes. docs/import.md says what is kept.
#include <assimp/material.h>
#include <assimp/postprocess.h>
#include <assimp/scene.h>
#include <assimp/version.h>
#include <assimp/Importer.hpp>

#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "parallax/core/error.h"
#include "parallax/importer/assimp_importer.h"
#include "parallax/importer/isolated_import.h"
#include "parallax/importer/mesh_readers.h"
#include "parallax/io/image_file.h"

namespace parallax::meshio {
namespace {

Vec3f toVec3(const aiColor3D& c) {
  return {c.r, c.g, c.b};
}

// assimp's aiMatrix4x4 is row-major and acts on column vectors (translation in a4, b4, c4),
// like our Mat4.
Mat4 toMat4(const aiMatrix4x4& a) {
  Mat4 m;
  const float rows[4][4] = {{a.a1, a.a2, a.a3, a.a4},
                            {a.b1, a.b2, a.b3, a.b4},
                            {a.c1, a.c2, a.c3, a.c4},
                            {a.d1, a.d2, a.d3, a.d4}};
  for (int r = 0; r < 4; ++r)
    for (int c = 0; c < 4; ++c) m.m[r][c] = rows[r][c];
  return m;
}

class AssimpConverter {
 public:
  AssimpConverter(const std::string& path, const aiScene& scene, FileContents& contents)
      : path_(path),
        folder_(std::filesystem::path(path).parent_path()),
        scene_(scene),
        contents_(contents) {}

  void convert() {
    readMaterials();
    readUpAxis();
    if (!scene_.mRootNode) fail(path_, "the file has no scene nodes");
    // Depth first with an explicit stack: a hostile file's deep hierarchy cannot overflow ours.
    std::vector<std::pair<const aiNode*, Mat4>> stack{{scene_.mRootNode, Mat4::identity()}};
    while (!stack.empty()) {
      const auto [node, parent] = stack.back();
      stack.pop_back();
      const Mat4 fileFromNode = node == scene_.mRootNode && rootIsAssimpsAxisConversion()
                                    ? parent
                                    : parent * toMat4(node->mTransformation);
      for (unsigned i = 0; i < node->mNumMeshes; ++i)
        addMesh(*node, node->mMeshes[i], fileFromNode);
      for (unsigned i = node->mNumChildren; i-- > 0;)
        stack.emplace_back(node->mChildren[i], fileFromNode);
    }
    if (singularNodes_ > 0)
      contents_.warnings.push_back("skipped " + std::to_string(singularNodes_) +
                                   " mesh instance(s) under a singular node transform");
    contents_.note = note();
  }

  // "DAE (assimp): took 4 mesh parts; ignored: 2 cameras, 2 lights": what the file has that
  // this import drops, as the glTF reader's note says (docs/import.md).
  std::string note() const {
    std::string format = std::filesystem::path(path_).extension().string();
    if (!format.empty()) format.erase(0, 1);
    for (char& c : format) c = char(std::toupper(static_cast<unsigned char>(c)));
    const auto count = [](size_t n, const char* what) {
      return std::to_string(n) + " " + what + (n == 1 ? "" : "s");
    };
    std::vector<std::string> ignored;
    if (scene_.mNumCameras > 0) ignored.push_back(count(scene_.mNumCameras, "camera"));
    if (scene_.mNumLights > 0) ignored.push_back(count(scene_.mNumLights, "light"));
    if (scene_.mNumAnimations > 0) ignored.push_back(count(scene_.mNumAnimations, "animation"));
    std::string text = format + " (assimp): took " + count(contents_.parts.size(), "mesh part");
    if (ignored.empty()) return text;
    text += "; ignored: ";
    for (size_t i = 0; i < ignored.size(); ++i) text += (i ? ", " : "") + ignored[i];
    return text + " (glTF keeps cameras, lights and animation: export glTF from Blender)";
  }

 private:
  void addMesh(const aiNode& node, unsigned meshIndex, const Mat4& fileFromNode) {
    if (meshIndex >= scene_.mNumMeshes)
      fail(path_, "node '" + std::string(node.mName.C_Str()) + "': mesh index out of range");
    const aiMesh& mesh = *scene_.mMeshes[meshIndex];
    if (!(mesh.mPrimitiveTypes & aiPrimitiveType_TRIANGLE)) return;
    FilePart part;
    try {
      part.fileFromPart = Transform(fileFromNode);
    } catch (const std::invalid_argument&) {
      ++singularNodes_;
      return;
    }
    for (const aiNode* n = &node; n; n = n->mParent)
      if (n->mName.length > 0) part.nodeNames.emplace_back(n->mName.C_Str());
    part.context = "node '" + std::string(node.mName.C_Str()) + "' mesh '" +
                   std::string(mesh.mName.C_Str()) + "'";
    part.material =
        mesh.mMaterialIndex < contents_.materials.size() ? int(mesh.mMaterialIndex) : -1;
    part.positions.resize(mesh.mNumVertices);
    for (unsigned v = 0; v < mesh.mNumVertices; ++v)
      part.positions[v] = {mesh.mVertices[v].x, mesh.mVertices[v].y, mesh.mVertices[v].z};
    if (mesh.HasNormals()) {
      part.normals.resize(mesh.mNumVertices);
      for (unsigned v = 0; v < mesh.mNumVertices; ++v)
        part.normals[v] = {mesh.mNormals[v].x, mesh.mNormals[v].y, mesh.mNormals[v].z};
    }
    // assimp's UVs have v = 0 at the image's bottom row unless aiProcess_FlipUVs, as ours.
    if (mesh.HasTextureCoords(0)) {
      part.uvs.resize(mesh.mNumVertices);
      for (unsigned v = 0; v < mesh.mNumVertices; ++v)
        part.uvs[v] = {mesh.mTextureCoords[0][v].x, mesh.mTextureCoords[0][v].y};
    }
    part.indices.reserve(size_t(mesh.mNumFaces) * 3);
    for (unsigned f = 0; f < mesh.mNumFaces; ++f) {
      const aiFace& face = mesh.mFaces[f];
      if (face.mNumIndices != 3) continue;  // points and lines of a mixed mesh
      part.indices.insert(part.indices.end(), face.mIndices, face.mIndices + 3);
    }
    // One aiMesh instanced by several nodes is copied once per node, like glTF meshes.
    contents_.parts.push_back(std::move(part));
  }

  void readMaterials() {
    for (unsigned i = 0; i < scene_.mNumMaterials; ++i) {
      const aiMaterial& source = *scene_.mMaterials[i];
      FileMaterial material;
      aiString name;
      material.material.name = source.Get(AI_MATKEY_NAME, name) == AI_SUCCESS && name.length > 0
                                   ? std::string(name.C_Str())
                                   : "material" + std::to_string(i);
      aiColor3D colour;
      if (source.Get(AI_MATKEY_COLOR_DIFFUSE, colour) == AI_SUCCESS)
        material.material.diffuse = toVec3(colour);
      if (source.Get(AI_MATKEY_COLOR_EMISSIVE, colour) == AI_SUCCESS)
        material.material.emission = toVec3(colour);
      aiString texture;
      if (source.GetTexture(aiTextureType_DIFFUSE, 0, &texture) == AI_SUCCESS ||
          source.GetTexture(aiTextureType_BASE_COLOR, 0, &texture) == AI_SUCCESS)
        material.image = image(texture.C_Str(), material.material.name);
      contents_.materials.push_back(std::move(material));
    }
  }

  // The image of a texture reference: "*N" or a name assimp knows as embedded, else a file
  // relative to the model's folder. Missing or unreadable: a warning, and the colour alone.
  int image(const std::string& reference, const std::string& materialName) {
    auto [it, inserted] = images_.try_emplace(reference, -1);
    if (!inserted) return it->second;
    const std::string where = "material '" + materialName + "': texture '" + reference + "'";
    Image decoded;
    if (const aiTexture* embedded = scene_.GetEmbeddedTexture(reference.c_str())) {
      if (embedded->mHeight == 0) {  // compressed (PNG, JPEG): mWidth bytes
        try {
          decoded = decodeImage(
              std::string_view(reinterpret_cast<const char*>(embedded->pcData), embedded->mWidth),
              path_ + " " + where);
        } catch (const InputError& e) {
          contents_.warnings.push_back(where + ": embedded image not readable (" + e.what() +
                                       "); using its colour alone");
          return -1;
        }
      } else {  // raw BGRA8 texels, top row first, sRGB-encoded
        decoded = Image(int(embedded->mWidth), int(embedded->mHeight));
        for (unsigned y = 0; y < embedded->mHeight; ++y)
          for (unsigned x = 0; x < embedded->mWidth; ++x) {
            const aiTexel& t = embedded->pcData[size_t(y) * embedded->mWidth + x];
            decoded.at(int(x), int(y)) = {srgb8ToLinear(t.r), srgb8ToLinear(t.g),
                                          srgb8ToLinear(t.b)};
          }
      }
    } else {
      std::string name = reference;
      std::replace(name.begin(), name.end(), '\\', '/');  // files written on Windows
      std::string file = (folder_ / name).string();
      std::error_code error;
      // Files written elsewhere often name their textures by absolute paths of the machine
      // that wrote them ("D:\\models\\wood.jpg"); the texture is then usually beside the file.
      if (!std::filesystem::exists(file, error))
        file = (folder_ / std::filesystem::path(name).filename()).string();
      if (!std::filesystem::exists(file, error)) {
        contents_.warnings.push_back(where + ": file not found; using its colour alone");
        return -1;
      }
      // The long tail brings textures we cannot decode (TGA, BMP, DDS): unlike an OBJ's,
      // they cost the texture, not the model.
      try {
        decoded = readImage(file);
      } catch (const InputError& e) {
        contents_.warnings.push_back(where + ": not readable (" + e.what() +
                                     "); using its colour alone");
        return -1;
      }
    }
    contents_.images.push_back(std::move(decoded));
    return it->second = int(contents_.images.size()) - 1;
  }

  // FBX files say which axis is up (metadata UpAxis 0/1/2 = X/Y/Z with UpAxisSign); assimp
  // keeps it as metadata without applying it. Collada's <up_axis> and the 3DS Z-up convention
  // are applied by assimp's importers themselves; Blender's is not (docs/import.md).
  void readUpAxis() {
    if (!scene_.mMetaData) return;
    int32_t axis = -1, sign = 1;
    if (!scene_.mMetaData->Get("UpAxis", axis)) return;
    scene_.mMetaData->Get("UpAxisSign", sign);
    if (axis == 1 && sign > 0) {
      contents_.declaredUp = UpAxis::Y;
    } else if (axis == 2 && sign > 0) {
      contents_.declaredUp = UpAxis::Z;
    } else {
      // Formatted, not concatenated: GCC 12 warns falsely (-Warray-bounds) on the appends.
      char declared[80];
      std::snprintf(declared, sizeof declared,
                    "declares up axis %c%c, which is not supported; taking +Y as up",
                    sign < 0 ? '-' : '+', "XYZ"[std::clamp(axis, 0, 2)]);
      contents_.warnings.emplace_back(declared);
      contents_.declaredUp = UpAxis::Y;
    }
  }

  // assimp 5.3 and later (Debian 13's 5.4) turn an FBX file's declared axes into the
  // transform of the root node it makes for the file (Z-up becomes Y-up; with contradictory
  // axes, a singular matrix), where 5.2 (Debian 12) leaves it at identity and reports the axes
  // only as metadata. We apply the declared up axis ourselves, as the `up` option says
  // (readUpAxis), so that root transform is left out and the file's own coordinates are the
  // same with either assimp. Nothing the file says is lost: an FBX file has no transform of
  // its own for that root (its objects hang below it with theirs).
  bool rootIsAssimpsAxisConversion() const {
    std::string extension = std::filesystem::path(path_).extension().string();
    for (char& c : extension) c = char(std::tolower(static_cast<unsigned char>(c)));
    return extension == ".fbx";
  }

  const std::string& path_;
  std::filesystem::path folder_;
  const aiScene& scene_;
  FileContents& contents_;
  std::map<std::string, int> images_;  // texture reference -> image
  size_t singularNodes_ = 0;
};

std::string oneLine(std::string text) {
  std::replace(text.begin(), text.end(), '\n', ' ');
  std::replace(text.begin(), text.end(), '\r', ' ');
  while (!text.empty() && text.back() == ' ') text.pop_back();
  return text;
}

}  // namespace

bool assimpReads(const std::string& lowerExtension) {
  static const Assimp::Importer importer;
  return !lowerExtension.empty() && importer.IsExtensionSupported(lowerExtension);
}

// In the child process of readIsolated (docs/import.md, "Isolation"): assimp and the
// texture decoding the conversion does.
FileContents readAssimp(const std::string& path) {
  std::string format = std::filesystem::path(path).extension().string();
  if (!format.empty()) format.erase(0, 1);
  for (char& c : format) c = char(std::toupper(static_cast<unsigned char>(c)));
  return readIsolated(path, "the " + format + " importer (assimp)", readAssimpInProcess);
}

FileContents readAssimpInProcess(const std::string& path) {
  Assimp::Importer importer;
  // Points and lines are not surfaces: SortByPType separates them and this drops them.
  importer.SetPropertyInteger(AI_CONFIG_PP_SBP_REMOVE,
                              aiPrimitiveType_POINT | aiPrimitiveType_LINE);
  // ValidateDataStructure refuses scenes with out-of-range indices and the like, which
  // malformed files produce; it reports them as an import failure.
  const aiScene* scene = importer.ReadFile(
      path, aiProcess_Triangulate | aiProcess_SortByPType | aiProcess_ValidateDataStructure);
  if (!scene) {
    const std::string error = oneLine(importer.GetErrorString());
    fail(path, "assimp cannot read it" + (error.empty() ? std::string() : ": " + error));
  }
  if (scene->mFlags & AI_SCENE_FLAGS_INCOMPLETE)
    fail(path, "assimp read an incomplete scene (no meshes it can use)");
  FileContents contents;
  AssimpConverter(path, *scene, contents).convert();
  return contents;
}

}  // namespace parallax::meshio

namespace parallax {

LibraryVersion assimpVersion() {
  return {int(aiGetVersionMajor()), int(aiGetVersionMinor()), int(aiGetVersionPatch())};
}

}  // namespace parallax

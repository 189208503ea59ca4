// Private to the importer: the readers loadMeshFile (mesh_file.cpp) picks by extension, each
// decoding its format into FileContents (mesh_reading.h).
#pragma once

#include <string>

#include "parallax/importer/mesh_reading.h"

namespace parallax::meshio {

FileContents readObj(const std::string& path);
FileContents readPly(const std::string& path);
FileContents readStl(const std::string& path);
FileContents readGltf(const std::string& path);
FileContents readOff(const std::string& path);  // Geomview's OFF (mesh_off.cpp)
// Every format assimp reads (mesh_assimp.cpp), in a child process with limits
// (isolated_import.h); assimpReads says which extensions (".fbx").
FileContents readAssimp(const std::string& path);
bool assimpReads(const std::string& lowerExtension);

}  // namespace parallax::meshio

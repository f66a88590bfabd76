#pragma once
// The file sandbox: reading a glTF file and letting tinygltf parse it with
// file callbacks that keep every URI inside the asset's folder.
#include <filesystem>
#include <string>
#include <vector>

#include "gltf/common.hpp"

namespace headlight::gltf {

// The file's bytes, after checking that it exists, is a regular file and is
// named .gltf or .glb (`extension`, lowercase), so that a wrong file is not
// read whole just to be refused. Throws SceneError.
std::vector<unsigned char> readAssetBytes(const std::filesystem::path& path, const std::string& file,
                                          const std::string& extension);

// Parses `bytes` (GLB when `binary`) into `model`. External buffers and
// images are read only from inside `path`'s folder unless
// `allowExternalPaths`; images are kept encoded (decoded later, once the
// structure is checked) after their bufferView range is checked.
// `warnings` receives tinygltf's warnings as one line. Throws SceneError.
void parseSandboxed(tinygltf::Model& model, const std::vector<unsigned char>& bytes, bool binary,
                    const std::filesystem::path& path, bool allowExternalPaths, const std::string& file,
                    std::string& warnings);

}  // namespace headlight::gltf

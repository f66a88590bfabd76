#pragma once
// What tinygltf 2.7 (Debian's, built without Draco) cannot parse in valid
// compressed files, given stand-ins in the JSON before it parses them:
// - EXT_meshopt_compression's placeholder buffers without uri: tinygltf
//   refuses them in .gltf and, in .glb, copies the BIN chunk into them or
//   refuses them when longer. They get a 3-byte data URI; their indices are
//   kept so that gltf_meshopt refuses any use of them but the extension's.
// - KHR_draco_mesh_compression's indices accessors without bufferView:
//   tinygltf requires one. They get a stand-in bufferView (over a stand-in
//   buffer, both appended), which gltf_draco replaces with the decoded data.
// A file that names neither extension costs one substring search each.
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace headlight::gltf {

struct StandIns {
  std::optional<std::vector<unsigned char>> bytes;  // the file to parse instead; none: the original
  std::vector<int> placeholderBuffers;              // EXT_meshopt_compression's buffers without data
};

// `json` is the file's JSON text (jsonText()), already checked by checkStructure().
StandIns standInsForTinygltf(std::span<const unsigned char> bytes, std::string_view json, bool binary);

}  // namespace headlight::gltf

#pragma once
// Checks on a glTF file's raw bytes and JSON, made before tinygltf sees it.
//
// tinygltf converts JSON to its Value type recursively (20,000 nested levels
// overflow the stack), reads negative or string byteOffset/byteStride as 0,
// accepts any asset.version and any GLB container version. So the nesting
// depth is measured on the text with a bounded scan, and the rules tinygltf
// does not enforce are checked on the JSON itself (nlohmann-json, whose parser
// and destructor do not recurse). Each failure is a SceneError starting with
// the file name and naming the element and the rule.
#include <cstddef>
#include <span>
#include <string>
#include <string_view>

namespace headlight::gltf {

// The JSON text: the whole file for .gltf; for .glb, the JSON chunk, after
// the container header (magic, version 2, length) and chunk header are checked.
std::string_view jsonText(std::span<const unsigned char> bytes, bool binary, const std::string& file);

// Throws when arrays/objects nest deeper than detail::kMaxJsonDepth (io/bounded_json.hpp). Reads each byte
// once and keeps no stack, so it cannot itself be exhausted.
void checkNestingDepth(std::string_view json, const std::string& file);

// Parses the JSON and checks what tinygltf lets through: asset.version 2.x,
// every index, offset, length, stride and count a non-negative integer, the
// top-level arrays arrays of objects. Throws SceneError.
void checkStructure(std::string_view json, const std::string& file);

}  // namespace headlight::gltf

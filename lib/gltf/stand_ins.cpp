#include "gltf/stand_ins.hpp"

#include <cstring>
#include <string>

#include <nlohmann/json.hpp>

#include "gltf/draco.hpp"
#include "gltf/meshopt.hpp"

namespace headlight::gltf {

namespace {

using nlohmann::json;

// A 3-byte data URI: tinygltf decodes it and checks it against byteLength.
constexpr const char* kStandInUri = "data:application/octet-stream;base64,AAAA";
constexpr std::size_t kStandInBytes = 3;

std::uint32_t readU32(std::span<const unsigned char> bytes, std::size_t at) {
  std::uint32_t value = 0;
  std::memcpy(&value, bytes.data() + at, sizeof value);
  return value;
}

void writeU32(std::vector<unsigned char>& out, std::size_t at, std::uint32_t value) {
  std::memcpy(out.data() + at, &value, sizeof value);
}

// A GLB of `text` (padded with spaces, as GLB asks) and the original's
// chunks after the JSON chunk (the BIN chunk), unchanged.
std::vector<unsigned char> repackGlb(std::span<const unsigned char> original, std::string text) {
  while (text.size() % 4 != 0) text += ' ';
  const std::size_t rest = 20 + std::size_t(readU32(original, 12));
  const std::size_t tail = rest < original.size() ? original.size() - rest : 0;
  std::vector<unsigned char> out(20 + text.size() + tail);
  std::memcpy(out.data(), original.data(), 8);  // magic, version
  writeU32(out, 8, std::uint32_t(out.size()));
  writeU32(out, 12, std::uint32_t(text.size()));
  std::memcpy(out.data() + 16, original.data() + 16, 4);  // "JSON"
  std::memcpy(out.data() + 20, text.data(), text.size());
  if (tail > 0) std::memcpy(out.data() + 20 + text.size(), original.data() + rest, tail);
  return out;
}

json* arrayIn(json& root, const char* key) {
  const auto found = root.find(key);
  return found != root.end() && found->is_array() ? &*found : nullptr;
}

// Placeholder buffers: no uri (in a .glb, index 1 on: buffer 0 without uri is the BIN chunk).
bool standInPlaceholders(json& root, bool binary, std::vector<int>& placeholders) {
  json* buffers = arrayIn(root, "buffers");
  if (buffers == nullptr) return false;
  for (std::size_t index = binary ? 1 : 0; index < buffers->size(); ++index) {
    json& buffer = (*buffers)[index];
    if (buffer.is_object() && !buffer.contains("uri")) {
      buffer["uri"] = kStandInUri;
      buffer["byteLength"] = kStandInBytes;
      placeholders.push_back(int(index));
    }
  }
  return !placeholders.empty();
}

// Draco primitives' indices accessors without bufferView.
bool standInDracoIndices(json& root) {
  json* meshes = arrayIn(root, "meshes");
  json* accessors = arrayIn(root, "accessors");
  if (meshes == nullptr || accessors == nullptr) return false;
  int standInView = -1;
  for (json& mesh : *meshes) {
    json* primitives = mesh.is_object() ? arrayIn(mesh, "primitives") : nullptr;
    for (std::size_t p = 0; primitives != nullptr && p < primitives->size(); ++p) {
      const json& primitive = (*primitives)[p];
      if (!primitive.is_object() || !primitive.contains("extensions") || !primitive["extensions"].is_object() ||
          !primitive["extensions"].contains("KHR_draco_mesh_compression") || !primitive.contains("indices") ||
          !primitive["indices"].is_number_unsigned() || primitive["indices"].get<std::size_t>() >= accessors->size()) {
        continue;
      }
      json& accessor = (*accessors)[primitive["indices"].get<std::size_t>()];
      if (!accessor.is_object() || accessor.contains("bufferView")) continue;
      if (standInView < 0) {
        if (!root.contains("buffers")) root["buffers"] = json::array();
        if (!root.contains("bufferViews")) root["bufferViews"] = json::array();
        if (!root["buffers"].is_array() || !root["bufferViews"].is_array()) return false;
        root["buffers"].push_back({{"uri", kStandInUri}, {"byteLength", kStandInBytes}});
        standInView = int(root["bufferViews"].size());
        root["bufferViews"].push_back({{"buffer", root["buffers"].size() - 1}, {"byteLength", kStandInBytes}});
      }
      accessor["bufferView"] = standInView;
    }
  }
  return standInView >= 0;
}

}  // namespace

StandIns standInsForTinygltf(std::span<const unsigned char> bytes, std::string_view json, bool binary) {
  StandIns result;
  const bool meshopt = meshoptDecoding() && json.find("EXT_meshopt_compression") != std::string_view::npos;
  const bool draco = dracoDecoding() && json.find("KHR_draco_mesh_compression") != std::string_view::npos;
  if (!meshopt && !draco) return result;
  nlohmann::json root = nlohmann::json::parse(json.begin(), json.end());
  if (!root.is_object()) return result;
  bool changed = meshopt && standInPlaceholders(root, binary, result.placeholderBuffers);
  changed = (draco && standInDracoIndices(root)) || changed;
  if (!changed) return result;
  std::string text = root.dump();
  result.bytes = binary ? repackGlb(bytes, std::move(text)) : std::vector<unsigned char>(text.begin(), text.end());
  return result;
}

}  // namespace headlight::gltf

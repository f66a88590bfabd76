#include "hostile_inputs.hpp"

#include <cstring>

#include "support/encoding.hpp"

namespace headlight::test::hostile {

using nlohmann::json;

std::vector<unsigned char> trianglePositions() {
  const float positions[9] = {-1, -1, 0, 1, -1, 0, 0, 1, 0};
  std::vector<unsigned char> bytes(sizeof positions);
  std::memcpy(bytes.data(), positions, sizeof positions);
  return bytes;
}

json triangleScene() {
  const std::vector<unsigned char> bytes = trianglePositions();
  return {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", bytes.size()}}}},
      {"accessors",
       {{{"bufferView", 0},
         {"componentType", 5126},
         {"type", "VEC3"},
         {"count", 3},
         {"min", {-1, -1, 0}},
         {"max", {1, 1, 0}}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0},
  };
}

json withLight(json document, const std::vector<double>& color, double intensity) {
  document["extensionsUsed"] = {"KHR_lights_punctual"};
  document["extensions"]["KHR_lights_punctual"]["lights"] = {
      {{"type", "point"}, {"color", color}, {"intensity", intensity}}};
  document["nodes"].push_back({{"translation", {0, 0, 2}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  document["scenes"][0]["nodes"].push_back(document["nodes"].size() - 1);
  return document;
}

std::string nestedArrays(int depth) {
  return std::string(std::size_t(depth), '[') + std::string(std::size_t(depth), ']');
}

namespace {
void appendU32(std::string& out, std::uint32_t value) {
  char bytes[4];
  std::memcpy(bytes, &value, 4);
  out.append(bytes, 4);
}
}  // namespace

std::vector<unsigned char> glb(const std::string& json, const std::vector<unsigned char>& bin, std::uint32_t version) {
  std::string text = json;
  while (text.size() % 4 != 0) text += ' ';
  std::string binary(bin.begin(), bin.end());
  while (binary.size() % 4 != 0) binary += '\0';
  const std::uint32_t length =
      12 + 8 + std::uint32_t(text.size()) + (binary.empty() ? 0 : 8 + std::uint32_t(binary.size()));
  std::string out = "glTF";
  appendU32(out, version);
  appendU32(out, length);
  appendU32(out, std::uint32_t(text.size()));
  out += "JSON" + text;
  if (!binary.empty()) {
    appendU32(out, std::uint32_t(binary.size()));
    out += std::string("BIN\0", 4) + binary;
  }
  return {out.begin(), out.end()};
}

}  // namespace headlight::test::hostile

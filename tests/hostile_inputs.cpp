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

namespace headlight::test::hostile {

// The static pose (issue 17 item 2): bytes of one buffer, laid out as
// posedScene() describes.
json posedScene() {
  std::vector<float> floats = {-1, -1, 0, 1, -1, 0, 0, 1, 0,  // 0: POSITION
                               0,  0,  1, 0, 0,  1, 0, 0, 1}; // 36: morph target POSITION deltas
  std::vector<unsigned char> bytes(floats.size() * 4);
  std::memcpy(bytes.data(), floats.data(), bytes.size());
  bytes.resize(bytes.size() + 12, 0);  // 72: JOINTS_0, UNSIGNED_BYTE VEC4, all joint 0
  const float weights[12] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0};
  const float identity[16] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1};
  const float translations[6] = {0, 0, 0, 3, 0, 0};
  for (const auto& [data, size] : {std::pair<const float*, std::size_t>{weights, sizeof weights},  // 84: WEIGHTS_0
                                   {identity, sizeof identity},           // 132: inverseBindMatrices
                                   {translations, sizeof translations}})  // 196: instance TRANSLATION
  {
    const auto* raw = reinterpret_cast<const unsigned char*>(data);
    bytes.insert(bytes.end(), raw, raw + size);
  }
  json views = json::array();
  for (const auto& [offset, length] : std::vector<std::pair<int, int>>{{0, 36}, {36, 36}, {72, 12}, {84, 48}, {132, 64},
                                                                       {196, 24}}) {
    views.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}});
  }
  return {
      {"asset", {{"version", "2.0"}}},
      {"extensionsUsed", {"EXT_mesh_gpu_instancing"}},
      {"buffers", {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}}},
      {"bufferViews", views},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"type", "VEC3"}, {"count", 3}},
        {{"bufferView", 1}, {"componentType", 5126}, {"type", "VEC3"}, {"count", 3}},
        {{"bufferView", 2}, {"componentType", 5121}, {"type", "VEC4"}, {"count", 3}},
        {{"bufferView", 3}, {"componentType", 5126}, {"type", "VEC4"}, {"count", 3}},
        {{"bufferView", 4}, {"componentType", 5126}, {"type", "MAT4"}, {"count", 1}},
        {{"bufferView", 5}, {"componentType", 5126}, {"type", "VEC3"}, {"count", 2}}}},
      {"meshes",
       {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}},
        {{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"targets", {{{"POSITION", 1}}}}}}}, {"weights", {0.5}}},
        {{"primitives", {{{"attributes", {{"POSITION", 0}, {"JOINTS_0", 2}, {"WEIGHTS_0", 3}}}}}}}}},
      {"skins", {{{"joints", {2}}, {"inverseBindMatrices", 4}}}},
      {"nodes",
       {{{"mesh", 1}},
        {{"mesh", 2}, {"skin", 0}, {"translation", {100, 0, 0}}},
        {{"rotation", {0, 0, 0.70710678, 0.70710678}}},
        {{"mesh", 0}, {"extensions", {{"EXT_mesh_gpu_instancing", {{"attributes", {{"TRANSLATION", 5}}}}}}}}}},
      {"scenes", {{{"nodes", {0, 1, 2, 3}}}}},
      {"scene", 0},
  };
}

}  // namespace headlight::test::hostile

// Points and lines in the glTF loader (no GL): LINE_STRIP and LINE_LOOP
// become line lists, normals are 0 where the file gives none (gbuffer.frag
// faces them toward the camera), and none of them counts as a triangle.
#include <doctest/doctest.h>

#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
using namespace headlight::test;

namespace {

// Four vertices of a unit quad, (0,0) (1,0) (0,1) (1,1), indices 0 1 2 3,
// drawn with `mode`; with a NORMAL accessor (all +X) when `normals`.
std::filesystem::path writeQuad(const TempFolder& folder, int mode, bool normals, int indexCount = 4) {
  const float positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  const float normalValues[12] = {1, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0};
  const std::uint16_t indices[4] = {0, 1, 2, 3};
  std::vector<unsigned char> buffer(104, 0);
  std::memcpy(buffer.data(), positions, sizeof positions);
  std::memcpy(buffer.data() + 48, indices, sizeof indices);
  std::memcpy(buffer.data() + 56, normalValues, sizeof normalValues);
  folder.write("quad.bin", buffer);
  const std::string attributes = normals ? R"({"POSITION":0,"NORMAL":2})" : R"({"POSITION":0})";
  const std::string json =
      R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
      "meshes":[{"primitives":[{"attributes":)" + attributes + R"(,"indices":1,"mode":)" + std::to_string(mode) +
      R"(}]}],"buffers":[{"uri":"quad.bin","byteLength":104}],
      "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":8},
                     {"buffer":0,"byteOffset":56,"byteLength":48}],
      "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
                   {"bufferView":1,"componentType":5123,"count":)" + std::to_string(indexCount) + R"(,"type":"SCALAR"},
                   {"bufferView":2,"componentType":5126,"count":4,"type":"VEC3"}]})";
  return folder.write("mode" + std::to_string(mode) + ".gltf", json);
}

}  // namespace

TEST_CASE("glTF points and lines: decoded as point and line lists, drawn, not named, not triangles") {
  TempFolder folder;
  struct Case {
    int mode;
    PrimitiveMode primitiveMode;
    std::vector<std::uint32_t> indices;
  };
  const Case cases[] = {
      {0, PrimitiveMode::Points, {0, 1, 2, 3}},
      {1, PrimitiveMode::Lines, {0, 1, 2, 3}},
      {2, PrimitiveMode::Lines, {0, 1, 1, 2, 2, 3, 3, 0}},  // LINE_LOOP closes
      {3, PrimitiveMode::Lines, {0, 1, 1, 2, 2, 3}},        // LINE_STRIP
  };
  for (const Case& c : cases) {
    CAPTURE(c.mode);
    const Scene scene = loadGltf(writeQuad(folder, c.mode, false));
    REQUIRE(scene.primitives.size() == 1);
    REQUIRE(scene.instances.size() == 1);
    CHECK(scene.ignored.empty());
    CHECK(scene.primitives[0].mode == c.primitiveMode);
    CHECK(scene.primitives[0].indices == c.indices);
    CHECK(scene.triangleCount() == 0);
    // No NORMAL: 0, for the G-buffer to face toward the camera.
    for (const glm::vec3& normal : scene.primitives[0].normals) CHECK(normal == glm::vec3(0.0f));
    // The file's normals are kept.
    const Scene withNormals = loadGltf(writeQuad(folder, c.mode, true));
    for (const glm::vec3& normal : withNormals.primitives[0].normals) CHECK(normal == glm::vec3(1, 0, 0));
  }
}

TEST_CASE("glTF points and lines: LINES with an odd index count is refused, naming the primitive") {
  TempFolder folder;
  CHECK_THROWS_WITH_AS(loadGltf(writeQuad(folder, 1, false, 3)),
                       doctest::Contains("mesh 0 primitive 0 has 3 indices in accessor 1, expected a multiple of 2 for LINES"),
                       SceneError);
}

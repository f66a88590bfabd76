#include "gltf_test_files.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstring>

#include "headlight/error.hpp"

namespace fs = std::filesystem;

namespace headlight::test {

bool isHex16(const std::string& text) {
  return text.size() == 16 && text.find_first_not_of("0123456789abcdef") == std::string::npos;
}

bool near(const glm::vec3& a, const glm::vec3& b, float tolerance) {
  return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tolerance)));
}

// One triangle in the XY plane, counter-clockwise seen from +Z: 36 bytes of
// positions, then 6 bytes of 16-bit indices and 2 bytes of padding.
std::vector<unsigned char> triangleBuffer(std::array<std::uint16_t, 3> indices, float firstX) {
  const float positions[9] = {firstX, 0, 0, 1, 0, 0, 0, 1, 0};
  std::vector<unsigned char> bytes(44, 0);
  std::memcpy(bytes.data(), positions, sizeof positions);
  std::memcpy(bytes.data() + 36, indices.data(), 6);
  return bytes;
}

std::string gltfJson(const GltfParts& parts) {
  const std::string uri = parts.bufferUri.empty() ? "" : R"("uri":")" + parts.bufferUri + R"(",)";
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":)" + parts.sceneNodes + R"(}],"nodes":)" +
         parts.nodes + R"(,"meshes":[{"primitives":[)" + parts.primitive + R"(]}],"buffers":[{)" + uri +
         R"("byteLength":44}],)" + R"("bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},{"buffer":0,)" +
         parts.indexView + "}]," + R"("accessors":[{"bufferView":0,"componentType":5126,"count":)" +
         parts.positionCount + R"(,"type":"VEC3"},{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"})" +
         parts.moreAccessors + "]" + parts.extra + "}";
}

// Writes triangle.bin and scene.gltf into `folder` and returns the glTF's path.
fs::path writeTriangleGltf(const TempFolder& folder, const GltfParts& parts, const std::vector<unsigned char>& buffer) {
  folder.write("triangle.bin", buffer);
  return folder.write("scene.gltf", gltfJson(parts));
}

void appendU32(std::vector<unsigned char>& bytes, std::uint32_t value) {
  for (int shift = 0; shift < 32; shift += 8) {
    bytes.push_back(static_cast<unsigned char>(value >> shift));
  }
}

// A .glb: 12-byte header, a JSON chunk padded with spaces and a BIN chunk
// padded with zeros, as the glTF spec lays them out.
std::vector<unsigned char> makeGlb(std::string json, std::vector<unsigned char> bin) {
  json.resize((json.size() + 3) / 4 * 4, ' ');
  bin.resize((bin.size() + 3) / 4 * 4, 0);
  std::vector<unsigned char> glb;
  appendU32(glb, 0x46546C67);  // "glTF"
  appendU32(glb, 2);
  appendU32(glb, static_cast<std::uint32_t>(12 + 8 + json.size() + 8 + bin.size()));
  appendU32(glb, static_cast<std::uint32_t>(json.size()));
  appendU32(glb, 0x4E4F534A);  // "JSON"
  glb.insert(glb.end(), json.begin(), json.end());
  appendU32(glb, static_cast<std::uint32_t>(bin.size()));
  appendU32(glb, 0x004E4942);  // "BIN"
  glb.insert(glb.end(), bin.begin(), bin.end());
  return glb;
}

// Loads `path` expecting a SceneError; returns its message ("" if none).
std::string loadError(const fs::path& path, const SceneLoadOptions& options) {
  try {
    loadGltf(path, options);
  } catch (const SceneError& error) {
    return error.what();
  }
  return "";
}

// The checks every scene must pass whatever its source: what the renderer
// relies on without checking again.
void checkWellFormed(const Scene& scene) {
  for (const Instance& instance : scene.instances) {
    CHECK(instance.primitive < static_cast<int>(scene.primitives.size()));
    CHECK(instance.material < static_cast<int>(scene.materials.size()));
  }
  for (const Primitive& primitive : scene.primitives) {
    REQUIRE(primitive.normals.size() == primitive.positions.size());
    CHECK((primitive.texcoords.empty() || primitive.texcoords.size() == primitive.positions.size()));
    CHECK((primitive.tangents.empty() || primitive.tangents.size() == primitive.positions.size()));
    CHECK(primitive.indices.size() % 3 == 0);
    Bounds bounds;
    for (const glm::vec3& position : primitive.positions) {
      bounds.extend(position);
    }
    CHECK(near(bounds.min, primitive.bounds.min, 0.0f));
    CHECK(near(bounds.max, primitive.bounds.max, 0.0f));
    // Counted, not checked one by one: the shared asset has ~10^6 of each.
    const auto nonUnitNormals =
        std::count_if(primitive.normals.begin(), primitive.normals.end(),
                      [](const glm::vec3& n) { return std::abs(glm::length(n) - 1.0f) > 1e-4f; });
    CHECK(nonUnitNormals == 0);
    const auto indicesOutOfRange =
        std::count_if(primitive.indices.begin(), primitive.indices.end(),
                      [&](std::uint32_t index) { return index >= primitive.positions.size(); });
    CHECK(indicesOutOfRange == 0);
  }
  for (const Instance& instance : scene.instances) {
    CHECK(instance.primitive >= 0);
    CHECK(instance.primitive < static_cast<int>(scene.primitives.size()));
  }
}

// Counter-clockwise triangles face where their vertex normals point (the
// built-in scenes are single-sided, so a flipped one would vanish).
void checkWindingMatchesNormals(const Primitive& primitive) {
  for (std::size_t first = 0; first < primitive.indices.size(); first += 3) {
    const glm::vec3 a = primitive.positions[primitive.indices[first]];
    const glm::vec3 b = primitive.positions[primitive.indices[first + 1]];
    const glm::vec3 c = primitive.positions[primitive.indices[first + 2]];
    const glm::vec3 face = glm::cross(b - a, c - a);
    if (glm::length(face) < 1e-6f) {
      continue;  // sphere poles: rings of (almost) coincident vertices
    }
    CHECK(glm::dot(face, primitive.normals[primitive.indices[first]]) > 0.0f);
  }
}
}  // namespace headlight::test

#pragma once
// What the GL-free scene and glTF tests share: small glTF files written by
// the test itself (one triangle whose parts a case swaps out, or a .glb),
// the load-error probe, and the checks every loaded scene must pass.
#include <array>
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "headlight/scene.hpp"
#include "headlight/scene_loader.hpp"
#include "support/temp_folder.hpp"

namespace headlight::test {

bool isHex16(const std::string& text);
bool near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f);

// One triangle in the XY plane, counter-clockwise seen from +Z: 36 bytes of
// positions, then 6 bytes of 16-bit indices and 2 bytes of padding.
std::vector<unsigned char> triangleBuffer(std::array<std::uint16_t, 3> indices = {0, 1, 2}, float firstX = 0.0f);

// The parts of a one-triangle glTF that tests swap out.
struct GltfParts {
  std::string bufferUri = "triangle.bin";  // empty: no uri (GLB's BIN chunk)
  std::string positionCount = "3";
  std::string primitive = R"({"attributes":{"POSITION":0},"indices":1})";
  std::string nodes = R"([{"mesh":0}])";
  std::string sceneNodes = "[0]";
  std::string indexView = R"("byteOffset":36,"byteLength":6)";
  std::string moreAccessors;  // appended to the accessors array, each starting with a comma
  std::string extra;          // more top-level members, each starting with a comma
};

std::string gltfJson(const GltfParts& parts);

// Writes triangle.bin and scene.gltf into `folder` and returns the glTF's path.
std::filesystem::path writeTriangleGltf(const TempFolder& folder, const GltfParts& parts = {},
                                        const std::vector<unsigned char>& buffer = triangleBuffer());

// A .glb: 12-byte header, a JSON chunk padded with spaces and a BIN chunk
// padded with zeros, as the glTF spec lays them out.
std::vector<unsigned char> makeGlb(std::string json, std::vector<unsigned char> bin);

// Loads `path` expecting a SceneError; returns its message ("" if none).
std::string loadError(const std::filesystem::path& path, const SceneLoadOptions& options = {});

// The checks every scene must pass whatever its source: what the renderer
// relies on without checking again.
void checkWellFormed(const Scene& scene);

// Counter-clockwise triangles face where their vertex normals point (the
// built-in scenes are single-sided, so a flipped one would vanish).
void checkWindingMatchesNormals(const Primitive& primitive);

inline glm::vec3 cameraPosition(const Camera& camera) { return glm::vec3(camera.worldFromCamera[3]); }
inline glm::vec3 cameraForward(const Camera& camera) { return -glm::vec3(camera.worldFromCamera[2]); }

}  // namespace headlight::test

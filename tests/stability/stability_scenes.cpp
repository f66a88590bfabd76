// The stability suite's scenes, built in code: each is the smallest setup
// that provokes one known failure of screen-space GI (docs/STABILITY.md).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"
#include "stability/stability.hpp"

namespace headlight::stability {

namespace {

// A square floor at y = 0 facing +Y, `halfSize` each way.
Primitive floorQuad(float halfSize) {
  return makeQuad({-halfSize, 0, -halfSize}, {0, 0, 2 * halfSize}, {2 * halfSize, 0, 0});
}

int addMaterial(Scene& scene, glm::vec3 color) {
  scene.materials.push_back(matteMaterial(color));
  return int(scene.materials.size()) - 1;
}

void addInstance(Scene& scene, Primitive primitive, int material, const glm::mat4& worldFromLocal = glm::mat4(1.0f)) {
  scene.primitives.push_back(std::move(primitive));
  scene.instances.push_back({int(scene.primitives.size()) - 1, worldFromLocal, material});
}

glm::mat4 moved(glm::vec3 offset) { return glm::translate(glm::mat4(1.0f), offset); }

// Sets bounds from the positions; NaN coordinates are left out of them by
// Bounds::extend's comparisons (NaN < x is false).
void recomputeBounds(Primitive& primitive) {
  primitive.bounds = Bounds{};
  for (const glm::vec3& p : primitive.positions) primitive.bounds.extend(p);
}

}  // namespace

Material matteMaterial(glm::vec3 color) {
  Material material;
  material.baseColorFactor = glm::vec4(color, 1.0f);
  material.metallicFactor = 0.0f;
  material.roughnessFactor = 0.9f;
  return material;
}

Camera lookAt(glm::vec3 eye, glm::vec3 target, float yfov) {
  Camera camera;
  camera.yfov = yfov;
  camera.worldFromCamera = glm::inverse(glm::lookAt(eye, target, glm::vec3(0, 1, 0)));
  return camera;
}

// The failure cases a user can render too are built-in scenes
// (lib/scene/builtin_scenes.cpp), so the goldens and this suite share them.
Scene flatPlaneScene() { return makeBuiltinScene("plane"); }
Scene slatsScene() { return makeBuiltinScene("slats"); }

Scene nearWallScene() {
  Scene scene = makeBuiltinScene("cornell");
  scene.source = "stability:near-wall";
  // 0.1 from the back wall (z = -1), looking down-left into the corner of
  // the back wall, the floor and the red wall; the radius is 0.52.
  scene.cameras = {lookAt({-0.6f, 0.3f, -0.9f}, {-1.0f, 0.0f, -1.0f}, 1.2f)};
  return scene;
}
Scene offscreenBoxScene() { return makeBuiltinScene("offscreen"); }
Scene depthStepScene() { return makeBuiltinScene("depth-step"); }
Scene grazingFloorScene() { return makeBuiltinScene("grazing"); }

Scene scaledScene(Scene scene, float scale) {
  const glm::mat4 scaling = glm::scale(glm::mat4(1.0f), glm::vec3(scale));
  for (Instance& instance : scene.instances) instance.worldFromLocal = scaling * instance.worldFromLocal;
  for (Camera& camera : scene.cameras) {
    camera.worldFromCamera[3] = glm::vec4(glm::vec3(camera.worldFromCamera[3]) * scale, 1.0f);
    camera.znear *= scale;
    camera.zfar *= scale;
  }
  for (Light& light : scene.lights) {
    light.position *= scale;
    light.range *= scale;
    // Candela at scale^2 the distance: scale^2 the intensity keeps the lux.
    if (light.type != Light::Type::Directional) light.intensity *= scale * scale;
  }
  return scene;
}

Camera cornellOrbitCamera(float degrees) {
  const glm::vec3 target{0.0f, 1.0f, 0.0f};
  const float angle = glm::radians(degrees);
  const glm::vec3 eye = target + 3.6f * glm::vec3(std::sin(angle), 0.0f, std::cos(angle));
  return lookAt(eye, target, 0.7f);
}

Scene nanVertexScene() {
  Scene scene;
  scene.source = "stability:nan-vertex";
  const int white = addMaterial(scene, glm::vec3(0.8f));
  addInstance(scene, floorQuad(2.0f), white);
  Primitive broken = makeQuad({-0.5f, 0.2f, -0.5f}, {1, 0, 0}, {0, 1, 0});
  broken.positions[2].y = std::numeric_limits<float>::quiet_NaN();
  recomputeBounds(broken);
  addInstance(scene, std::move(broken), white);
  scene.cameras.push_back(lookAt({0, 1.5f, 3}, {0, 0.3f, 0}, 0.8f));
  return scene;
}

Scene zeroAreaScene() {
  Scene scene;
  scene.source = "stability:zero-area";
  const int white = addMaterial(scene, glm::vec3(0.8f));
  addInstance(scene, floorQuad(2.0f), white);
  Primitive wall = makeQuad({-1, 0, -1}, {2, 0, 0}, {0, 1.5f, 0});
  // A triangle collapsed to a point, and one whose corners lie on a line;
  // both add nothing to the area-weighted normals.
  const auto first = std::uint32_t(wall.positions.size());
  wall.positions.insert(wall.positions.end(), {{0, 0.5f, -1}, {0, 0.5f, -1}, {0, 0.5f, -1}});
  wall.positions.insert(wall.positions.end(), {{-0.5f, 1, -1}, {0, 1, -1}, {0.5f, 1, -1}});
  for (std::uint32_t i = 0; i < 6; ++i) wall.indices.push_back(first + i);
  wall.normals.clear();
  generateNormals(wall);
  recomputeBounds(wall);
  addInstance(scene, std::move(wall), white);
  scene.cameras.push_back(lookAt({0, 1.2f, 3}, {0, 0.5f, 0}, 0.8f));
  return scene;
}

Scene missingNormalsScene() {
  Scene scene;
  scene.source = "stability:missing-normals";
  const int white = addMaterial(scene, glm::vec3(0.8f));
  addInstance(scene, floorQuad(2.0f), white);
  Primitive block = makeBox({0.8f, 0.8f, 0.8f});
  block.normals.clear();
  generateNormals(block);
  addInstance(scene, std::move(block), white, moved({0, 0.4f, 0}));
  scene.cameras.push_back(lookAt({1, 1.5f, 3}, {0, 0.3f, 0}, 0.8f));
  return scene;
}

Scene hugeCoordinateScene() {
  Scene scene;
  scene.source = "stability:huge-coordinates";
  const int white = addMaterial(scene, glm::vec3(0.8f));
  addInstance(scene, floorQuad(1e20f), white);
  addInstance(scene, makeBox({1, 1, 1}), white, moved({0, 0.5f, 0}));
  scene.cameras.push_back(lookAt({2, 1.5f, 3}, {0, 0.5f, 0}, 0.8f));
  return scene;
}

Scene emptyScene() {
  Scene scene;
  scene.source = "stability:empty";
  return scene;
}

std::string quadGltfJson(bool nanPosition) {
  // Two triangles, six vertices, no indices and no normals.
  float positions[18] = {-1, 0, -1, -1, 0, 1, 1, 0, 1, -1, 0, -1, 1, 0, 1, 1, 0, -1};
  if (nanPosition) positions[0] = std::numeric_limits<float>::quiet_NaN();
  std::vector<unsigned char> bytes(sizeof positions);
  std::memcpy(bytes.data(), positions, sizeof positions);
  static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string base64;
  for (std::size_t at = 0; at < bytes.size(); at += 3) {
    const std::uint32_t group = (std::uint32_t(bytes[at]) << 16) |
                                (at + 1 < bytes.size() ? std::uint32_t(bytes[at + 1]) << 8 : 0u) |
                                (at + 2 < bytes.size() ? std::uint32_t(bytes[at + 2]) : 0u);
    for (std::size_t sextet = 0; sextet < 4; ++sextet)
      base64 += at + sextet <= bytes.size() ? kAlphabet[(group >> (18 - 6 * sextet)) & 63] : '=';
  }
  // glTF requires min and max on POSITION accessors; NaN has no JSON
  // spelling, so they stay those of the finite quad.
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
         R"("buffers":[{"uri":"data:application/octet-stream;base64,)" +
         base64 + R"(","byteLength":72}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":72}],)"
                  R"("accessors":[{"bufferView":0,"componentType":5126,"count":6,"type":"VEC3",)"
                  R"("min":[-1,0,-1],"max":[1,0,1]}]})";
}

}  // namespace headlight::stability

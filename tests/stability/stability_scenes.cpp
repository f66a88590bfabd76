// The stability suite's scenes, built in code: each is the smallest setup
// that provokes one known failure of screen-space GI (docs/STABILITY.md).
#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <string>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"
#include "stability/stability.hpp"
#include "support/encoding.hpp"

namespace headlight::stability {

namespace {

// The start of every degenerate-input scene: `source`, a matte white floor
// (material 0, `floorHalfSize` each way) and a camera at `eye` looking at
// `target`; the caller adds the one broken thing.
constexpr int kWhite = 0;
Scene floorScene(const char* source, float floorHalfSize, glm::vec3 eye, glm::vec3 target) {
  Scene scene;
  scene.source = source;
  addInstance(scene, makeFloor(floorHalfSize), addMaterial(scene, makeMaterial(glm::vec3(0.8f), 0.9f)));
  scene.cameras.push_back(makeLookAtCamera(eye, target, 0.8f));
  return scene;
}

// Sets bounds from the positions; NaN coordinates are left out of them by
// Bounds::extend's comparisons (NaN < x is false).
void recomputeBounds(Primitive& primitive) {
  primitive.bounds = Bounds{};
  for (const glm::vec3& p : primitive.positions) primitive.bounds.extend(p);
}

}  // namespace

// The failure cases a user can render too are built-in scenes
// (lib/scene/builtin_scenes.cpp), so the goldens and this suite share them.
Scene flatPlaneScene() { return makeBuiltinScene("plane"); }
Scene slatsScene() { return makeBuiltinScene("slats"); }

Scene nearWallScene() {
  Scene scene = makeBuiltinScene("cornell");
  scene.source = "stability:near-wall";
  // 0.1 from the back wall (z = -1), looking down-left into the corner of
  // the back wall, the floor and the red wall; the radius is 0.52.
  scene.cameras = {makeLookAtCamera({-0.6f, 0.3f, -0.9f}, {-1.0f, 0.0f, -1.0f}, 1.2f)};
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
  return makeLookAtCamera(eye, target, 0.7f);
}

Scene nanVertexScene() {
  Scene scene = floorScene("stability:nan-vertex", 2.0f, {0, 1.5f, 3}, {0, 0.3f, 0});
  Primitive broken = makeQuad({-0.5f, 0.2f, -0.5f}, {1, 0, 0}, {0, 1, 0});
  broken.positions[2].y = std::numeric_limits<float>::quiet_NaN();
  recomputeBounds(broken);
  addInstance(scene, std::move(broken), kWhite);
  return scene;
}

Scene zeroAreaScene() {
  Scene scene = floorScene("stability:zero-area", 2.0f, {0, 1.2f, 3}, {0, 0.5f, 0});
  Primitive wall = makeQuad({-1, 0, -1}, {2, 0, 0}, {0, 1.5f, 0});
  // A triangle collapsed to a point, and one whose corners lie on a line;
  // both add nothing to the area-weighted normals.
  const auto first = std::uint32_t(wall.positions.size());
  wall.positions.insert(wall.positions.end(), {{0, 0.5f, -1}, {0, 0.5f, -1}, {0, 0.5f, -1}});
  wall.positions.insert(wall.positions.end(), {{-0.5f, 1, -1}, {0, 1, -1}, {0.5f, 1, -1}});
  for (std::uint32_t i = 0; i < 6; ++i) wall.indices.push_back(first + i);
  wall.texcoords.resize(wall.positions.size(), glm::vec2(0.0f));  // one per position, as Primitive asks
  wall.normals.clear();
  generateNormals(wall);
  recomputeBounds(wall);
  addInstance(scene, std::move(wall), kWhite);
  return scene;
}

Scene missingNormalsScene() {
  Scene scene = floorScene("stability:missing-normals", 2.0f, {1, 1.5f, 3}, {0, 0.3f, 0});
  Primitive block = makeBox({0.8f, 0.8f, 0.8f});
  block.normals.clear();
  generateNormals(block);
  addInstance(scene, std::move(block), kWhite, moved({0, 0.4f, 0}));
  return scene;
}

Scene hugeCoordinateScene() {
  Scene scene = floorScene("stability:huge-coordinates", 1e20f, {2, 1.5f, 3}, {0, 0.5f, 0});
  addInstance(scene, makeBox({1, 1, 1}), kWhite, moved({0, 0.5f, 0}));
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
  const std::string base64 = test::base64(bytes);
  // glTF requires min and max on POSITION accessors; NaN has no JSON
  // spelling, so they stay those of the finite quad.
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
         R"("buffers":[{"uri":"data:application/octet-stream;base64,)" +
         base64 +
         R"(","byteLength":72}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":72}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"count":6,"type":"VEC3",)"
         R"("min":[-1,0,-1],"max":[1,0,1]}]})";
}

}  // namespace headlight::stability

// The built-in scenes, described as tables of surfaces and placements fed to
// three small geometry generators (quad, box, UV sphere). They need no files,
// so tests and first runs always have something to render.

#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <glm/gtc/matrix_transform.hpp>
#include <string>

#include "headlight/error.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"
#include "io/fingerprint.hpp"
#include "scene/builtin_layouts.hpp"

namespace headlight {

namespace {

// Bumped whenever a built-in scene's content changes, so that anything keyed
// on Scene::sourceHash (caches, EXR metadata) sees a different scene.
constexpr const char* kBuiltinVersion = "v1";

// The classic Cornell box, resized to x -1..1, y 0..2, z -1..1 and open at
// +Z for the camera. Colours are the usual reflectances of the original.
Scene makeCornell() {
  Scene scene;
  const int white = addMaterial(scene, makeMaterial(glm::vec3(0.73f), 0.9f, 0.0f, "cornell white"));
  const int red = addMaterial(scene, makeMaterial({0.63f, 0.065f, 0.05f}, 0.9f, 0.0f, "cornell red"));
  const int green = addMaterial(scene, makeMaterial({0.14f, 0.45f, 0.091f}, 0.9f, 0.0f, "cornell green"));
  Material lampMaterial = makeMaterial(glm::vec3(1.0f), 0.9f, 0.0f, "cornell lamp");
  lampMaterial.emissiveFactor = glm::vec3(1.0f, 0.85f, 0.7f) * 4.0f;
  const int lamp = addMaterial(scene, lampMaterial);

  struct Wall {
    glm::vec3 corner, edgeU, edgeV;  // front face = cross(edgeU, edgeV), inward
    int material;
    const char* name;  // the ids target's
  };
  const std::array<Wall, 5> walls{{
      {{-1, 0, -1}, {0, 0, 2}, {2, 0, 0}, white, "floor"},      // faces +Y
      {{-1, 2, -1}, {2, 0, 0}, {0, 0, 2}, white, "ceiling"},    // faces -Y
      {{-1, 0, -1}, {2, 0, 0}, {0, 2, 0}, white, "back wall"},  // faces +Z
      {{-1, 0, -1}, {0, 2, 0}, {0, 0, 2}, red, "left wall"},    // faces +X
      {{1, 0, -1}, {0, 0, 2}, {0, 2, 0}, green, "right wall"},  // faces -X
  }};
  for (const Wall& wall : walls) {
    addInstance(scene, makeQuad(wall.corner, wall.edgeU, wall.edgeV), wall.material, glm::mat4(1.0f), wall.name);
  }

  struct Block {
    glm::vec3 size, center;
    float yawDegrees;
    const char* name;
  };
  const std::array<Block, 2> blocks{{
      {{0.6f, 1.2f, 0.6f}, {-0.33f, 0.6f, -0.3f}, 17.0f, "tall block"},
      {{0.6f, 0.6f, 0.6f}, {0.33f, 0.3f, 0.3f}, -17.0f, "short block"},
  }};
  for (const Block& block : blocks) {
    addInstance(scene, makeBox(block.size), white, rotatedAboutYThenMoved(block.yawDegrees, block.center), block.name);
  }

  // 1.999: a millimetre below the ceiling, enough for 32-bit depth to keep
  // them apart, and too little for the lamp to shadow the ceiling round it.
  addInstance(scene, makeQuad({-0.25f, 1.999f, -0.25f}, {0.5f, 0, 0}, {0, 0, 0.5f}), lamp, glm::mat4(1.0f), "lamp");

  Light light;
  light.name = "cornell lamp light";
  light.type = Light::Type::Point;
  light.color = {1.0f, 0.85f, 0.7f};
  light.intensity = 10.0f;  // candela: about 2.8 lux on the floor below
  light.position = {0.0f, 1.9f, 0.0f};
  light.castsShadows = true;
  scene.lights.push_back(light);

  scene.cameras.push_back(makeLookAtCamera({0.0f, 1.0f, 3.6f}, {0.0f, 1.0f, 0.0f}, 0.7f, "cornell camera"));
  // The box is closed but for its front: the sky only fills the shadows a
  // little, and the lamp is the key light.
  scene.sky.intensity = 0.15f;
  return scene;
}

// Five spheres on a floor, sweeping roughness 0.2..0.9 with one metal, lit by
// a low sun: a quick look at the BRDF and the shadows.
Scene makeSpheres() {
  Scene scene;
  const int floor = addMaterial(scene, makeMaterial(glm::vec3(0.8f), 0.9f, 0.0f, "spheres floor"));
  addInstance(scene, makeQuad({-4, 0, 4}, {8, 0, 0}, {0, 0, -8}), floor);

  struct Ball {
    const char* name;
    glm::vec3 baseColor;
    float roughness, metallic, x;
  };
  const std::array<Ball, 5> balls{{
      {"sphere red", {0.8f, 0.1f, 0.08f}, 0.2f, 0.0f, -2.4f},
      {"sphere orange", {0.9f, 0.45f, 0.1f}, 0.375f, 0.0f, -1.2f},
      {"sphere yellow metal", {0.95f, 0.8f, 0.3f}, 0.55f, 1.0f, 0.0f},
      {"sphere green", {0.15f, 0.65f, 0.2f}, 0.725f, 0.0f, 1.2f},
      {"sphere blue", {0.2f, 0.35f, 0.85f}, 0.9f, 0.0f, 2.4f},
  }};
  constexpr float kRadius = 0.5f;
  // 64 x 32: smooth silhouettes at full-HD framing, ~4k triangles each.
  const int sphere = addGeometry(scene, makeUvSphere(kRadius, 64, 32));  // one sphere, five instances
  for (const Ball& ball : balls) {
    const int material = addMaterial(scene, makeMaterial(ball.baseColor, ball.roughness, ball.metallic, ball.name));
    addInstance(scene, sphere, material, glm::translate(glm::mat4(1.0f), glm::vec3(ball.x, kRadius, 0.0f)));
  }

  Light sun;
  sun.name = "spheres sun";
  sun.type = Light::Type::Directional;
  sun.intensity = 3.0f;  // lux
  sun.direction = glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f));
  sun.castsShadows = true;
  scene.lights.push_back(sun);

  scene.cameras.push_back(makeLookAtCamera({0.0f, 2.6f, 7.5f}, {0.0f, 0.4f, 0.0f}, 0.6f, "spheres camera"));
  return scene;
}

// ---- Failure cases of screen-space GI (docs/STABILITY.md) ------------------
// No lights: each gets the renderer's default key light.

// A 100 x 100 plane: nothing can occlude it.
Scene makePlane() {
  Scene scene;
  addInstance(scene, makeFloor(50.0f), addMaterial(scene, makeMaterial(glm::vec3(0.8f), 0.9f, 0.0f, "plane")));
  scene.cameras.push_back(makeLookAtCamera({0, 2, 6}, {0, 0, -4}, 0.8f, "plane camera"));
  return scene;
}

// Slats one or two pixels wide in front of a wall.
Scene makeSlats() {
  using L = builtin::SlatLayout;
  Scene scene;
  const int wall = addMaterial(scene, makeMaterial(glm::vec3(0.8f), 0.9f, 0.0f, "slats wall"));
  const int wood = addMaterial(scene, makeMaterial({0.6f, 0.45f, 0.3f}, 0.9f, 0.0f, "slats wood"));
  addInstance(scene, makeQuad({-1.2f, -1.2f, 0}, {2.4f, 0, 0}, {0, 2.4f, 0}), wall);  // faces +Z
  const int slat = addGeometry(scene, makeBox({L::kWidth, L::kHeight, L::kWidth}));
  for (int i = 0; i < L::kCount; ++i)
    addInstance(scene, slat, wood, moved({L::kFirstX + float(i) * L::kSpacing, 0, L::kGap}));
  scene.cameras.push_back(makeLookAtCamera({0.4f, 0.2f, 3.2f}, {0, 0, 0}, 0.8f, "slats camera"));
  return scene;
}

// A tall box cut by the left image border, its shadowed floor partly off
// screen (the camera sees x = -1.69..1.69 at the box's depth).
Scene makeOffscreen() {
  Scene scene;
  const int white = addMaterial(scene, makeMaterial(glm::vec3(0.8f), 0.9f, 0.0f, "offscreen white"));
  addInstance(scene, makeFloor(3.0f), white);
  addInstance(scene, makeBox({0.6f, 1.5f, 0.6f}), white, moved({-1.7f, 0.75f, 0}));
  addInstance(scene, makeBox({0.6f, 0.6f, 0.6f}), white, moved({0.3f, 0.3f, -0.5f}));
  scene.cameras.push_back(makeLookAtCamera({0, 1.2f, 3}, {0, 0.4f, 0}, 0.8f, "offscreen camera"));
  return scene;
}

// A sphere 1.4..2.6 units in front of a wall: the depth-discontinuity halo.
Scene makeDepthStep() {
  using L = builtin::DepthStepLayout;
  Scene scene;
  const int white = addMaterial(scene, makeMaterial(glm::vec3(0.8f), 0.9f, 0.0f, "depth-step wall"));
  addInstance(scene, makeQuad({-3, -3, L::kWallZ}, {6, 0, 0}, {0, 6, 0}), white);  // faces +Z
  addInstance(scene, makeUvSphere(L::kSphereRadius, 32, 16),
              addMaterial(scene, makeMaterial({0.7f, 0.3f, 0.2f}, 0.9f, 0.0f, "depth-step sphere")),
              moved({0, 0, L::kSphereZ}));
  scene.cameras.push_back(makeLookAtCamera({0, 0, 5}, {0, 0, 0}, 0.6f, "depth-step camera"));
  return scene;
}

// A 1000 x 1000 floor seen from half a unit up, 3 degrees down: grazing
// angles all the way to the horizon.
Scene makeGrazing() {
  Scene scene;
  addInstance(scene, makeFloor(500.0f), addMaterial(scene, makeMaterial(glm::vec3(0.8f), 0.9f, 0.0f, "grazing floor")));
  scene.cameras.push_back(makeLookAtCamera({0, 0.5f, 0}, {0, 0.5f - 0.0524f, -1}, 0.7f, "grazing camera"));
  return scene;
}

struct BuiltinScene {
  const char* name;
  Scene (*make)();
};

constexpr std::array<BuiltinScene, 7> kBuiltinScenes{{
    {"cornell", &makeCornell},
    {"spheres", &makeSpheres},
    {"plane", &makePlane},
    {"slats", &makeSlats},
    {"offscreen", &makeOffscreen},
    {"depth-step", &makeDepthStep},
    {"grazing", &makeGrazing},
}};

}  // namespace

std::vector<std::string> builtinSceneNames() {
  std::vector<std::string> names;
  for (const BuiltinScene& builtin : kBuiltinScenes) {
    names.emplace_back(builtin.name);
  }
  return names;
}

Scene makeBuiltinScene(std::string_view name) {
  for (const BuiltinScene& builtin : kBuiltinScenes) {
    if (name == builtin.name) {
      Scene scene = builtin.make();
      scene.source = "builtin:" + std::string(name);
      scene.sourceHash = textFingerprint(scene.source + ":" + kBuiltinVersion);
      return scene;
    }
  }
  std::string known;
  for (const std::string& builtinName : builtinSceneNames()) {
    known += (known.empty() ? "" : ", ") + builtinName;
  }
  throw SceneError("builtin:" + std::string(name) + ": no such built-in scene; known: " + known);
}

}  // namespace headlight

// The scene model and the built-in scenes, without GL: bounds, per-instance
// counts, generated normals, each built-in's contents, and the shared asset's
// geometry sharing.
#include <doctest/doctest.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>
#include <string>
#include <vector>

#include "headlight/camera.hpp"
#include "headlight/error.hpp"
#include "headlight/limits.hpp"
#include "headlight/shapes.hpp"
#include "headlight/scene_loader.hpp"
#include "support/assets.hpp"
#include "gltf_test_files.hpp"
#include "support/encoding.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using namespace headlight;
using namespace headlight::test;
using headlight::test::base64;
using headlight::test::TempFolder;


// ---- Scene model -------------------------------------------------------------

TEST_CASE("Bounds::transformed moves all eight corners") {
  Bounds unit;
  unit.extend(glm::vec3(-1.0f));
  unit.extend(glm::vec3(1.0f));
  const glm::mat4 turned =
      glm::rotate(glm::translate(glm::mat4(1.0f), glm::vec3(10, 0, 0)), glm::radians(45.0f), glm::vec3(0, 1, 0));
  const Bounds moved = unit.transformed(turned);
  const float halfDiagonal = std::sqrt(2.0f);
  CHECK(near(moved.min, {10 - halfDiagonal, -1, -halfDiagonal}));
  CHECK(near(moved.max, {10 + halfDiagonal, 1, halfDiagonal}));
  CHECK(Bounds().transformed(turned).empty());
}

TEST_CASE("Scene queries count per instance") {
  Scene scene;
  Primitive triangle;
  triangle.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  triangle.indices = {0, 1, 2};
  triangle.bounds.extend(glm::vec3(0, 0, 0));
  triangle.bounds.extend(glm::vec3(1, 1, 0));
  scene.primitives.push_back(triangle);
  scene.materials.resize(2);
  scene.materials[1].emissiveFactor = glm::vec3(1.0f);  // emissive but unused
  scene.instances.push_back({0, glm::mat4(1.0f), 0});
  scene.instances.push_back({0, glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5)), 0});
  CHECK(scene.triangleCount() == 2);
  CHECK(near(scene.worldBounds().min, {0, 0, 0}));
  CHECK(near(scene.worldBounds().max, {1, 1, 5}));
  CHECK_FALSE(scene.hasEmissive());
  scene.instances[1].material = 1;
  CHECK(scene.hasEmissive());
}

TEST_CASE("generateNormals weights by area and falls back to +Z") {
  Primitive primitive;
  // Vertex 0 is shared by a 2x2 triangle facing +Y and a 1x1 one facing +X.
  primitive.positions = {{0, 0, 0},  {0, 0, 2}, {2, 0, 0},  // floor, area 2
                         {0, 1, 0},  {0, 0, 1},             // wall, area 0.5
                         {5, 5, 5},                         // untouched
                         {7, 7, 7},  {8, 8, 8},             // degenerate (collinear)
                         {NAN, 0, 0}};                      // poisoned
  primitive.indices = {0, 1, 2, 0, 3, 4, 6, 7, 6, 0, 8, 1};
  generateNormals(primitive);
  REQUIRE(primitive.normals.size() == primitive.positions.size());
  CHECK(near(primitive.normals[0], glm::normalize(glm::vec3(0.5f, 2.0f, 0.0f) * 2.0f)));
  CHECK(near(primitive.normals[1], {0, 1, 0}));
  CHECK(near(primitive.normals[3], {1, 0, 0}));
  CHECK(near(primitive.normals[5], {0, 0, 1}));
  CHECK(near(primitive.normals[6], {0, 0, 1}));
  CHECK(near(primitive.normals[8], {0, 0, 1}));
}

// ---- Built-in scenes ---------------------------------------------------------

// A scene built in code that breaks Primitive's contract would be drawn with
// reads past its vertex buffers: checkSceneRanges (setScene's check) refuses it.
TEST_CASE("checkSceneRanges refuses a primitive whose attribute counts or indices break Primitive's contract") {
  const auto sceneWith = [](Primitive primitive) {
    Scene scene;
    scene.source = "built";
    scene.primitives.push_back(std::move(primitive));
    scene.instances.push_back(Instance{});
    return scene;
  };
  const Primitive quad = makeQuad({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  REQUIRE(quad.positions.size() == 4);
  CHECK_NOTHROW(checkSceneRanges(sceneWith(quad)));

  Primitive shortTexcoords = quad;
  shortTexcoords.texcoords.resize(3);
  CHECK_THROWS_WITH_AS(checkSceneRanges(sceneWith(shortTexcoords)),
                       "built: primitive 0 has 4 positions but 3 texcoords (TEXCOORD_0), expected none or 4",
                       SceneError);
  Primitive noTexcoords = quad;
  noTexcoords.texcoords.clear();
  CHECK_NOTHROW(checkSceneRanges(sceneWith(noTexcoords)));

  Primitive noNormals = quad;
  noNormals.normals.clear();
  CHECK_THROWS_WITH_AS(checkSceneRanges(sceneWith(noNormals)),
                       "built: primitive 0 has 4 positions but 0 normals, expected 4", SceneError);
  Primitive extraColors = quad;
  extraColors.colors.resize(5, glm::vec4(1.0f));
  CHECK_THROWS_WITH_AS(checkSceneRanges(sceneWith(extraColors)), doctest::Contains("5 colors, expected none or 4"),
                       SceneError);

  Primitive pastTheEnd = quad;
  pastTheEnd.indices.back() = 4;
  CHECK_THROWS_WITH_AS(checkSceneRanges(sceneWith(pastTheEnd)),
                       doctest::Contains("primitive 0 has index 4 at 5, expected at most 4 - 1"), SceneError);
}

// What an instance and a material name must exist, and an image hold its
// texels: the passes index the scene's tables with them.
TEST_CASE("checkSceneRanges refuses an instance, material texture or image that names what the scene lacks") {
  const auto texturedScene = [] {
    Scene scene;
    scene.source = "built";
    scene.primitives.push_back(makeQuad({0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
    scene.images.push_back(ImageData{"checker", 2, 2, std::vector<std::uint8_t>(16, 255)});
    Material material;
    material.name = "painted";
    material.baseColorTexture.image = 0;
    scene.materials.push_back(material);
    scene.instances.push_back(Instance{0, glm::mat4(1.0f), 0});
    return scene;
  };
  CHECK_NOTHROW(checkSceneRanges(texturedScene()));

  Scene noPrimitive = texturedScene();
  noPrimitive.instances[0].primitive = 1;
  CHECK_THROWS_WITH_AS(checkSceneRanges(noPrimitive),
                       "built: instance 0 names primitive 1, expected 0..0 (the scene has 1)", SceneError);
  Scene noMaterial = texturedScene();
  noMaterial.instances[0].material = 3;
  CHECK_THROWS_WITH_AS(checkSceneRanges(noMaterial),
                       "built: instance 0 names material 3, expected -1 (the default) or 0..0 (the scene has 1)",
                       SceneError);
  Scene belowDefault = texturedScene();
  belowDefault.instances[0].material = -2;
  CHECK_THROWS_AS(checkSceneRanges(belowDefault), SceneError);
  Scene defaultMaterial = texturedScene();
  defaultMaterial.instances[0].material = -1;
  CHECK_NOTHROW(checkSceneRanges(defaultMaterial));

  Scene missingImage = texturedScene();
  missingImage.materials[0].baseColorTexture.image = 1;
  CHECK_THROWS_WITH_AS(checkSceneRanges(missingImage),
                       "built: material 0 'painted' samples image 1 as its BASE_COLOR texture, expected 0..0 (the "
                       "scene has 1)",
                       SceneError);
  // An extension's texture goes through the same table.
  Scene missingCoatImage = texturedScene();
  missingCoatImage.materials[0].clearcoat = MaterialClearcoat{};
  missingCoatImage.materials[0].clearcoat->clearcoatNormalTexture.image = 7;
  CHECK_THROWS_WITH_AS(checkSceneRanges(missingCoatImage), doctest::Contains("image 7 as its CLEARCOAT_NORMAL"),
                       SceneError);

  Scene shortImage = texturedScene();
  shortImage.images[0].rgba.resize(15);
  CHECK_THROWS_WITH_AS(checkSceneRanges(shortImage), "built: image 0 'checker' has 15 bytes, expected 16 (RGBA8, 2x2)",
                       SceneError);
  Scene emptyImage = texturedScene();
  emptyImage.images[0] = ImageData{"empty", 0, 4, {}};
  CHECK_THROWS_WITH_AS(checkSceneRanges(emptyImage), "built: image 0 'empty' is 0x4, expected at least 1x1",
                       SceneError);
}

TEST_CASE("built-in scenes are well formed") {
  for (const std::string& name : builtinSceneNames()) {
    CAPTURE(name);
    const Scene scene = loadScene("builtin:" + name);
    CHECK(scene.source == "builtin:" + name);
    CHECK(isHex16(scene.sourceHash));
    CHECK_FALSE(scene.instances.empty());
    CHECK(scene.cameras.size() == 1);
    // The failure-case scenes (plane, slats, ...) carry no light: the
    // renderer's default key light lights them.
    CHECK(scene.lights.size() == ((name == "cornell" || name == "spheres") ? 1u : 0u));
    checkWellFormed(scene);
    for (const Primitive& primitive : scene.primitives) {
      checkWindingMatchesNormals(primitive);
      CHECK(primitive.texcoords.size() == primitive.positions.size());
    }
    for (const Material& material : scene.materials) {
      CHECK_FALSE(material.name.empty());
    }
  }
  CHECK(makeBuiltinScene("cornell").sourceHash != makeBuiltinScene("spheres").sourceHash);
}

TEST_CASE("cornell: box, blocks, lamp, camera") {
  const Scene scene = makeBuiltinScene("cornell");
  const Bounds bounds = scene.worldBounds();
  CHECK(near(bounds.min, {-1, 0, -1}));
  CHECK(near(bounds.max, {1, 2, 1}));
  CHECK(scene.hasEmissive());
  // 5 walls + 2 blocks + lamp: 5*2 + 2*12 + 2 triangles.
  CHECK(scene.instances.size() == 8);
  CHECK(scene.triangleCount() == 36);
  const Light& light = scene.lights[0];
  CHECK(light.type == Light::Type::Point);
  CHECK(near(light.position, {0, 1.9f, 0}));
  CHECK(light.intensity > 0.0f);
  CHECK(light.castsShadows);
  const Camera& camera = scene.cameras[0];
  CHECK(near(cameraPosition(camera), {0, 1, 3.6f}));
  CHECK(near(cameraForward(camera), {0, 0, -1}));
  CHECK(camera.yfov == doctest::Approx(0.7f));
  CHECK(camera.znear == 0.0f);
  CHECK(camera.zfar == 0.0f);
}

TEST_CASE("spheres: floor, five spheres, sun, camera") {
  const Scene scene = makeBuiltinScene("spheres");
  const Bounds bounds = scene.worldBounds();
  CHECK(near(bounds.min, {-4, 0, -4}));
  CHECK(near(bounds.max, {4, 1, 4}));
  CHECK(scene.instances.size() == 6);
  int metals = 0;
  for (const Material& material : scene.materials) {
    metals += material.metallicFactor == 1.0f ? 1 : 0;
  }
  CHECK(metals == 1);
  const Light& sun = scene.lights[0];
  CHECK(sun.type == Light::Type::Directional);
  CHECK(near(sun.direction, glm::normalize(glm::vec3(-0.4f, -1.0f, -0.3f))));
  CHECK(scene.primitives.size() == 2);  // the floor, and one sphere drawn five times
  // The camera sees every sphere whole at 4:3: each sphere's bounding box
  // projects inside the image.
  const CameraView view = makeCameraView(scene.cameras[0], bounds, 640, 480);
  for (const Instance& instance : scene.instances) {
    const Bounds sphere = scene.primitives[std::size_t(instance.primitive)].bounds.transformed(instance.worldFromLocal);
    if (sphere.size().y < 0.5f) continue;  // the floor
    for (const glm::vec3& corner : {sphere.min, sphere.max}) {
      const glm::vec4 clip = view.projection * view.view * glm::vec4(corner, 1.0f);
      CHECK(std::abs(clip.x / clip.w) < 1.0f);
      CHECK(std::abs(clip.y / clip.w) < 1.0f);
    }
  }
}

TEST_CASE("an unknown built-in scene names the known ones") {
  try {
    loadScene("builtin:teapot");
    FAIL("expected a SceneError");
  } catch (const SceneError& error) {
    CHECK(std::string(error.what()) ==
          "builtin:teapot: no such built-in scene; known: cornell, spheres, plane, slats, offscreen, depth-step, "
          "grazing");
  }
}

// ---- Shared asset -------------------------------------------------------------

// Skipped (and counted so) when the asset is absent: set HEADLIGHT_SHARED_DIR.
TEST_CASE("MetalRoughSpheresNoTextures loads with shared geometry" *
          doctest::skip(!test::exists(test::metalRoughSpheresGltf()))) {
  const fs::path path = test::metalRoughSpheresGltf();
  const Scene scene = loadGltf(path);
  // 102 nodes carry meshes; four label meshes have several primitives, so
  // there are 123 (node, primitive) instances. The 98 sphere meshes differ
  // only in material and share their accessors: one sphere geometry.
  CHECK(scene.instances.size() == 123);
  CHECK(scene.primitives.size() == 123 - 97);
  CHECK(scene.triangleCount() >= 1000000);
  CHECK(scene.triangleCount() <= 1100000);
  CHECK(scene.materials.size() == 98);
  CHECK(scene.cameras.empty());
  CHECK(scene.lights.empty());
  CHECK(isHex16(scene.sourceHash));
  CHECK(scene.source == path.string());
  // About 7.4 x 7.5 x 3.7 millimetres: the file is in metres.
  const glm::vec3 size = scene.worldBounds().size();
  CHECK(size.x == doctest::Approx(0.0074).epsilon(0.01));
  CHECK(size.y == doctest::Approx(0.0075).epsilon(0.01));
  CHECK(size.z == doctest::Approx(0.0037).epsilon(0.01));
  checkWellFormed(scene);
}

TEST_CASE("MetalRoughSpheresNoTextures' anchor file adds one camera and one directional light" *
          doctest::skip(!test::exists(test::metalRoughSpheresGltf().parent_path() / "anchor_metalrough.gltf"))) {
  const Scene anchored = loadGltf(test::metalRoughSpheresGltf().parent_path() / "anchor_metalrough.gltf");
  REQUIRE(anchored.cameras.size() == 1);
  REQUIRE(anchored.lights.size() == 1);
  CHECK(anchored.lights[0].type == Light::Type::Directional);
  CHECK(glm::length(anchored.lights[0].direction) == doctest::Approx(1.0f));
  CHECK(anchored.cameras[0].zfar > anchored.cameras[0].znear);
}

// ---- glTF files written by the tests ------------------------------------------

TEST_CASE("a scene of no extent gets a finite fitted view: every vertex at one point, at the origin or far out") {
  for (const glm::vec3 point : {glm::vec3(0.0f), glm::vec3(0.5f), glm::vec3(1e4f, -3e3f, 7.0f)}) {
    CAPTURE(point.x);
    headlight::Bounds bounds;
    bounds.min = bounds.max = point;
    const headlight::Camera camera = headlight::fitCamera(bounds, 4.0f / 3.0f);
    const headlight::CameraView view = headlight::makeCameraView(camera, bounds, 32, 24);
    bool finite = true;
    for (int column = 0; column < 4; ++column)
      for (int row = 0; row < 4; ++row)
        finite = finite && std::isfinite(view.view[column][row]) && std::isfinite(view.projection[column][row]);
    CHECK(finite);
    CHECK(view.nearPlane > 0.0f);
    CHECK(view.farPlane > view.nearPlane);
    // The point projects inside the image, at a depth between the planes.
    const glm::vec4 clip = view.projection * view.view * glm::vec4(point, 1.0f);
    REQUIRE(clip.w > 0.0f);
    CHECK(std::abs(clip.x / clip.w) <= 1.0f);
    CHECK(std::abs(clip.y / clip.w) <= 1.0f);
    CHECK(std::abs(clip.z / clip.w) <= 1.0f);
  }
}

TEST_CASE("max-memory auto: half of physical memory, or of the address-space limit where that is less (issue 32)") {
  CHECK(headlight::maxMemoryBytes({}) > 0);
  headlight::ResourceLimits set;
  set.maxMemoryMiB = 100;
  CHECK(headlight::maxMemoryBytes(set) == std::uint64_t(100) << 20);
  // Under `ulimit -v` 1 GiB (in a child: the limit stays with it): auto is
  // 512 MiB, a set value is kept. Nothing is allocated after the limit.
  const pid_t child = fork();
  if (child == 0) {
    const rlimit limit{rlim_t(1) << 30, rlim_t(1) << 30};
    if (::setrlimit(RLIMIT_AS, &limit) != 0) _exit(3);
    const bool halved = headlight::maxMemoryBytes({}) <= std::uint64_t(512) << 20;
    const bool kept = headlight::maxMemoryBytes(set) == std::uint64_t(100) << 20;
    _exit(halved && kept ? 0 : 1);
  }
  int status = 0;
  REQUIRE(waitpid(child, &status, 0) == child);
  REQUIRE(WIFEXITED(status));
  CHECK_MESSAGE(WEXITSTATUS(status) != 3, "setrlimit failed");
  CHECK(WEXITSTATUS(status) == 0);
}

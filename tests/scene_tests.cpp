// Scene model, built-in scenes and glTF loading. None of these need a GL
// context. Malformed files are written by the tests themselves into a fresh
// temporary folder, so each case is a few lines of JSON next to its check.
#include <doctest/doctest.h>

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
#include "headlight/scene_loader.hpp"
#include "support/assets.hpp"
#include "support/encoding.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using namespace headlight;
using headlight::test::base64;
using headlight::test::TempFolder;

namespace {

// ---- Helpers -------------------------------------------------------------

bool isHex16(const std::string& text) {
  return text.size() == 16 && text.find_first_not_of("0123456789abcdef") == std::string::npos;
}

bool near(const glm::vec3& a, const glm::vec3& b, float tolerance = 1e-5f) {
  return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec3(tolerance)));
}

// One triangle in the XY plane, counter-clockwise seen from +Z: 36 bytes of
// positions, then 6 bytes of 16-bit indices and 2 bytes of padding.
std::vector<unsigned char> triangleBuffer(std::array<std::uint16_t, 3> indices = {0, 1, 2}, float firstX = 0.0f) {
  const float positions[9] = {firstX, 0, 0, 1, 0, 0, 0, 1, 0};
  std::vector<unsigned char> bytes(44, 0);
  std::memcpy(bytes.data(), positions, sizeof positions);
  std::memcpy(bytes.data() + 36, indices.data(), 6);
  return bytes;
}

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
fs::path writeTriangleGltf(const TempFolder& folder, const GltfParts& parts = {},
                           const std::vector<unsigned char>& buffer = triangleBuffer()) {
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
std::string loadError(const fs::path& path, const SceneLoadOptions& options = {}) {
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

glm::vec3 cameraPosition(const Camera& camera) { return glm::vec3(camera.worldFromCamera[3]); }
glm::vec3 cameraForward(const Camera& camera) { return -glm::vec3(camera.worldFromCamera[2]); }

}  // namespace

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

TEST_CASE("a minimal glTF triangle loads, with generated normals") {
  TempFolder folder;
  const Scene scene = loadGltf(writeTriangleGltf(folder));
  REQUIRE(scene.primitives.size() == 1);
  REQUIRE(scene.instances.size() == 1);
  CHECK(scene.triangleCount() == 1);
  CHECK(scene.instances[0].material == -1);
  CHECK(scene.primitives[0].texcoords.empty());
  CHECK(scene.primitives[0].tangents.empty());
  CHECK(near(scene.primitives[0].normals[0], {0, 0, 1}));
  CHECK(isHex16(scene.sourceHash));
  checkWellFormed(scene);
}

TEST_CASE("glTF: buffers as data URIs, non-indexed primitives") {
  TempFolder folder;
  GltfParts parts;
  parts.bufferUri = "data:application/octet-stream;base64," + base64(triangleBuffer());
  parts.primitive = R"({"attributes":{"POSITION":0}})";
  const Scene scene = loadGltf(folder.write("inline.gltf", gltfJson(parts)));
  REQUIRE(scene.primitives.size() == 1);
  CHECK(scene.primitives[0].indices == std::vector<std::uint32_t>{0, 1, 2});
}

TEST_CASE("glTF: a sparse accessor without a bufferView is zeros plus its substitutions") {
  TempFolder folder;
  std::string json = gltfJson({});
  const std::string dense = R"({"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"})";
  // Positions 0..2 are all substituted: the indices view doubles as the
  // sparse indices (0, 1, 2) and the positions view as the values.
  const std::string sparse = R"({"componentType":5126,"count":3,"type":"VEC3","sparse":{"count":3,)"
                             R"("indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":0}}})";
  json.replace(json.find(dense), dense.size(), sparse);
  folder.write("triangle.bin", triangleBuffer());
  const Scene scene = loadGltf(folder.write("sparse.gltf", json));
  REQUIRE(scene.primitives.size() == 1);
  CHECK(near(scene.primitives[0].positions[1], {1, 0, 0}));
  CHECK(near(scene.primitives[0].positions[2], {0, 1, 0}));

  folder.write("triangle.bin", triangleBuffer({0, 1, 7}));
  CHECK(loadError(folder.path() / "sparse.gltf").find("accessor 0 sparse index 2 is 7, expected < count 3") !=
        std::string::npos);
}

TEST_CASE("glTF: nodes share a mesh, transforms accumulate, camera and light are placed") {
  TempFolder folder;
  GltfParts parts;
  parts.nodes = R"([{"translation":[1,0,0],"children":[1,2,3]},
                    {"mesh":0,"scale":[2,2,2]},
                    {"mesh":0,"matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 0,3,0,1]},
                    {"camera":0,"translation":[0,0,5],"scale":[3,3,3],
                     "extensions":{"KHR_lights_punctual":{"light":0}}}])";
  parts.extra = R"(,"cameras":[{"type":"perspective","perspective":{"yfov":0.5,"znear":0.1}}],
                   "extensionsUsed":["KHR_lights_punctual"],
                   "extensions":{"KHR_lights_punctual":{"lights":[
                     {"type":"spot","color":[1,0.5,0.25],"intensity":40,"spot":{"outerConeAngle":0.5}}]}})";
  const Scene scene = loadGltf(writeTriangleGltf(folder, parts));
  CHECK(scene.primitives.size() == 1);
  REQUIRE(scene.instances.size() == 2);
  const Bounds bounds = scene.worldBounds();
  CHECK(near(bounds.min, {1, 0, 0}));
  CHECK(near(bounds.max, {3, 4, 0}));
  REQUIRE(scene.cameras.size() == 1);
  CHECK(near(cameraPosition(scene.cameras[0]), {1, 0, 5}));
  CHECK(near(glm::vec3(scene.cameras[0].worldFromCamera[0]), {1, 0, 0}));  // scale removed
  CHECK(scene.cameras[0].zfar == 0.0f);
  REQUIRE(scene.lights.size() == 1);
  CHECK(scene.lights[0].type == Light::Type::Spot);
  CHECK(near(scene.lights[0].position, {1, 0, 5}));
  CHECK(near(scene.lights[0].direction, {0, 0, -1}));
  CHECK(near(scene.lights[0].color, {1, 0.5f, 0.25f}));
  CHECK(scene.lights[0].outerConeAngle == doctest::Approx(0.5f));
}

TEST_CASE("glTF: an embedded PNG is decoded to RGBA, top row first") {
  // 1x2 RGB PNG: red on top, blue below.
  const std::string png =
      "iVBORw0KGgoAAAANSUhEUgAAAAEAAAACCAIAAAAW4yFwAAAADUlEQVR4nGP4zwAC/wEIAAH/2ZC7NQAAAABJRU5ErkJggg==";
  TempFolder folder;
  GltfParts parts;
  parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":0})";
  parts.extra = R"(,"materials":[{"name":"painted","pbrMetallicRoughness":{"baseColorTexture":{"index":0}},
                     "emissiveFactor":[1,1,1],"extensions":{"KHR_materials_emissive_strength":{"emissiveStrength":5}}}],
                   "textures":[{"source":0,"sampler":0}],
                   "samplers":[{"magFilter":9728,"wrapS":33071}],
                   "images":[{"uri":"data:image/png;base64,)" +
                png + R"("}])";
  const Scene scene = loadGltf(writeTriangleGltf(folder, parts));
  REQUIRE(scene.images.size() == 1);
  const ImageData& image = scene.images[0];
  CHECK(image.width == 1);
  CHECK(image.height == 2);
  CHECK(image.rgba == std::vector<std::uint8_t>{255, 0, 0, 255, 0, 0, 255, 255});
  REQUIRE(scene.materials.size() == 1);
  const Material& material = scene.materials[0];
  CHECK(material.name == "painted");
  CHECK(material.baseColorTexture.image == 0);
  CHECK(material.baseColorTexture.magFilter == 9728);
  CHECK(material.baseColorTexture.wrapS == 33071);
  CHECK(material.baseColorTexture.wrapT == 10497);
  CHECK(near(material.emissiveFactor, glm::vec3(5.0f)));
  CHECK(scene.hasEmissive());
  // A textured material gets texcoords even where the file has none.
  CHECK(scene.primitives[0].texcoords.size() == 3);
}

TEST_CASE("glTF: alphaMode and alphaCutoff are read; MASK is rendered, BLEND named; bad values are refused") {
  TempFolder folder;
  GltfParts parts;
  parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":0})";
  auto load = [&](const std::string& material) {
    parts.extra = R"(,"materials":[)" + material + "]";
    return loadGltf(writeTriangleGltf(folder, parts));
  };
  const Scene masked = load(R"({"alphaMode":"MASK","alphaCutoff":0.25})");
  CHECK(masked.materials[0].alphaMode == AlphaMode::Mask);
  CHECK(masked.materials[0].alphaCutoff == 0.25f);
  CHECK(masked.ignored.empty());
  const Scene byDefault = load(R"({"alphaMode":"MASK"})");
  CHECK(byDefault.materials[0].alphaCutoff == 0.5f);
  CHECK(load("{}").materials[0].alphaMode == AlphaMode::Opaque);
  const Scene blend = load(R"({"alphaMode":"BLEND"})");
  CHECK(blend.materials[0].alphaMode == AlphaMode::Blend);
  REQUIRE(blend.ignored.size() == 1);
  CHECK(blend.ignored[0].feature == "alphaMode BLEND");
  CHECK_THROWS_WITH_AS(load(R"({"alphaMode":"CUTOUT"})"),
                       doctest::Contains("material 0 has alphaMode 'CUTOUT', expected OPAQUE, MASK or BLEND"),
                       SceneError);
  CHECK_THROWS_WITH_AS(load(R"({"alphaMode":"MASK","alphaCutoff":1.5})"),
                       doctest::Contains("material 0 has alphaCutoff 1.5"), SceneError);
  CHECK_THROWS_WITH_AS(load(R"({"alphaMode":"MASK","alphaCutoff":-0.1})"),
                       doctest::Contains("material 0 has alphaCutoff -0.1"), SceneError);
}

TEST_CASE("glTF: COLOR_0 is read as float or normalized unsigned integers, RGB or RGBA; a wrong one is refused") {
  TempFolder folder;
  GltfParts parts;
  parts.primitive = R"({"attributes":{"POSITION":0,"COLOR_0":2},"indices":1})";
  auto load = [&](const std::string& color) {
    parts.moreAccessors = ",{\"bufferView\":0," + color + "}";
    return loadGltf(writeTriangleGltf(folder, parts));
  };
  // Float RGB: the positions' bytes read as colours, A = 1.
  const Scene rgb = load(R"("componentType":5126,"count":3,"type":"VEC3")");
  REQUIRE(rgb.primitives[0].colors.size() == 3);
  for (std::size_t v = 0; v < 3; ++v)
    CHECK(rgb.primitives[0].colors[v] == glm::vec4(rgb.primitives[0].positions[v], 1.0f));
  CHECK(rgb.ignored.empty());
  // Normalized unsigned bytes and shorts land in 0..1.
  for (const char* color : {R"("componentType":5121,"normalized":true,"count":3,"type":"VEC4")",
                            R"("componentType":5123,"normalized":true,"count":3,"type":"VEC3")"}) {
    CAPTURE(color);
    const Scene scene = load(color);
    REQUIRE(scene.primitives[0].colors.size() == 3);
    for (const glm::vec4& c : scene.primitives[0].colors)
      for (int i = 0; i < 4; ++i) CHECK((c[i] >= 0.0f && c[i] <= 1.0f));
  }
  CHECK_THROWS_WITH_AS(load(R"("componentType":5126,"count":2,"type":"VEC3")"),
                       doctest::Contains("COLOR_0 accessor 2 has 2 elements, but POSITION accessor 0 has 3"),
                       SceneError);
  CHECK_THROWS_WITH_AS(load(R"("componentType":5121,"count":3,"type":"VEC3")"), doctest::Contains("COLOR_0"),
                       SceneError);  // unsigned bytes must be normalized
  // A primitive with COLOR_0 does not share the geometry of one without.
  parts.primitive =
      R"({"attributes":{"POSITION":0,"COLOR_0":2},"indices":1},{"attributes":{"POSITION":0},"indices":1})";
  const Scene both = load(R"("componentType":5126,"count":3,"type":"VEC3")");
  REQUIRE(both.primitives.size() == 2);
  CHECK(both.primitives[0].colors.size() == 3);
  CHECK(both.primitives[1].colors.empty());
  // COLOR_1 stays named as not rendered.
  parts.primitive = R"({"attributes":{"POSITION":0,"COLOR_1":2},"indices":1})";
  const Scene second = load(R"("componentType":5126,"count":3,"type":"VEC3")");
  REQUIRE(second.ignored.size() == 1);
  CHECK(second.ignored[0].feature == "COLOR_1");
}

TEST_CASE("glTF: a .glb with its BIN chunk loads") {
  TempFolder folder;
  GltfParts parts;
  parts.bufferUri = "";
  const Scene scene = loadGltf(folder.write("triangle.glb", makeGlb(gltfJson(parts), triangleBuffer())));
  CHECK(scene.triangleCount() == 1);

  parts.positionCount = "4";
  const fs::path broken = folder.write("broken.glb", makeGlb(gltfJson(parts), triangleBuffer()));
  CHECK(loadError(broken) == broken.string() + ": accessor 0 reads bytes 0..48 of bufferView 0, which has 36");
}

TEST_CASE("glTF errors name the file, the element and the problem") {
  TempFolder folder;

  SUBCASE("missing file") {
    const fs::path missing = folder.path() / "absent.gltf";
    CHECK(loadError(missing) == missing.string() + ": no such file");
  }
  SUBCASE("unknown extension") {
    const std::string message = loadError(folder.write("scene.obj", "o triangle"));
    CHECK(message.find("scene.obj: ") != std::string::npos);
    CHECK(message.find(".gltf or .glb") != std::string::npos);
  }
  SUBCASE("invalid JSON") {
    const fs::path path = folder.write("broken.gltf", R"({"asset": {"version": "2.0"}, "nodes": [)");
    const std::string message = loadError(path);
    CHECK(message.find(path.string() + ": ") == 0);
    CHECK(message.find("is not valid JSON") != std::string::npos);  // checked before tinygltf parses
  }
  SUBCASE("accessor past its bufferView") {
    GltfParts parts;
    parts.positionCount = "4";
    const fs::path path = writeTriangleGltf(folder, parts);
    CHECK(loadError(path) == path.string() + ": accessor 0 reads bytes 0..48 of bufferView 0, which has 36");
  }
  SUBCASE("bufferView past its buffer") {
    GltfParts parts;
    parts.indexView = R"("byteOffset":40,"byteLength":6)";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("scene.gltf: bufferView 1 spans bytes 40..46 of buffer 0, which has 44") != std::string::npos);
  }
  SUBCASE("index beyond the vertices") {
    const fs::path path = writeTriangleGltf(folder, {}, triangleBuffer({0, 1, 3}));
    const std::string message = loadError(path);
    CHECK(message.find(path.string() + ": mesh 0 primitive 0: index 2 of accessor 1 is 3") == 0);
  }
  SUBCASE("unknown primitive mode") {
    GltfParts parts;
    parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"mode":7})";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("scene.gltf: mesh 0 primitive 0 has mode 7, expected 0..6") != std::string::npos);
  }
  SUBCASE("no POSITION") {
    GltfParts parts;
    parts.primitive = R"({"attributes":{"NORMAL":0},"indices":1})";
    CHECK(loadError(writeTriangleGltf(folder, parts)).find("mesh 0 primitive 0 has no POSITION") != std::string::npos);
  }
  SUBCASE("wrong component type") {
    GltfParts parts;
    parts.primitive = R"({"attributes":{"POSITION":0},"indices":0})";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("mesh 0 primitive 0 indices accessor 0 is FLOAT VEC3, expected UNSIGNED_BYTE SCALAR") !=
          std::string::npos);
  }
  SUBCASE("attribute counts differ") {
    GltfParts parts;
    parts.primitive = R"({"attributes":{"POSITION":0,"NORMAL":2},"indices":1})";
    parts.moreAccessors = R"(,{"bufferView":0,"componentType":5126,"count":2,"type":"VEC3"})";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("NORMAL accessor 2 has 2 elements, but POSITION accessor 0 has 3") != std::string::npos);
  }
  SUBCASE("non-finite position") {
    const fs::path path = writeTriangleGltf(folder, {}, triangleBuffer({0, 1, 2}, NAN));
    CHECK(loadError(path).find("accessor 0 (POSITION of mesh 0 primitive 0) has a non-finite value at element 0") !=
          std::string::npos);
  }
  SUBCASE("node cycle") {
    GltfParts parts;
    parts.nodes = R"([{"mesh":0,"children":[1]},{"children":[0]}])";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("scene.gltf: node 1 has child node 0") != std::string::npos);
    CHECK(message.find("cycle") != std::string::npos);
  }
  SUBCASE("external image missing") {
    GltfParts parts;
    parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":0})";
    parts.extra = R"(,"materials":[{"normalTexture":{"index":0}}],"textures":[{"source":0}],
                     "images":[{"uri":"absent.png"}])";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("image 0 (uri 'absent.png') could not be loaded") != std::string::npos);
  }
  SUBCASE("unsupported required extension") {
    GltfParts parts;
    parts.extra =
        R"(,"extensionsUsed":["KHR_draco_mesh_compression"],"extensionsRequired":["KHR_draco_mesh_compression"])";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("requires extension KHR_draco_mesh_compression, which is not supported") != std::string::npos);
  }
  SUBCASE("every unsupported required extension is named at once") {
    GltfParts parts;
    parts.extra = R"(,"extensionsUsed":["KHR_draco_mesh_compression","KHR_texture_basisu","KHR_texture_transform"],
                    "extensionsRequired":["KHR_draco_mesh_compression","KHR_texture_transform","KHR_texture_basisu"])";
    const std::string message = loadError(writeTriangleGltf(folder, parts));
    CHECK(message.find("requires extensions KHR_draco_mesh_compression, KHR_texture_basisu, which are not supported") !=
          std::string::npos);
  }
}

// ---- Never silent: features that are not rendered are named ----------------

const IgnoredFeature* findIgnored(const Scene& scene, const std::string& feature) {
  for (const IgnoredFeature& ignored : scene.ignored) {
    if (ignored.feature == feature) return &ignored;
  }
  return nullptr;
}

TEST_CASE("glTF: a texCoord other than 0 loads, sampling TEXCOORD_0, and is named") {
  TempFolder folder;
  const std::string png =
      "iVBORw0KGgoAAAANSUhEUgAAAAEAAAACCAIAAAAW4yFwAAAADUlEQVR4nGP4zwAC/wEIAAH/2ZC7NQAAAABJRU5ErkJggg==";
  GltfParts parts;
  parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":0})";
  parts.extra = R"(,"materials":[{"name":"Cloth","normalTexture":{"index":0,"texCoord":1}}],
                   "textures":[{"source":0}],"images":[{"uri":"data:image/png;base64,)" +
                png + R"("}])";
  const Scene scene = loadGltf(writeTriangleGltf(folder, parts));
  REQUIRE(scene.ignored.size() == 1);
  CHECK(scene.ignored[0].describe() ==
        "TEXCOORD_1 on 1 material (first: material 0 'Cloth') is not rendered (TEXCOORD_0 is sampled instead)");
}

TEST_CASE("glTF: each feature that is not rendered is named once, with a count and the first element") {
  TempFolder folder;
  GltfParts parts;
  parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":1})";
  parts.extra = R"(,"extensionsUsed":["KHR_materials_sheen","KHR_materials_unlit","KHR_xmp"],
    "extensionsRequired":["KHR_materials_unlit"],
    "materials":[{"name":"A","alphaMode":"BLEND"},
                 {"name":"Cloth","extensions":{"KHR_materials_sheen":{},"KHR_materials_unlit":{}}},
                 {"extensions":{"KHR_materials_sheen":{}}},{"alphaMode":"MASK"}],
    "animations":[{"name":"Walk","channels":[],"samplers":[]},{"channels":[],"samplers":[]}])";
  const Scene scene = loadGltf(writeTriangleGltf(folder, parts));  // material 3's MASK is rendered: not named
  CHECK(scene.triangleCount() == 1);  // KHR_materials_unlit, though required, leaves the geometry right
  std::vector<std::string> lines;
  for (const IgnoredFeature& feature : scene.ignored) lines.push_back(feature.describe());
  const std::vector<std::string> expected{
      "alphaMode BLEND on 1 material (first: material 0 'A') is not rendered (drawn opaque)",
      "2 animations (first: animation 0 'Walk') are not played (the static pose is drawn)",
      "KHR_materials_sheen on 2 materials (first: material 1 'Cloth') is not rendered",
      "KHR_materials_unlit on 1 material (first: material 1 'Cloth') is not rendered",
      "KHR_xmp (listed in extensionsUsed) is not rendered",
  };
  CHECK(lines == expected);

  SceneLoadOptions strict;
  strict.strictGltf = true;
  const std::string message = loadError(folder.path() / "scene.gltf", strict);
  CHECK(message.find("scene.gltf: strict-gltf: alphaMode BLEND on 1 material") != std::string::npos);
  CHECK(message.find("; KHR_xmp (listed in extensionsUsed) is not rendered") != std::string::npos);
}

TEST_CASE("glTF: points and lines are skipped and named; strips and fans become triangle lists") {
  TempFolder folder;
  // Four vertices of a unit quad: (0,0) (1,0) (0,1) (1,1), indices 0 1 2 3.
  const float positions[12] = {0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0};
  const std::uint16_t indices[4] = {0, 1, 2, 3};
  std::vector<unsigned char> buffer(56, 0);
  std::memcpy(buffer.data(), positions, sizeof positions);
  std::memcpy(buffer.data() + 48, indices, sizeof indices);
  folder.write("quad.bin", buffer);
  auto write = [&](int mode) {
    const std::string json =
        R"({"asset":{"version":"2.0"},"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],
        "meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1,"mode":)" +
        std::to_string(mode) + R"(}]}],"buffers":[{"uri":"quad.bin","byteLength":56}],
        "bufferViews":[{"buffer":0,"byteLength":48},{"buffer":0,"byteOffset":48,"byteLength":8}],
        "accessors":[{"bufferView":0,"componentType":5126,"count":4,"type":"VEC3"},
                     {"bufferView":1,"componentType":5123,"count":4,"type":"SCALAR"}]})";
    return folder.write("mode" + std::to_string(mode) + ".gltf", json);
  };
  SUBCASE("TRIANGLE_STRIP: (0 1 2) and (2 1 3), both counter-clockwise") {
    const Scene scene = loadGltf(write(5));
    REQUIRE(scene.primitives.size() == 1);
    CHECK(scene.primitives[0].indices == std::vector<std::uint32_t>{0, 1, 2, 2, 1, 3});
    CHECK(scene.ignored.empty());
    for (const glm::vec3& normal : scene.primitives[0].normals) CHECK(near(normal, {0, 0, 1}));
  }
  SUBCASE("TRIANGLE_FAN: (0 1 2) and (0 2 3)") {
    const Scene scene = loadGltf(write(6));
    REQUIRE(scene.primitives.size() == 1);
    CHECK(scene.primitives[0].indices == std::vector<std::uint32_t>{0, 1, 2, 0, 2, 3});
  }
  SUBCASE("LINE_STRIP: no instance, named") {
    const Scene scene = loadGltf(write(3));
    CHECK(scene.instances.empty());
    REQUIRE(scene.ignored.size() == 1);
    CHECK(scene.ignored[0].describe() == "mode LINE_STRIP on 1 primitive (first: mesh 0 primitive 0) is not rendered (skipped)");
  }
}

TEST_CASE("glTF: --scene picks a scene by index or name") {
  TempFolder folder;
  GltfParts parts;
  parts.nodes = R"([{"mesh":0},{"mesh":0,"translation":[5,0,0]},{"mesh":0,"translation":[9,0,0]}])";
  parts.sceneNodes = R"([0],"name":"first"},{"nodes":[1,2],"name":"second")";
  const fs::path path = writeTriangleGltf(folder, parts);
  CHECK(loadGltf(path).instances.size() == 1);
  SceneLoadOptions options;
  options.gltfScene = "1";
  CHECK(loadGltf(path, options).instances.size() == 2);
  options.gltfScene = "second";
  CHECK(loadGltf(path, options).worldBounds().max.x == doctest::Approx(10.0f));
  options.gltfScene = "2";
  CHECK(loadError(path, options).find("scene.gltf: scene 2: the file has 2 scenes (0 'first', 1 'second')") !=
        std::string::npos);
}

TEST_CASE("glTF: URIs outside the asset folder are refused unless allowed") {
  TempFolder folder;
  folder.write("outside.bin", triangleBuffer());
  GltfParts parts;
  parts.bufferUri = "../outside.bin";
  const fs::path path = folder.write("asset/scene.gltf", gltfJson(parts));

  const std::string message = loadError(path);
  CHECK(message.find(path.string() + ": ") == 0);
  CHECK(message.find("URI '../outside.bin'") != std::string::npos);
  CHECK(message.find("outside the asset folder") != std::string::npos);

  SceneLoadOptions allowed;
  allowed.allowExternalPaths = true;
  CHECK(loadGltf(path, allowed).triangleCount() == 1);
}

TEST_CASE("glTF: KHR_mesh_quantization's integer attributes decode as the extension says") {
  TempFolder folder;
  // POSITION: normalized SHORT VEC3 (stride 8); NORMAL: normalized BYTE VEC3 (stride 4).
  const std::int16_t positions[12] = {0, 0, 0, 0, 32767, 0, 0, 0, 0, -32767, 0, 0};
  const std::int8_t normals[12] = {0, 0, 127, 0, 0, 127, 0, 0, -128, 0, 0, 0};
  std::vector<unsigned char> bytes(sizeof positions + sizeof normals);
  std::memcpy(bytes.data(), positions, sizeof positions);
  std::memcpy(bytes.data() + sizeof positions, normals, sizeof normals);
  auto write = [&](const std::string& name, const std::string& extensions) {
    return folder.write(name, R"({"asset":{"version":"2.0"},)" + extensions + R"("scenes":[{"nodes":[0]}],
      "nodes":[{"mesh":0}],"meshes":[{"primitives":[{"attributes":{"POSITION":0,"NORMAL":1}}]}],
      "buffers":[{"byteLength":36,"uri":"data:application/octet-stream;base64,)" + base64(bytes) + R"("}],
      "bufferViews":[{"buffer":0,"byteLength":24,"byteStride":8},{"buffer":0,"byteOffset":24,"byteLength":12,"byteStride":4}],
      "accessors":[{"bufferView":0,"componentType":5122,"normalized":true,"count":3,"type":"VEC3"},
                   {"bufferView":1,"componentType":5120,"normalized":true,"count":3,"type":"VEC3"}]})");
  };
  const Scene scene = loadGltf(write("quantized.gltf", R"("extensionsUsed":["KHR_mesh_quantization"],
                                                         "extensionsRequired":["KHR_mesh_quantization"],)"));
  REQUIRE(scene.primitives.size() == 1);
  const Primitive& primitive = scene.primitives[0];
  CHECK(near(primitive.positions[0], {0, 0, 0}));
  CHECK(near(primitive.positions[1], {1, 0, 0}));
  CHECK(near(primitive.positions[2], {0, -1, 0}));
  CHECK(near(primitive.normals[0], {0, 0, 1}));
  CHECK(near(primitive.normals[1], {0, 1, 0}));
  CHECK(near(primitive.normals[2], {-1, 0, 0}));  // -128 and -127 are both -1
  CHECK(scene.ignored.empty());
  // Without the extension the formats are core glTF's.
  CHECK(loadError(write("plain.gltf", "")).find("POSITION accessor 0 is normalized SHORT VEC3, expected FLOAT VEC3") !=
        std::string::npos);
}

// ---- Tangents (MikkTSpace's rules) -----------------------------------------

namespace {

// A unit quad in the XY plane facing +Z, two triangles, with `uvs`.
Primitive quad(const std::vector<glm::vec2>& uvs) {
  Primitive primitive;
  primitive.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  primitive.normals.assign(4, glm::vec3(0, 0, 1));
  primitive.texcoords = uvs;
  primitive.indices = {0, 1, 2, 0, 2, 3};
  return primitive;
}

bool near4(const glm::vec4& a, const glm::vec4& b) {
  return glm::all(glm::lessThanEqual(glm::abs(a - b), glm::vec4(1e-5f)));
}

}  // namespace

TEST_CASE("tangents: a quad's tangent follows +u, with w = +1 when v runs down the image as glTF's does") {
  // Seen from +Z: u along +X, v along -Y (top-left UV origin, as glTF's).
  Primitive primitive = quad({{0, 1}, {1, 1}, {1, 0}, {0, 0}});
  generateTangents(primitive);
  REQUIRE(primitive.tangents.size() == 4);
  for (const glm::vec4& tangent : primitive.tangents) CHECK(near4(tangent, {1, 0, 0, 1}));
  // v along +Y instead: the bitangent cross(N, T) w must point up the image (-Y), so w = -1.
  Primitive flippedV = quad({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  generateTangents(flippedV);
  for (const glm::vec4& tangent : flippedV.tangents) CHECK(near4(tangent, {1, 0, 0, -1}));
}

TEST_CASE("tangents: a mirrored-UV quad has w = -1, and a seam between mirrored halves splits its vertices") {
  Primitive mirrored = quad({{1, 1}, {0, 1}, {0, 0}, {1, 0}});  // u runs along -X
  generateTangents(mirrored);
  REQUIRE(mirrored.tangents.size() == 4);
  for (const glm::vec4& tangent : mirrored.tangents) CHECK(near4(tangent, {-1, 0, 0, -1}));

  // Two quads sharing the edge x = 1, the second with u mirrored (as a
  // symmetric model's UVs are): the shared vertices get one tangent per side.
  Primitive seam;
  seam.positions = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}, {2, 0, 0}, {2, 1, 0}};
  seam.normals.assign(6, glm::vec3(0, 0, 1));
  seam.texcoords = {{0, 1}, {1, 1}, {1, 0}, {0, 0}, {0, 1}, {0, 0}};
  seam.indices = {0, 1, 2, 0, 2, 3, 1, 4, 5, 1, 5, 2};
  generateTangents(seam);
  CHECK(seam.positions.size() == 8);  // vertices 1 and 2 split
  CHECK(seam.tangents.size() == 8);
  for (std::size_t corner = 0; corner < seam.indices.size(); ++corner) {
    const glm::vec4& tangent = seam.tangents[seam.indices[corner]];
    CAPTURE(corner);
    CHECK(near4(tangent, corner < 6 ? glm::vec4(1, 0, 0, 1) : glm::vec4(-1, 0, 0, -1)));
  }
}

TEST_CASE("tangents: a vertex whose triangles have no UV area gets a unit tangent perpendicular to its normal") {
  Primitive primitive = quad({{0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}, {0.5f, 0.5f}});
  generateTangents(primitive);
  for (const glm::vec4& tangent : primitive.tangents) {
    CHECK(std::abs(glm::length(glm::vec3(tangent)) - 1.0f) < 1e-5f);
    CHECK(std::abs(glm::dot(glm::vec3(tangent), glm::vec3(0, 0, 1))) < 1e-5f);
  }
}

TEST_CASE("glTF: KHR_materials_pbrSpecularGlossiness is approximated as metallic-roughness, and says so") {
  TempFolder folder;
  GltfParts parts;
  parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":0})";
  parts.extra = R"(,"extensionsUsed":["KHR_materials_pbrSpecularGlossiness"],
    "extensionsRequired":["KHR_materials_pbrSpecularGlossiness"],
    "materials":[{"name":"Old","extensions":{"KHR_materials_pbrSpecularGlossiness":
      {"diffuseFactor":[0.5,0.25,1,1],"specularFactor":[1,1,1],"glossinessFactor":0.75}}}])";
  const Scene scene = loadGltf(writeTriangleGltf(folder, parts));
  REQUIRE(scene.materials.size() == 1);
  CHECK(near(glm::vec3(scene.materials[0].baseColorFactor), {0.5f, 0.25f, 1.0f}));
  CHECK(scene.materials[0].metallicFactor == 0.0f);
  CHECK(scene.materials[0].roughnessFactor == doctest::Approx(0.25f));
  REQUIRE(scene.ignored.size() == 1);
  CHECK(scene.ignored[0].describe().find(
            "KHR_materials_pbrSpecularGlossiness on 1 material (first: material 0 'Old') is approximated") == 0);
}

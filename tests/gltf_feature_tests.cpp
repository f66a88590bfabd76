// glTF features beyond the core, without GL: what is named as not rendered
// (once, with a count and the first element), primitive modes, --scene,
// the asset-folder sandbox, KHR_mesh_quantization and the specular-glossiness
// conversion.
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
#include "gltf_test_files.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using namespace headlight;
using namespace headlight::test;

// ---- Never silent: features that are not rendered are named ----------------

TEST_CASE("glTF: a texCoord past 1 loads, sampling TEXCOORD_0, and is named") {
  TempFolder folder;
  const std::string png =
      "iVBORw0KGgoAAAANSUhEUgAAAAEAAAACCAIAAAAW4yFwAAAADUlEQVR4nGP4zwAC/wEIAAH/2ZC7NQAAAABJRU5ErkJggg==";
  GltfParts parts;
  parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":0})";
  parts.extra = R"(,"materials":[{"name":"Cloth","normalTexture":{"index":0,"texCoord":2}}],
                   "textures":[{"source":0}],"images":[{"uri":"data:image/png;base64,)" +
                png + R"("}])";
  const Scene scene = loadGltf(writeTriangleGltf(folder, parts));
  REQUIRE(scene.ignored.size() == 1);
  CHECK(scene.ignored[0].describe() ==
        "TEXCOORD_2 on 1 material (first: material 0 'Cloth') is not rendered (TEXCOORD_0 is sampled instead)");
}

TEST_CASE("glTF: each feature that is not rendered is named once, with a count and the first element") {
  TempFolder folder;
  GltfParts parts;
  parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":1})";
  parts.extra = R"(,"extensionsUsed":["KHR_materials_dispersion","KHR_materials_unlit","KHR_xmp"],
    "extensionsRequired":["KHR_materials_unlit"],
    "materials":[{"name":"A","alphaMode":"BLEND"},
                 {"name":"Cloth","extensions":{"KHR_materials_dispersion":{},"KHR_materials_unlit":{}}},
                 {"extensions":{"KHR_materials_dispersion":{}}},{"alphaMode":"MASK"}],
    "animations":[{"name":"Walk","channels":[],"samplers":[]},{"channels":[],"samplers":[]}])";
  const Scene scene = loadGltf(writeTriangleGltf(folder, parts));  // material 3's MASK is rendered: not named
  CHECK(scene.triangleCount() == 1);  // KHR_materials_unlit, though required, leaves the geometry right
  std::vector<std::string> lines;
  for (const IgnoredFeature& feature : scene.ignored) lines.push_back(feature.describe());
  const std::vector<std::string> expected{
      "2 animations (first: animation 0 'Walk') are not played (the static pose is drawn; --animation N|NAME "
      "--time SECONDS poses the file by one)",
      "KHR_materials_dispersion on 2 materials (first: material 1 'Cloth') is not rendered",
      "KHR_xmp (listed in extensionsUsed) is not rendered",
  };
  CHECK(lines == expected);

  SceneLoadOptions strict;
  strict.strictGltf = true;
  const std::string message = loadError(folder.path() / "scene.gltf", strict);
  CHECK(message.find("scene.gltf: strict-gltf: 2 animations") != std::string::npos);
  CHECK(message.find("; KHR_xmp (listed in extensionsUsed) is not rendered") != std::string::npos);
}

TEST_CASE("glTF: line strips become segment lists; triangle strips and fans become triangle lists") {
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
  SUBCASE("LINE_STRIP: drawn as a list of segments, nothing named") {
    const Scene scene = loadGltf(write(3));
    CHECK(scene.instances.size() == 1);
    REQUIRE(scene.primitives.size() == 1);
    CHECK(scene.primitives[0].indices == std::vector<std::uint32_t>{0, 1, 1, 2, 2, 3});
    CHECK(scene.ignored.empty());
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

TEST_CASE("glTF: KHR_materials_pbrSpecularGlossiness is rendered through the specular lobe, not named") {
  TempFolder folder;
  GltfParts parts;
  parts.primitive = R"({"attributes":{"POSITION":0},"indices":1,"material":0})";
  // A pbrMetallicRoughness fallback, as exporters write one: the extension wins.
  parts.extra = R"(,"extensionsUsed":["KHR_materials_pbrSpecularGlossiness"],
    "extensionsRequired":["KHR_materials_pbrSpecularGlossiness"],
    "materials":[{"name":"Old","pbrMetallicRoughness":{"metallicFactor":1,"roughnessFactor":0.5},
      "extensions":{"KHR_materials_pbrSpecularGlossiness":
      {"diffuseFactor":[0.5,0.25,1,1],"specularFactor":[1,0.75,0.5],"glossinessFactor":0.75}}}])";
  const Scene scene = loadGltf(writeTriangleGltf(folder, parts));
  REQUIRE(scene.materials.size() == 1);
  const Material& m = scene.materials[0];
  CHECK(near(glm::vec3(m.baseColorFactor), {0.5f, 0.25f, 1.0f}));
  CHECK(m.metallicFactor == 0.0f);
  CHECK(m.roughnessFactor == doctest::Approx(0.25f));
  CHECK_FALSE(m.roughnessFromGlossiness);
  // F0 = ((ior - 1) / (ior + 1))^2 x specular colour with ior 0: the colour itself, at full weight.
  REQUIRE(m.specular);
  CHECK(near(m.specular->specularColorFactor, {1.0f, 0.75f, 0.5f}));
  CHECK(m.specular->specularFactor == 1.0f);
  CHECK(m.ior == 0.0f);
  CHECK(scene.ignored.empty());

  // The specularGlossinessTexture: the specular colour (sRGB RGB) and, in
  // the metallic-roughness slot, the glossiness (A) times the factor.
  const std::string png =
      "iVBORw0KGgoAAAANSUhEUgAAAAEAAAACCAIAAAAW4yFwAAAADUlEQVR4nGP4zwAC/wEIAAH/2ZC7NQAAAABJRU5ErkJggg==";
  parts.extra = R"(,"extensionsUsed":["KHR_materials_pbrSpecularGlossiness"],
    "materials":[{"extensions":{"KHR_materials_pbrSpecularGlossiness":
      {"glossinessFactor":0.5,"specularGlossinessTexture":{"index":0},"diffuseTexture":{"index":0}}}}],
    "textures":[{"source":0}],"images":[{"uri":"data:image/png;base64,)" +
                png + R"("}])";
  const Scene textured = loadGltf(writeTriangleGltf(folder, parts));
  const Material& t = textured.materials.at(0);
  CHECK(t.roughnessFromGlossiness);
  CHECK(t.roughnessFactor == doctest::Approx(0.5f));
  CHECK(t.metallicRoughnessTexture.image == 0);
  CHECK(t.baseColorTexture.image == 0);
  REQUIRE(t.specular);
  CHECK(t.specular->specularColorTexture.image == 0);
}

// Issue 17, the loader's side (no GL): TEXCOORD_1 decoded when a material
// samples it, KHR_texture_transform read and checked, KHR_materials_unlit
// read; the conformance models load with none of these named as not
// rendered. Generated files are written by the tests; the models are read
// from ../shared/gltf-conformance (a missing folder is a skip).
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "frame/frame_plan.hpp"
#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "reference/texture_sampler.hpp"
#include "support/assets.hpp"
#include "support/encoding.hpp"
#include "support/scene_checks.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using namespace headlight;
using headlight::test::conformanceGltf;
using headlight::test::findIgnored;
using headlight::test::haveConformanceModel;
using nlohmann::json;

namespace {

void append(std::vector<unsigned char>& bytes, const void* data, std::size_t size) {
  const auto* begin = static_cast<const unsigned char*>(data);
  bytes.insert(bytes.end(), begin, begin + size);
}

// One triangle with TEXCOORD_0 (accessor 1) and TEXCOORD_1 (accessor 2,
// other values), a 1x1 texture, and material 0 whose baseColorTexture is
// `textureInfo`; mesh 0 is drawn by node 0.
json uvTriangle(const json& textureInfo) {
  const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const float uv0[] = {0, 0, 1, 0, 0, 1};
  const float uv1[] = {0.5f, 0.25f, 0.75f, 0.25f, 0.5f, 0.125f};
  std::vector<unsigned char> bytes;
  append(bytes, positions, sizeof positions);
  append(bytes, uv0, sizeof uv0);
  append(bytes, uv1, sizeof uv1);
  const auto view = [](std::size_t offset, std::size_t length) {
    return json{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}};
  };
  json document = {
      {"asset", {{"version", "2.0"}}},
      {"buffers",
       {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + test::base64(bytes)}}}},
      {"bufferViews", {view(0, 36), view(36, 24), view(60, 24)}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"type", "VEC3"}, {"count", 3}},
        {{"bufferView", 1}, {"componentType", 5126}, {"type", "VEC2"}, {"count", 3}},
        {{"bufferView", 2}, {"componentType", 5126}, {"type", "VEC2"}, {"count", 3}}}},
      {"meshes",
       {{{"primitives",
          {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}, {"TEXCOORD_1", 2}}}, {"material", 0}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0},
      {"images",
       {{{"uri", "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR42mNkYPhfDwAChwGA60e6kgAAAABJRU5ErkJggg=="}}}},
      {"textures", {{{"source", 0}}}},
      {"materials", {{{"name", "Uv"}, {"pbrMetallicRoughness", {{"baseColorTexture", textureInfo}}}}}},
  };
  return document;
}

Scene loadDocument(const test::TempFolder& folder, const json& document) {
  return loadGltf(folder.write("scene.gltf", document.dump()));
}

std::string documentLoadError(const test::TempFolder& folder, const json& document) {
  try {
    loadDocument(folder, document);
  } catch (const SceneError& error) {
    return error.what();
  }
  return "(loaded)";
}

}  // namespace

// ---- TEXCOORD_1 ---------------------------------------------------------------

TEST_CASE("glTF: TEXCOORD_1 is decoded when a material samples it, and not otherwise") {
  test::TempFolder folder;
  SUBCASE("texCoord 1") {
    const Scene scene = loadDocument(folder, uvTriangle({{"index", 0}, {"texCoord", 1}}));
    CHECK(scene.ignored.empty());
    REQUIRE(scene.primitives.size() == 1);
    CHECK(scene.materials[0].baseColorTexture.texCoord == 1);
    REQUIRE(scene.primitives[0].texcoords1.size() == 3);
    CHECK(scene.primitives[0].texcoords1[1] == glm::vec2(0.75f, 0.25f));
    CHECK(scene.primitives[0].texcoords[1] == glm::vec2(1.0f, 0.0f));
  }
  SUBCASE("texCoord 0: TEXCOORD_1 is left undecoded") {
    const Scene scene = loadDocument(folder, uvTriangle({{"index", 0}}));
    CHECK(scene.primitives[0].texcoords1.empty());
    CHECK(scene.primitives[0].texcoords.size() == 3);
  }
  SUBCASE("KHR_texture_transform's texCoord overrides the reference's") {
    const Scene scene = loadDocument(
        folder, uvTriangle({{"index", 0}, {"extensions", {{"KHR_texture_transform", {{"texCoord", 1}}}}}}));
    CHECK(scene.materials[0].baseColorTexture.texCoord == 1);
    CHECK(scene.primitives[0].texcoords1.size() == 3);
  }
  SUBCASE("a set the primitive lacks samples (0, 0), as TEXCOORD_0 does") {
    json document = uvTriangle({{"index", 0}, {"texCoord", 1}});
    document["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_1");
    const Scene scene = loadDocument(folder, document);
    REQUIRE(scene.primitives[0].texcoords1.size() == 3);
    CHECK(scene.primitives[0].texcoords1[2] == glm::vec2(0.0f));
  }
  SUBCASE("TEXCOORD_2 and beyond are named, sampling TEXCOORD_0") {
    const Scene scene = loadDocument(folder, uvTriangle({{"index", 0}, {"texCoord", 2}}));
    const IgnoredFeature* named = findIgnored(scene, "TEXCOORD_2");
    REQUIRE(named != nullptr);
    CHECK(named->describe() ==
          "TEXCOORD_2 on 1 material (first: material 0 'Uv') is not rendered (TEXCOORD_0 is sampled instead)");
    CHECK(scene.primitives[0].texcoords1.empty());
  }
}

TEST_CASE("glTF: one primitive drawn with and without a TEXCOORD_1 material is decoded once for each") {
  test::TempFolder folder;
  json document = uvTriangle({{"index", 0}, {"texCoord", 1}});
  document["materials"].push_back({{"name", "Plain"}});
  json second = document["meshes"][0];
  second["primitives"][0]["material"] = 1;
  document["meshes"].push_back(second);
  document["nodes"].push_back({{"mesh", 1}});
  document["scenes"][0]["nodes"].push_back(1);
  const Scene scene = loadDocument(folder, document);
  REQUIRE(scene.primitives.size() == 2);
  REQUIRE(scene.instances.size() == 2);
  CHECK(scene.primitives[std::size_t(scene.instances[0].primitive)].texcoords1.size() == 3);
  CHECK(scene.primitives[std::size_t(scene.instances[1].primitive)].texcoords1.empty());
}

TEST_CASE("MultiUVTest: TEXCOORD_1 holds the file's accessor, and nothing is named" *
          doctest::skip(!haveConformanceModel("MultiUVTest"))) {
  const Scene scene = loadGltf(conformanceGltf("MultiUVTest"));
  CHECK(scene.ignored.empty());
  REQUIRE(scene.primitives.size() == 1);
  CHECK(scene.materials[0].emissiveTexture.texCoord == 1);
  CHECK(scene.materials[0].baseColorTexture.texCoord == 0);
  // Accessor 5 (TEXCOORD_1), read here from the .bin without the loader.
  std::ifstream file(conformanceGltf("MultiUVTest"));
  const json document = json::parse(file);
  const json& accessor = document["accessors"][5];
  const json& view = document["bufferViews"][accessor["bufferView"].get<int>()];
  REQUIRE(accessor["componentType"] == 5126);
  std::ifstream bin(conformanceGltf("MultiUVTest").parent_path() / document["buffers"][0]["uri"].get<std::string>(),
                    std::ios::binary);
  bin.seekg(view.value("byteOffset", 0) + accessor.value("byteOffset", 0));
  std::vector<glm::vec2> expected(accessor["count"].get<std::size_t>());
  bin.read(reinterpret_cast<char*>(expected.data()), std::streamsize(expected.size() * sizeof(glm::vec2)));
  REQUIRE(bin.good());
  const Primitive& primitive = scene.primitives[0];
  REQUIRE(primitive.texcoords1.size() == expected.size());  // the file has TANGENT: no vertex is split
  CHECK(primitive.texcoords1 == expected);
  CHECK(primitive.texcoords != expected);
}

// ---- KHR_texture_transform ----------------------------------------------------

TEST_CASE("glTF: KHR_texture_transform is read on every texture reference") {
  test::TempFolder folder;
  const json transform = {{"offset", {0.25, -0.5}}, {"rotation", 0.5}, {"scale", {2, 3}}};
  json document = uvTriangle({{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}});
  document["extensionsUsed"] = {"KHR_texture_transform"};
  document["extensionsRequired"] = {"KHR_texture_transform"};  // rendered: accepted as required
  json& material = document["materials"][0];
  for (const char* slot : {"normalTexture", "occlusionTexture", "emissiveTexture"})
    material[slot] = {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}};
  material["pbrMetallicRoughness"]["metallicRoughnessTexture"] = material["normalTexture"];
  const Scene scene = loadDocument(folder, document);
  CHECK(scene.ignored.empty());
  const Material& m = scene.materials[0];
  for (const TextureRef* ref : {&m.baseColorTexture, &m.metallicRoughnessTexture, &m.normalTexture,
                                &m.occlusionTexture, &m.emissiveTexture}) {
    CHECK(ref->transform.offset == glm::vec2(0.25f, -0.5f));
    CHECK(ref->transform.rotation == 0.5f);
    CHECK(ref->transform.scale == glm::vec2(2.0f, 3.0f));
    CHECK(!ref->transform.identity());
  }
}

TEST_CASE("TextureTransform: T * R * S, the rotation turning the sampled image clockwise on screen") {
  // Scale, then rotate, then offset: (1, 0) scaled by 2 is (2, 0); turned by
  // 90 degrees it samples (0, -2) (u toward -v); offset by (0.5, 1): (0.5, -1).
  TextureTransform t;
  t.offset = {0.5f, 1.0f};
  t.rotation = 1.5707963f;
  t.scale = {2.0f, 3.0f};
  const glm::vec2 uv = t.apply({1.0f, 0.0f});
  CHECK(uv.x == doctest::Approx(0.5f).epsilon(1e-6));
  CHECK(uv.y == doctest::Approx(-1.0f).epsilon(1e-6));
  const glm::vec2 v = t.apply({0.0f, 1.0f});  // (0, 3) turned to (3, 0), offset
  CHECK(v.x == doctest::Approx(3.5f).epsilon(1e-6));
  CHECK(v.y == doctest::Approx(1.0f).epsilon(1e-5));
  CHECK(TextureTransform{}.identity());
  CHECK(TextureTransform{}.apply({0.3f, 0.7f}) == glm::vec2(0.3f, 0.7f));
}

TEST_CASE("the reference's textureUv: the reference's set, interpolated, then transformed") {
  Primitive primitive;
  primitive.texcoords = {{0, 0}, {1, 0}, {0, 1}};
  primitive.texcoords1 = {{0.5f, 0.5f}, {0.5f, 0.5f}, {1.0f, 0.5f}};
  primitive.indices = {0, 1, 2};
  TextureRef ref;
  ref.image = 0;
  CHECK(reference::textureUv(primitive, ref, primitive.indices.data(), 0.5f, 0.25f) == glm::vec2(0.5f, 0.25f));
  ref.texCoord = 1;
  CHECK(reference::textureUv(primitive, ref, primitive.indices.data(), 0.0f, 1.0f) == glm::vec2(1.0f, 0.5f));
  ref.transform.offset = {0.25f, 0.0f};
  CHECK(reference::textureUv(primitive, ref, primitive.indices.data(), 0.0f, 1.0f) == glm::vec2(1.25f, 0.5f));
  primitive.texcoords1.clear();  // no such set: (0, 0), transformed
  CHECK(reference::textureUv(primitive, ref, primitive.indices.data(), 0.0f, 1.0f) == glm::vec2(0.25f, 0.0f));
}

TEST_CASE("glTF: a KHR_texture_transform value that is not a finite number is refused, naming where") {
  test::TempFolder folder;
  const auto withTransform = [](const json& transform) {
    return uvTriangle({{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}});
  };
  CHECK(documentLoadError(folder, withTransform({{"offset", {1e39, 0}}}))
            .find("material 0 baseColorTexture (texture 0) KHR_texture_transform offset[0] is 1e+39, expected a finite "
                  "number") != std::string::npos);
  CHECK(documentLoadError(folder, withTransform({{"rotation", -1e300}}))
            .find("KHR_texture_transform rotation is -1e+300, expected a finite number") != std::string::npos);
  CHECK(documentLoadError(folder, withTransform({{"scale", {1}}}))
            .find("KHR_texture_transform scale is not an array of 2 numbers") != std::string::npos);
  CHECK(documentLoadError(folder, withTransform({{"offset", {"a", 0}}}))
            .find("KHR_texture_transform offset[0] is not a number") != std::string::npos);
  CHECK(documentLoadError(folder, withTransform({{"texCoord", -1}}))
            .find("KHR_texture_transform texCoord is not an integer >= 0") != std::string::npos);
  CHECK(documentLoadError(folder, withTransform({{"offset", {1e39, 0}}})).find("scene.gltf") != std::string::npos);
}

TEST_CASE("TextureTransformTest and TextureTransformMultiTest: transforms read, nothing named" *
          doctest::skip(!haveConformanceModel("TextureTransformTest") ||
                        !haveConformanceModel("TextureTransformMultiTest"))) {
  const Scene single = loadGltf(conformanceGltf("TextureTransformTest"));
  CHECK(single.ignored.empty());
  std::ifstream file(conformanceGltf("TextureTransformTest"));
  const json document = json::parse(file);
  REQUIRE(single.materials.size() == document["materials"].size());
  for (std::size_t i = 0; i < single.materials.size(); ++i) {
    CAPTURE(i);
    const json info = document["materials"][i]["pbrMetallicRoughness"]["baseColorTexture"];
    const json transform = info.value("extensions", json::object()).value("KHR_texture_transform", json::object());
    const TextureTransform& t = single.materials[i].baseColorTexture.transform;
    const json offset = transform.value("offset", json{0.0, 0.0}), scale = transform.value("scale", json{1.0, 1.0});
    CHECK(t.offset == glm::vec2(offset[0].get<float>(), offset[1].get<float>()));
    CHECK(t.scale == glm::vec2(scale[0].get<float>(), scale[1].get<float>()));
    CHECK(t.rotation == transform.value("rotation", 0.0f));
  }
  const Scene multi = loadGltf(conformanceGltf("TextureTransformMultiTest"));
  CHECK(multi.ignored.empty());  // its clearcoat is rendered (specular_clearcoat_conformance_tests.cpp)
  int transformed = 0, secondSet = 0, unlit = 0;
  for (const Material& m : multi.materials) {
    for (const TextureRef* ref : {&m.baseColorTexture, &m.metallicRoughnessTexture, &m.normalTexture,
                                  &m.occlusionTexture, &m.emissiveTexture}) {
      transformed += ref->present() && !ref->transform.identity();
      secondSet += ref->present() && ref->texCoord == 1;
    }
    unlit += m.unlit;
  }
  MESSAGE("TextureTransformMultiTest: " << transformed << " transformed references, " << secondSet
                                        << " on TEXCOORD_1, " << unlit << " unlit materials");
  CHECK(transformed > 0);
  CHECK(secondSet > 0);
  CHECK(unlit > 0);
}

// ---- KHR_materials_unlit ------------------------------------------------------

TEST_CASE("glTF: KHR_materials_unlit is read, and accepted as required" *
          doctest::skip(!haveConformanceModel("UnlitTest"))) {
  const Scene scene = loadGltf(conformanceGltf("UnlitTest"));
  CHECK(scene.ignored.empty());
  REQUIRE(scene.materials.size() == 2);
  CHECK(scene.materials[0].unlit);
  CHECK(scene.materials[1].unlit);
  CHECK(scene.materials[0].baseColorFactor.r == 1.0f);
  test::TempFolder folder;
  const Scene plain = loadDocument(folder, uvTriangle({{"index", 0}}));
  CHECK(!plain.materials[0].unlit);
}

TEST_CASE("frame plan: material.exr gains material.unlit only for a scene with an unlit material") {
  RenderSettings settings;
  settings.lighting.shadowMapSize = 1024;
  settings.lighting.skyIntensity = 1.0f;
  const auto materialChannels = [&](bool unlit) {
    SceneSummary scene;
    scene.unlit = unlit;
    const std::vector<std::string> targets{"material"};
    const FramePlan plan = planFrame(scene, settings, targets);
    REQUIRE(plan.reads.size() == 1);
    return plan.reads[0].channels;
  };
  CHECK(materialChannels(false) ==
        std::vector<std::string>{"material.metallic", "material.roughness", "material.occlusion"});
  CHECK(materialChannels(true) == std::vector<std::string>{"material.metallic", "material.roughness",
                                                           "material.occlusion", "material.unlit"});
  Scene scene;
  scene.materials.emplace_back();
  CHECK(!summarizeScene(scene).unlit);
  scene.materials.back().unlit = true;
  CHECK(summarizeScene(scene).unlit);
}

TEST_CASE("generated tangents follow the normal map's set and transform") {
  Primitive primitive;
  primitive.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  primitive.normals.assign(3, glm::vec3(0, 0, 1));
  primitive.indices = {0, 1, 2};
  for (const glm::vec3& p : primitive.positions) {
    primitive.texcoords.emplace_back(p.x, 1.0f - p.y);  // u along +x
    primitive.texcoords1.emplace_back(1.0f - p.y, p.x);  // u along -y
  }
  const auto tangentOf = [&](const TextureRef& ref) {
    Primitive copy = primitive;
    generateTangents(copy, ref);
    REQUIRE(copy.tangents.size() == 3);
    return glm::vec3(copy.tangents[0]);
  };
  TextureRef ref;
  ref.image = 0;
  CHECK(glm::length(tangentOf(ref) - glm::vec3(1, 0, 0)) < 1e-5f);
  ref.texCoord = 1;
  CHECK(glm::length(tangentOf(ref) - glm::vec3(0, -1, 0)) < 1e-5f);
  // Set 0 turned by 90 degrees: u' = v, which grows toward -y.
  ref.texCoord = 0;
  ref.transform.rotation = 1.5707963f;
  CHECK(glm::length(tangentOf(ref) - glm::vec3(0, -1, 0)) < 1e-5f);
}

// Issue 18 item 1's foundation and item 4, the loader's side (no GL): the
// KHR_materials_* extensions are read into Material with the
// specification's defaults, each range is checked with a message naming the
// material, the extension, the property and the value, and the frame plan
// learns which lobes a scene uses.
#include <doctest/doctest.h>

#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "frame/frame_plan.hpp"
#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "support/encoding.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
using nlohmann::json;

namespace {

// One triangle drawn with material 0, which has `extensions`; a 1x1 image
// for the extensions' textures to name.
json triangleWith(const json& extensions) {
  const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const auto* first = reinterpret_cast<const unsigned char*>(positions);
  const std::vector<unsigned char> bytes(first, first + sizeof positions);
  const std::string encoded = test::base64(bytes);
  return {{"asset", {{"version", "2.0"}}},
          {"buffers", {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + encoded}}}},
          {"bufferViews", {{{"buffer", 0}, {"byteLength", bytes.size()}}}},
          {"accessors",
           {{{"bufferView", 0},
             {"componentType", 5126},
             {"count", 3},
             {"type", "VEC3"},
             {"min", {0, 0, 0}},
             {"max", {1, 1, 0}}}}},
          {"images",
           {{{"uri",
              "data:image/png;base64,iVBORw0KGgoAAAANSUhEUgAAAAEAAAABCAYAAAAfFcSJAAAADUlEQVR4nGP4z8DwHwAFAAH/"
              "iZk9HQAAAABJRU5ErkJggg=="}}}},
          {"textures", {{{"source", 0}}}},
          {"materials", {{{"name", "Layered"}, {"extensions", extensions}}}},
          {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"material", 0}}}}}}},
          {"nodes", {{{"mesh", 0}}}},
          {"scenes", {{{"nodes", {0}}}}},
          {"scene", 0}};
}

Scene loadWithExtensions(const test::TempFolder& folder, const json& extensions) {
  return loadGltf(folder.write("scene.gltf", triangleWith(extensions).dump()));
}

std::string extensionLoadError(const test::TempFolder& folder, const json& extensions) {
  try {
    loadWithExtensions(folder, extensions);
  } catch (const SceneError& error) {
    return error.what();
  }
  return "(loaded)";
}

}  // namespace

TEST_CASE("material extensions: every one is read with its values, textures and transforms") {
  test::TempFolder folder;
  const json transform = {{"KHR_texture_transform", {{"scale", {2, 2}}}}};
  const Scene scene = loadWithExtensions(
      folder,
      {
          {"KHR_materials_ior", {{"ior", 1.33}}},
          {"KHR_materials_specular",
           {{"specularFactor", 0.5}, {"specularColorFactor", {1, 0.5, 2}}, {"specularColorTexture", {{"index", 0}}}}},
          {"KHR_materials_clearcoat",
           {{"clearcoatFactor", 1},
            {"clearcoatRoughnessFactor", 0.25},
            {"clearcoatNormalTexture", {{"index", 0}, {"scale", 0.5}, {"extensions", transform}}}}},
          {"KHR_materials_sheen", {{"sheenColorFactor", {0.1, 0.2, 0.3}}, {"sheenRoughnessFactor", 0.7}}},
          {"KHR_materials_iridescence",
           {{"iridescenceFactor", 1},
            {"iridescenceThicknessMaximum", 800},
            {"iridescenceThicknessTexture", {{"index", 0}}}}},
          {"KHR_materials_anisotropy", {{"anisotropyStrength", 0.6}, {"anisotropyRotation", -1.5}}},
          {"KHR_materials_transmission",
           {{"transmissionFactor", 0.9}, {"transmissionTexture", {{"index", 0}, {"texCoord", 1}}}}},
          {"KHR_materials_volume",
           {{"thicknessFactor", 0.2}, {"attenuationDistance", 0.5}, {"attenuationColor", {0.2, 0.4, 1}}}},
      });
  REQUIRE(scene.materials.size() == 1);
  const Material& m = scene.materials[0];
  CHECK(m.ior == doctest::Approx(1.33));
  REQUIRE(m.specular);
  CHECK(m.specular->specularFactor == doctest::Approx(0.5));
  CHECK(m.specular->specularColorFactor.b == doctest::Approx(2.0));
  CHECK(m.specular->specularColorTexture.present());
  CHECK(!m.specular->specularTexture.present());
  REQUIRE(m.clearcoat);
  CHECK(m.clearcoat->clearcoatFactor == 1.0f);
  CHECK(m.clearcoat->clearcoatRoughnessFactor == doctest::Approx(0.25));
  CHECK(m.clearcoat->clearcoatNormalScale == doctest::Approx(0.5));
  CHECK(m.clearcoat->clearcoatNormalTexture.present());
  CHECK(!m.clearcoat->clearcoatNormalTexture.transform.identity());
  REQUIRE(m.sheen);
  CHECK(m.sheen->sheenColorFactor.g == doctest::Approx(0.2));
  CHECK(m.sheen->sheenRoughnessFactor == doctest::Approx(0.7));
  REQUIRE(m.iridescence);
  CHECK(m.iridescence->iridescenceIor == doctest::Approx(1.3));  // the default
  CHECK(m.iridescence->iridescenceThicknessMinimum == doctest::Approx(100));
  CHECK(m.iridescence->iridescenceThicknessMaximum == doctest::Approx(800));
  CHECK(m.iridescence->iridescenceThicknessTexture.present());
  REQUIRE(m.anisotropy);
  CHECK(m.anisotropy->anisotropyRotation == doctest::Approx(-1.5));
  REQUIRE(m.transmission);
  CHECK(m.transmission->transmissionFactor == doctest::Approx(0.9));
  CHECK(m.transmission->transmissionTexture.texCoord == 1);
  REQUIRE(m.volume);
  CHECK(m.volume->attenuationDistance == doctest::Approx(0.5));
  CHECK(m.volume->attenuationColor.r == doctest::Approx(0.2));

  const SceneSummary summary = summarizeScene(scene);
  CHECK(summary.lobes == (lobeBit(Lobe::Specular) | lobeBit(Lobe::Clearcoat) | lobeBit(Lobe::Sheen) |
                          lobeBit(Lobe::Anisotropy) | lobeBit(Lobe::Iridescence)));
  CHECK(summary.transmission);
  std::vector<std::string> lobeFlags;
  for (const std::string& define : lobeDefines(summary.lobes))
    if (define.starts_with("HAS_")) lobeFlags.push_back(define);
  CHECK(lobeFlags == std::vector<std::string>{"HAS_SPECULAR_LOBE", "HAS_CLEARCOAT_LOBE", "HAS_SHEEN_LOBE",
                                              "HAS_ANISOTROPY_LOBE", "HAS_IRIDESCENCE_LOBE"});
}

TEST_CASE("material extensions: an empty extension object takes the specification's defaults") {
  test::TempFolder folder;
  const Scene scene = loadWithExtensions(folder, {{"KHR_materials_specular", json::object()},
                                                  {"KHR_materials_volume", json::object()},
                                                  {"KHR_materials_ior", json::object()}});
  const Material& m = scene.materials[0];
  CHECK(m.ior == 1.5f);
  REQUIRE(m.specular);
  CHECK(m.specular->specularFactor == 1.0f);
  CHECK(m.specular->specularColorFactor == glm::vec3(1.0f));
  REQUIRE(m.volume);
  CHECK(std::isinf(m.volume->attenuationDistance));
  CHECK(m.volume->thicknessFactor == 0.0f);
  CHECK(!m.clearcoat);
  // ior 1.5 alone changes nothing: only KHR_materials_specular makes the lobe.
  CHECK(materialLobes(m) == lobeBit(Lobe::Specular));
  // KHR_materials_volume without KHR_materials_transmission lets no light
  // through: no transmission pass (Material::transmissive).
  CHECK(!summarizeScene(scene).transmission);
}

TEST_CASE("material extensions: ior alone makes the specular lobe; none, no lobe; unlit, none") {
  Material plain;
  CHECK(materialLobes(plain) == 0);
  Material water;
  water.ior = 1.33f;
  CHECK(materialLobes(water) == lobeBit(Lobe::Specular));
  Material flat = water;
  flat.unlit = true;
  flat.clearcoat.emplace();
  CHECK(materialLobes(flat) == 0);
  Scene scene;
  scene.materials = {plain};
  CHECK(summarizeScene(scene).lobes == 0);
  CHECK(!summarizeScene(scene).transmission);
}

TEST_CASE("material extensions: glTF's ior 0 is kept; values between 0 and 1 are refused") {
  test::TempFolder folder;
  CHECK(loadWithExtensions(folder, {{"KHR_materials_ior", {{"ior", 0}}}}).materials[0].ior == 0.0f);
  const std::string error = extensionLoadError(folder, {{"KHR_materials_ior", {{"ior", 0.5}}}});
  CHECK(error.find("scene.gltf") != std::string::npos);
  CHECK(error.find("material 0 KHR_materials_ior ior is 0.5, expected a number >= 1 or 0") != std::string::npos);
}

TEST_CASE("material extensions: out-of-range, non-finite and malformed values are refused, named") {
  test::TempFolder folder;
  struct Case {
    json extensions;
    std::string message;
  };
  const Case cases[] = {
      {{{"KHR_materials_volume", {{"thicknessFactor", -1}}}},
       "material 0 KHR_materials_volume thicknessFactor is -1, expected a number >= 0"},
      {{{"KHR_materials_volume", {{"attenuationDistance", 0}}}},
       "material 0 KHR_materials_volume attenuationDistance is 0, expected a number > 0"},
      {{{"KHR_materials_volume", {{"attenuationDistance", -2}}}},
       "KHR_materials_volume attenuationDistance is -2, expected a number > 0"},
      {{{"KHR_materials_volume", {{"attenuationColor", {1, 2, 0}}}}},
       "KHR_materials_volume attenuationColor is 2, expected a number in 0..1"},
      {{{"KHR_materials_clearcoat", {{"clearcoatFactor", 1.5}}}},
       "KHR_materials_clearcoat clearcoatFactor is 1.5, expected a number in 0..1"},
      {{{"KHR_materials_specular", {{"specularColorFactor", {1, -0.5, 1}}}}},
       "KHR_materials_specular specularColorFactor is -0.5, expected a number >= 0"},
      {{{"KHR_materials_specular", {{"specularColorFactor", {1, 1}}}}},
       "KHR_materials_specular specularColorFactor is not 3 numbers"},
      {{{"KHR_materials_sheen", {{"sheenRoughnessFactor", "rough"}}}},
       "KHR_materials_sheen sheenRoughnessFactor is not a number"},
      {{{"KHR_materials_iridescence", {{"iridescenceIor", 0.9}}}},
       "KHR_materials_iridescence iridescenceIor is 0.9, expected a number >= 1"},
      {{{"KHR_materials_iridescence", {{"iridescenceThicknessMinimum", -10}}}},
       "KHR_materials_iridescence iridescenceThicknessMinimum is -10, expected a number >= 0"},
      {{{"KHR_materials_anisotropy", {{"anisotropyStrength", 2}}}},
       "KHR_materials_anisotropy anisotropyStrength is 2, expected a number in 0..1"},
      // Any finite value is allowed; past float's range is not, and the message says so (not ">= -inf").
      {{{"KHR_materials_anisotropy", {{"anisotropyRotation", 1e300}}}},
       "KHR_materials_anisotropy anisotropyRotation is 1e+300, expected a number that is finite in float"},
      {{{"KHR_materials_transmission", {{"transmissionFactor", -0.1}}}},
       "KHR_materials_transmission transmissionFactor is -0.1, expected a number in 0..1"},
      {{{"KHR_materials_transmission", {{"transmissionTexture", {{"index", 7}}}}}},
       "KHR_materials_transmission transmissionTexture refers to texture 7"},
      {{{"KHR_materials_clearcoat", {{"clearcoatTexture", {{"texCoord", 0}}}}}},
       "KHR_materials_clearcoat clearcoatTexture has no texture index"},
      // JSON has no NaN: a number too large for a float is the non-finite value a file can carry.
      {{{"KHR_materials_volume", {{"thicknessFactor", 1e300}}}},
       "KHR_materials_volume thicknessFactor is 1e+300, expected a number >= 0"},
  };
  for (const Case& c : cases) {
    const std::string error = extensionLoadError(folder, c.extensions);
    INFO(c.extensions.dump(), " -> ", error);
    CHECK(error.find("scene.gltf") != std::string::npos);
    CHECK(error.find(c.message) != std::string::npos);
  }
}

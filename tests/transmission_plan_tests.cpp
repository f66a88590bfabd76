// KHR_materials_transmission in the frame plan, without a GL context: the
// transmission pass, its target and its skip line exist only for scenes
// that transmit; the G-buffer pass defers the transmissive surfaces only
// when the pass runs.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "support/plan_settings.hpp"
#include "frame/frame_plan.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "support/encoding.hpp"
#include "support/temp_folder.hpp"
#include "headlight/shapes.hpp"
#include "reference/lobe_transmission.hpp"

namespace headlight {
namespace {

using test::skips;

SceneSummary transmittingScene() {
  SceneSummary scene;
  scene.planarShadowCasters = 1;
  scene.transmission = true;
  return scene;
}

bool reads(const FramePlan& plan, std::string_view name) {
  return std::any_of(plan.reads.begin(), plan.reads.end(),
                     [&](const TargetRead& read) { return read.target->name == name; });
}

// One triangle drawn with material 0: `material` (a glTF material object).
std::string triangleGltf(const nlohmann::json& material) {
  const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const auto* first = reinterpret_cast<const unsigned char*>(positions);
  const std::vector<unsigned char> bytes(first, first + sizeof positions);
  const nlohmann::json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"buffers", {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + test::base64(bytes)}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteLength", bytes.size()}}}},
      {"accessors",
       {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}}}},
      {"materials", {material}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}, {"material", 0}}}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"scenes", {{{"nodes", {0}}}}},
      {"scene", 0}};
  return gltf.dump();
}

bool namesTransmission(const Scene& scene) {
  return std::any_of(scene.ignored.begin(), scene.ignored.end(), [](const IgnoredFeature& feature) {
    return feature.feature == "KHR_materials_transmission" && feature.describe().find("BLEND") != std::string::npos;
  });
}

}  // namespace

TEST_CASE("transmission: rendered, so not named, except on an alphaMode BLEND or unlit material") {
  test::TempFolder folder;
  const nlohmann::json glass = {{"name", "Glass"},
                                {"extensions",
                                 {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                  {"KHR_materials_volume", {{"thicknessFactor", 0.5}}}}}};
  const Scene drawn = loadGltf(folder.write("glass.gltf", triangleGltf(glass)));
  CHECK(drawn.ignored.empty());
  CHECK(drawn.materials[0].transmissive());
  nlohmann::json blended = glass;
  blended["alphaMode"] = "BLEND";
  const Scene named = loadGltf(folder.write("blended.gltf", triangleGltf(blended)));
  CHECK(namesTransmission(named));
  CHECK(!named.materials[0].transmissive());
  nlohmann::json unlit = glass;
  unlit["extensions"]["KHR_materials_unlit"] = nlohmann::json::object();
  CHECK(namesTransmission(loadGltf(folder.write("unlit.gltf", triangleGltf(unlit)))));
}

TEST_CASE("transmission: a lobe on a transmissive material is lit, so nothing is named") {
  // Until the transmission pass composed the lobes (issue 34), these were
  // named as not lit; now they are rendered there as on opaque materials.
  test::TempFolder folder;
  const nlohmann::json coated = {{"name", "Coated glass"},
                                 {"extensions",
                                  {{"KHR_materials_transmission", {{"transmissionFactor", 1.0}}},
                                   {"KHR_materials_clearcoat", {{"clearcoatFactor", 1.0}}},
                                   {"KHR_materials_iridescence", {{"iridescenceFactor", 1.0}}}}}};
  const Scene scene = loadGltf(folder.write("coated.gltf", triangleGltf(coated)));
  REQUIRE(scene.materials[0].transmissive());
  CHECK(scene.ignored.empty());
  SceneLoadOptions strict;
  strict.strictGltf = true;
  CHECK_NOTHROW(loadGltf(folder.write("strict.gltf", triangleGltf(coated)), strict));
  // The plan's transmission variant carries the scene's lobes (its programs' HAS_<NAME>_LOBE).
  SceneSummary summary = summarizeScene(scene);
  REQUIRE(summary.transmission);
  const FramePlan plan = planFrame(summary, test::resolvedPlanSettings(), {});
  REQUIRE(plan.transmission);
  CHECK(plan.transmission->lobes == (lobeBit(Lobe::Clearcoat) | lobeBit(Lobe::Iridescence)));
}

TEST_CASE("transmission plan: a transmitting scene runs the pass after the composite and before the blend pass") {
  SceneSummary scene = transmittingScene();
  scene.blended = true;
  const FramePlan plan = planFrame(scene, test::resolvedPlanSettings(), {});
  REQUIRE(plan.transmission);
  // The planar map and its transmittance map (the glass tints its shadow), the sky term, no map.
  CHECK(*plan.transmission == TransmissionVariant{.shadows = {.planar = true, .transmittance = true}, .sky = true});
  CHECK(plan.gbuffer.deferTransmissive);
  CHECK(plan.allocates(Attachment::Transmission));
  CHECK(reads(plan, "transmission"));
  CHECK(!skips(plan, "transmission"));
  const std::vector<std::string_view> names = plan.passNames();
  const auto at = [&](std::string_view name) { return std::find(names.begin(), names.end(), name) - names.begin(); };
  CHECK(at("composite") < at("transmission"));
  CHECK(at("transmission") < at("blend"));
}

TEST_CASE("transmission plan: a scene without transmission has no pass, no target and no skip line") {
  SceneSummary scene = transmittingScene();
  scene.transmission = false;
  const FramePlan plan = planFrame(scene, test::resolvedPlanSettings(), {});
  CHECK(!plan.transmission);
  CHECK(!plan.gbuffer.deferTransmissive);
  CHECK(!plan.allocates(Attachment::Transmission));
  CHECK(!reads(plan, "transmission"));
  CHECK(!skips(plan, "transmission"));
  const std::vector<std::string_view> names = plan.passNames();
  CHECK(std::find(names.begin(), names.end(), "transmission") == names.end());
}

TEST_CASE("transmission plan: without lit the pass is skipped and named, and the G-buffer draws the surfaces") {
  const std::vector<std::string> targets{"albedo", "depth"};
  const FramePlan plan = planFrame(transmittingScene(), test::resolvedPlanSettings(), targets);
  CHECK(!plan.transmission);
  CHECK(skips(plan, "transmission"));
  // Nothing refracts, so nothing waits for the opaque image: the G-buffer
  // holds the transmissive surfaces from its own pass.
  CHECK(!plan.gbuffer.deferTransmissive);
  CHECK(!plan.allocates(Attachment::Transmission));
}

TEST_CASE("transmission plan: the pass follows the frame's shadows, sky and environment map") {
  SceneSummary scene = transmittingScene();
  scene.cubeShadowCasters = 1;
  scene.environment = true;
  RenderSettings settings = test::resolvedPlanSettings();
  settings.lighting.shadows = false;
  const FramePlan plan = planFrame(scene, settings, {});
  REQUIRE(plan.transmission);
  CHECK(*plan.transmission == TransmissionVariant{.sky = true, .environment = true});
}

TEST_CASE("transmission: which materials the pass draws") {
  Material glass = makeMaterial({1.0f, 1.0f, 1.0f}, 0.0f);
  CHECK(!glass.transmissive());
  glass.transmission = MaterialTransmission{1.0f, {}};
  CHECK(glass.transmissive());
  Material none = glass;
  none.transmission->transmissionFactor = 0.0f;  // no light transmitted: an ordinary surface
  CHECK(!none.transmissive());
  Material blended = glass;
  blended.alphaMode = AlphaMode::Blend;  // the blend pass draws it
  CHECK(!blended.transmissive());
  Material unlit = glass;
  unlit.unlit = true;  // the specification excludes the pair; unlit wins
  CHECK(!unlit.transmissive());
  Material masked = glass;
  masked.alphaMode = AlphaMode::Mask;  // a cut-out transmissive surface (TransmissionTest's)
  CHECK(masked.transmissive());
}

TEST_CASE("transmission: the CPU port's volume terms") {
  // Beer-Lambert: attenuationColor is what remains after attenuationDistance.
  const glm::vec3 colour(0.1f, 0.5f, 0.9f);
  const glm::vec3 one = reference::volumeAttenuation(1.0f, colour, 1.0f);
  CHECK(one.x == doctest::Approx(0.1f));
  CHECK(one.z == doctest::Approx(0.9f));
  const glm::vec3 two = reference::volumeAttenuation(2.0f, colour, 1.0f);
  CHECK(two.x == doctest::Approx(0.01f));
  CHECK(two.y == doctest::Approx(0.25f));
  CHECK(reference::volumeAttenuation(2.0f, colour, 0.0f) == glm::vec3(1.0f));  // infinite distance
  CHECK(reference::volumeAttenuation(0.0f, colour, 1.0f) == glm::vec3(1.0f));  // thin wall
  // Head-on, the refracted path is the view ray, as long as the thickness
  // times the instance's scale along it.
  const glm::vec3 path =
      reference::volumeTransmissionRay({0, 0, 1}, {0, 0, 1}, 0.5f, 1.5f, glm::vec3(2.0f, 2.0f, 3.0f));
  CHECK(path.x == doctest::Approx(0.0f));
  CHECK(path.z == doctest::Approx(-1.5f));
  // Obliquely, the ray bends toward the normal (Snell: sin 45 deg / 1.5).
  const glm::vec3 view = glm::normalize(glm::vec3(1, 0, 1));
  const glm::vec3 bent = reference::volumeTransmissionRay({0, 0, 1}, view, 1.0f, 1.5f, glm::vec3(1.0f));
  CHECK(-bent.x == doctest::Approx(std::sin(glm::radians(45.0f)) / 1.5f).epsilon(1e-4));
  // The blur: none at ior 1, the roughness itself from 1.5 up.
  CHECK(reference::transmissionRoughness(0.8f, 1.0f) == 0.0f);
  CHECK(reference::transmissionRoughness(0.8f, 1.25f) == doctest::Approx(0.4f));
  CHECK(reference::transmissionRoughness(0.8f, 2.4f) == doctest::Approx(0.8f));
}

}  // namespace headlight

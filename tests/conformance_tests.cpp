// The Khronos conformance models (../shared/gltf-conformance, or
// $HEADLIGHT_SHARED_DIR): each loads, and every glTF feature it uses is
// either rendered or named in Scene::ignored. The features a file uses are
// read here from its JSON, independently of the loader's detectors, so a
// detector that misses one fails the test. A missing folder is a skip.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <glm/gtc/matrix_transform.hpp>
#include <glm/gtc/quaternion.hpp>

#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "support/assets.hpp"

namespace fs = std::filesystem;
using namespace headlight;
using nlohmann::json;

namespace {

fs::path conformanceFolder() { return test::sharedFolder() / "gltf-conformance"; }

bool haveConformance() { return test::exists(conformanceFolder() / "README.md"); }

fs::path modelPath(const std::string& model) { return conformanceFolder() / model / "glTF" / (model + ".gltf"); }

// What Headlight renders of what the test looks for; everything else a
// file uses must be named.
const std::set<std::string> kRendered{"KHR_lights_punctual",   "KHR_materials_emissive_strength",
                                      "EXT_mesh_gpu_instancing", "KHR_mesh_quantization",
                                      "skin",                  "morph targets",
                                      "alphaMode MASK",        "alphaMode BLEND",
                                      "COLOR_0",               "mode POINTS",
                                      "mode LINES",            "mode LINE_LOOP",
                                      "mode LINE_STRIP",       "KHR_texture_transform",
                                      "KHR_materials_unlit",   "TEXCOORD_1",
                                      "KHR_materials_transmission", "KHR_materials_volume",
                                      "KHR_materials_iridescence",
                                      "KHR_materials_ior",     "KHR_materials_specular",
                                      "KHR_materials_clearcoat",

                                      "KHR_materials_sheen",   "KHR_materials_anisotropy"};

bool nonZero(const json& weights) {
  return std::any_of(weights.begin(), weights.end(), [](const json& w) { return w.get<double>() != 0.0; });
}

// Floats of elements [first, first + count) of float accessor `index`, read
// from its .bin in `folder` here (not through the loader). The conformance
// models' animations are plain float accessors; anything else fails.
std::vector<float> readFloatElements(const fs::path& folder, const json& document, int index, std::size_t first,
                                     std::size_t count) {
  static const std::map<std::string, std::size_t> kComponents{{"SCALAR", 1}, {"VEC3", 3}, {"VEC4", 4}, {"MAT4", 16}};
  const json& accessor = document["accessors"][index];
  REQUIRE(accessor["componentType"].get<int>() == 5126);
  REQUIRE(!accessor.contains("sparse"));
  REQUIRE(first + count <= accessor["count"].get<std::size_t>());
  const std::size_t components = kComponents.at(accessor["type"].get<std::string>());
  const json& view = document["bufferViews"][accessor["bufferView"].get<int>()];
  const std::size_t stride = view.value("byteStride", 4 * components);
  std::ifstream file(folder / document["buffers"][view["buffer"].get<int>()]["uri"].get<std::string>(),
                     std::ios::binary);
  std::vector<float> values(count * components);
  for (std::size_t element = 0; element < count; ++element) {
    file.seekg(static_cast<std::streamoff>(view.value("byteOffset", std::size_t(0)) +
                                           accessor.value("byteOffset", std::size_t(0)) + (first + element) * stride));
    file.read(reinterpret_cast<char*>(&values[element * components]), static_cast<std::streamsize>(4 * components));
  }
  REQUIRE(file.good());
  return values;
}

bool sameWithin1e5(const std::vector<float>& a, const std::vector<double>& b, float sign = 1.0f) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const double x = sign * a[i];
    if (std::abs(x - b[i]) > 1e-5 * std::max({1.0, std::abs(x), std::abs(b[i])})) return false;
  }
  return true;
}

// Whether animation `animation` of the model in `folder` starts away from the
// static pose: some channel's first keyframe (a CUBICSPLINE's value) differs
// from the node's value (q and -q being one rotation) or weights.
bool leavesPose(const fs::path& folder, const json& document, const json& animation) {
  for (const json& channel : animation["channels"]) {
    const json& sampler = animation["samplers"][channel["sampler"].get<int>()];
    const json& node = document["nodes"][channel["target"]["node"].get<int>()];
    const std::string path = channel["target"]["path"];
    std::vector<double> pose;
    std::size_t elements = 1;
    if (path == "weights") {
      const json& mesh = document["meshes"][node["mesh"].get<int>()];
      elements = mesh["primitives"][0]["targets"].size();
      pose = node.value("weights", mesh.value("weights", std::vector<double>(elements, 0.0)));
    } else {
      const std::map<std::string, std::vector<double>> kRest{
          {"translation", {0, 0, 0}}, {"rotation", {0, 0, 0, 1}}, {"scale", {1, 1, 1}}};
      REQUIRE(!node.contains("matrix"));
      pose = node.value(path, kRest.at(path));
    }
    const bool cubic = sampler.value("interpolation", "LINEAR") == "CUBICSPLINE";
    const std::vector<float> first =
        readFloatElements(folder, document, sampler["output"].get<int>(), cubic ? elements : 0, elements);
    if (!sameWithin1e5(first, pose) && !(path == "rotation" && sameWithin1e5(first, pose, -1.0f))) return true;
  }
  return false;
}

// The features `document` (in `folder`) uses that the test checks, in the loader's names.
std::set<std::string> usedFeatures(const fs::path& folder, const json& document) {
  static const char* kModes[] = {"POINTS", "LINES", "LINE_LOOP", "LINE_STRIP"};
  std::set<std::string> used;
  for (const json& name : document.value("extensionsUsed", json::array())) used.insert(name.get<std::string>());
  for (const json& material : document.value("materials", json::array())) {
    const std::string alphaMode = material.value("alphaMode", "OPAQUE");
    if (alphaMode != "OPAQUE") used.insert("alphaMode " + alphaMode);
    const json pbr = material.value("pbrMetallicRoughness", json::object());
    for (const json* info : {&pbr, &material}) {
      for (const auto& [key, value] : info->items()) {
        if (key.size() > 7 && key.compare(key.size() - 7, 7, "Texture") == 0 && value.value("texCoord", 0) != 0) {
          used.insert("TEXCOORD_" + std::to_string(value.value("texCoord", 0)));
        }
      }
    }
  }
  const json meshes = document.value("meshes", json::array());
  std::vector<bool> weighted;
  for (const json& mesh : meshes) weighted.push_back(nonZero(mesh.value("weights", json::array())));
  for (const json& node : document.value("nodes", json::array())) {
    if (node.contains("mesh") && nonZero(node.value("weights", json::array()))) weighted[node["mesh"]] = true;
    if (node.contains("skin") && node.contains("mesh")) used.insert("skin");
  }
  for (std::size_t mesh = 0; mesh < meshes.size(); ++mesh) {
    for (const json& primitive : meshes[mesh]["primitives"]) {
      for (const auto& [attribute, accessor] : primitive["attributes"].items()) {
        if (attribute.rfind("COLOR_", 0) == 0) used.insert(attribute);
      }
      const int mode = primitive.value("mode", 4);
      if (mode >= 0 && mode <= 3) used.insert(std::string("mode ") + kModes[mode]);
      if (primitive.contains("targets") && weighted[mesh]) used.insert("morph targets");
    }
  }
  // Animations are not played; one matters to a still frame only where it
  // starts away from the pose.
  for (const json& animation : document.value("animations", json::array())) {
    if (leavesPose(folder, document, animation)) used.insert("animation");
  }
  return used;
}

std::vector<std::string> conformanceModels() {
  std::vector<std::string> models;
  for (const auto& entry : fs::directory_iterator(conformanceFolder())) {
    if (entry.is_directory() && test::exists(modelPath(entry.path().filename().string()))) {
      models.push_back(entry.path().filename().string());
    }
  }
  std::sort(models.begin(), models.end());
  return models;
}

}  // namespace

TEST_CASE("conformance: every model loads and names each feature it uses that is not rendered" *
          doctest::skip(!haveConformance())) {
  const std::vector<std::string> models = conformanceModels();
  CHECK(models.size() >= 28);  // the shared folder's README lists 28
  for (const std::string& model : models) {
    CAPTURE(model);
    Scene scene;
    try {
      scene = loadGltf(modelPath(model));
    } catch (const Error& error) {
      FAIL_CHECK("refused: " << error.what());
      continue;
    }
    CHECK(scene.triangleCount() > 0);
    std::set<std::string> named;
    for (const IgnoredFeature& feature : scene.ignored) {
      named.insert(feature.feature);
      CHECK(feature.count > 0);
      CHECK(!feature.describe().empty());
    }
    std::ifstream file(modelPath(model));
    for (const std::string& feature : usedFeatures(modelPath(model).parent_path(), json::parse(file))) {
      CAPTURE(feature);
      CHECK((kRendered.count(feature) != 0 || named.count(feature) != 0));
    }
  }
}

TEST_CASE("conformance: --strict-gltf refuses a model naming what is not rendered" *
          doctest::skip(!haveConformance())) {
  SceneLoadOptions strict;
  strict.strictGltf = true;
  // SimpleMorph's animation starts away from the static pose (the case below).
  CHECK_THROWS_WITH_AS(loadGltf(modelPath("SimpleMorph"), strict),
                       doctest::Contains("strict-gltf: 1 animation (first: animation 0) is not played"), SceneError);
  CHECK(loadGltf(modelPath("NormalTangentTest"), strict).ignored.empty());
}

TEST_CASE("conformance: MeshPrimitiveModes loads its strip and fan as triangles, its points and lines as lists" *
          doctest::skip(!haveConformance())) {
  const Scene scene = loadGltf(modelPath("MeshPrimitiveModes"));
  std::ifstream file(modelPath("MeshPrimitiveModes"));
  const json document = json::parse(file);
  // Expected triangles from the JSON: TRIANGLES count/3, strips and fans count-2.
  std::size_t expected = 0;
  for (const json& node : document["nodes"]) {
    if (!node.contains("mesh")) continue;
    for (const json& primitive : document["meshes"][node["mesh"].get<int>()]["primitives"]) {
      const int mode = primitive.value("mode", 4);
      const std::size_t count = primitive.contains("indices")
                                    ? document["accessors"][primitive["indices"].get<int>()]["count"].get<std::size_t>()
                                    : document["accessors"][primitive["attributes"]["POSITION"].get<int>()]["count"]
                                          .get<std::size_t>();
      if (mode == 4) expected += count / 3;
      if (mode == 5 || mode == 6) expected += count - 2;
    }
  }
  CHECK(expected > 0);
  CHECK(scene.triangleCount() == expected);
  CHECK(scene.ignored.empty());
  // Every mode is an instance: 7 vertices as 7 points, 12 indices as 6
  // segments, a loop of 7 as 7 segments, a strip of 7 as 6.
  REQUIRE(scene.instances.size() == 7);
  std::map<PrimitiveMode, std::vector<std::size_t>> indexCounts;
  for (const Instance& instance : scene.instances) {
    const Primitive& primitive = scene.primitives[std::size_t(instance.primitive)];
    indexCounts[primitive.mode].push_back(primitive.indices.size());
  }
  CHECK(indexCounts[PrimitiveMode::Points] == std::vector<std::size_t>{7});
  CHECK(indexCounts[PrimitiveMode::Lines] == std::vector<std::size_t>{12, 14, 12});
  CHECK(indexCounts[PrimitiveMode::Triangles].size() == 3);
}

namespace {

json readJson(const fs::path& path) {
  std::ifstream file(path);
  return json::parse(file);
}

// Accessor `index` of a float VEC3 accessor of the model, read from its .bin
// here (not through the loader).
std::vector<glm::vec3> readVec3(const std::string& model, const json& document, int index) {
  const json& accessor = document["accessors"][index];
  const json& view = document["bufferViews"][accessor["bufferView"].get<int>()];
  const json& buffer = document["buffers"][view["buffer"].get<int>()];
  std::ifstream file(modelPath(model).parent_path() / buffer["uri"].get<std::string>(), std::ios::binary);
  file.seekg(view.value("byteOffset", 0) + accessor.value("byteOffset", 0));
  std::vector<glm::vec3> values(accessor["count"].get<std::size_t>());
  file.read(reinterpret_cast<char*>(values.data()), static_cast<std::streamsize>(values.size() * sizeof(glm::vec3)));
  REQUIRE(file.good());
  return values;
}

}  // namespace

TEST_CASE("conformance: SimpleInstancing places 125 instances" * doctest::skip(!haveConformance())) {
  const Scene scene = loadGltf(modelPath("SimpleInstancing"));
  CHECK(scene.instances.size() == 125);
  CHECK(scene.primitives.size() == 1);
  CHECK(scene.ignored.empty());
  // TRANSLATION spans 0..10 and SCALE 1..2 on a 0..1 cube: the world bounds reach past 10.
  CHECK(scene.worldBounds().max.x > 10.0f);
  ResourceLimits limits;
  limits.maxInstances = 124;
  CHECK_THROWS_AS(loadGltf(modelPath("SimpleInstancing"), {}, limits), LimitError);
}

TEST_CASE("conformance: SimpleMorph's vertices move by its weighted targets" * doctest::skip(!haveConformance())) {
  const json document = readJson(modelPath("SimpleMorph"));
  const json& primitive = document["meshes"][0]["primitives"][0];
  std::vector<glm::vec3> expected = readVec3("SimpleMorph", document, primitive["attributes"]["POSITION"]);
  const json& weights = document["meshes"][0]["weights"];
  for (std::size_t target = 0; target < primitive["targets"].size(); ++target) {
    const std::vector<glm::vec3> deltas = readVec3("SimpleMorph", document, primitive["targets"][target]["POSITION"]);
    for (std::size_t v = 0; v < expected.size(); ++v) expected[v] += weights[target].get<float>() * deltas[v];
  }
  const Scene scene = loadGltf(modelPath("SimpleMorph"));
  REQUIRE(scene.primitives.size() == 1);
  const std::vector<glm::vec3>& positions = scene.primitives[0].positions;
  REQUIRE(positions.size() == expected.size());
  bool moved = false;
  const std::vector<glm::vec3> base = readVec3("SimpleMorph", document, primitive["attributes"]["POSITION"]);
  for (std::size_t v = 0; v < positions.size(); ++v) {
    CAPTURE(v);
    CHECK(glm::length(positions[v] - expected[v]) < 1e-6f);
    moved = moved || glm::length(positions[v] - base[v]) > 0.1f;
  }
  CHECK(moved);  // the weights (0.5, 0.5) move it
  std::set<std::string> named;
  for (const IgnoredFeature& feature : scene.ignored) named.insert(feature.feature);
  CHECK(named == std::set<std::string>{"animation"});  // its weights animation is not played
}

TEST_CASE("conformance: only SimpleMorph's animation starts away from the pose, and only it is named" *
          doctest::skip(!haveConformance())) {
  // SimpleMorph's weights start at 0 0 against the mesh's 0.5 0.5;
  // SimpleSkin's rotation and RecursiveSkeletons' 840 rotations start at
  // their nodes' rotations (the generic case above reads that from the files).
  const std::map<std::string, std::string> kExpected{
      {"SimpleMorph",
       "1 animation (first: animation 0) is not played (the static pose is drawn; --animation N|NAME --time SECONDS "
       "poses the file by one)"},
      {"SimpleSkin", ""},
      {"RecursiveSkeletons", ""}};
  for (const auto& [model, expected] : kExpected) {
    CAPTURE(model);
    std::string named;
    for (const IgnoredFeature& feature : loadGltf(modelPath(model)).ignored) {
      if (feature.feature == "animation") named = feature.describe();
    }
    CHECK(named == expected);
    const json document = readJson(modelPath(model));
    CHECK(leavesPose(modelPath(model).parent_path(), document, document["animations"][0]) == !expected.empty());
  }
}

TEST_CASE("conformance: SimpleSkin and RecursiveSkeletons are posed by their joints" *
          doctest::skip(!haveConformance())) {
  // SimpleSkin's joints rest where it was bound: posing with the nodes'
  // transforms and the inverse bind matrices gives back the accessor's
  // bounds (ignoring the inverse bind matrices would lift the top by 1).
  const json document = readJson(modelPath("SimpleSkin"));
  const json& position = document["accessors"][document["meshes"][0]["primitives"][0]["attributes"]["POSITION"].get<int>()];
  const Scene simple = loadGltf(modelPath("SimpleSkin"));
  REQUIRE(simple.instances.size() == 1);
  CHECK(simple.instances[0].worldFromLocal == glm::mat4(1.0f));
  const Bounds bounds = simple.worldBounds();
  for (int axis = 0; axis < 3; ++axis) {
    CHECK(bounds.min[axis] == doctest::Approx(position["min"][axis].get<float>()).epsilon(1e-5));
    CHECK(bounds.max[axis] == doctest::Approx(position["max"][axis].get<float>()).epsilon(1e-5));
  }
  const Scene recursive = loadGltf(modelPath("RecursiveSkeletons"));
  CHECK(!recursive.worldBounds().empty());
  CHECK(std::isfinite(recursive.worldBounds().radius()));
  for (const IgnoredFeature& feature : recursive.ignored) CHECK(feature.feature != "skin");
}

TEST_CASE("conformance: generated tangents match the MikkTSpace tangents NormalTangentMirrorTest ships" *
          doctest::skip(!haveConformance())) {
  const Scene scene = loadGltf(modelPath("NormalTangentMirrorTest"));
  std::size_t compared = 0, close = 0, sameSign = 0;
  for (const Primitive& shipped : scene.primitives) {
    REQUIRE(!shipped.tangents.empty());
    Primitive generated = shipped;
    generated.tangents.clear();
    generateTangents(generated);
    // Compare per corner (a split vertex is a new index).
    for (std::size_t corner = 0; corner < shipped.indices.size(); ++corner) {
      const glm::vec4& expected = shipped.tangents[shipped.indices[corner]];
      const glm::vec4& actual = generated.tangents[generated.indices[corner]];
      ++compared;
      sameSign += expected.w == actual.w;
      // 0.99: within about 8 degrees (Blender welds and weights a little differently).
      close += glm::dot(glm::normalize(glm::vec3(expected)), glm::vec3(actual)) > 0.99f;
    }
  }
  CAPTURE(compared);
  CAPTURE(close);
  CAPTURE(sameSign);
  CHECK(compared > 1000);
  CHECK(sameSign >= compared * 99 / 100);
  CHECK(close >= compared * 95 / 100);
}

// ---- Animations played at a chosen time (issue 34, item 4) -------------------

namespace {

// A LINEAR sampler's output at `time`, read from the file here: the two
// keyframes around it (the first / last outside), `width` floats each,
// mixed by `mix(a, b, s)`.
std::vector<float> sampleLinear(
    const std::string& model, const json& document, const json& sampler, float time, std::size_t width,
    const std::function<std::vector<float>(const std::vector<float>&, const std::vector<float>&, float)>& mix) {
  const fs::path folder = modelPath(model).parent_path();
  const int input = sampler["input"].get<int>(), output = sampler["output"].get<int>();
  const std::size_t count = document["accessors"][input]["count"].get<std::size_t>();
  const std::vector<float> times = readFloatElements(folder, document, input, 0, count);
  const std::size_t elements = width / (document["accessors"][output]["type"] == "VEC4" ? 4 : 1);
  auto value = [&](std::size_t k) { return readFloatElements(folder, document, output, k * elements, elements); };
  if (time <= times.front()) return value(0);
  if (time >= times.back()) return value(count - 1);
  std::size_t k = 0;
  while (times[k + 1] <= time) ++k;
  return mix(value(k), value(k + 1), (time - times[k]) / (times[k + 1] - times[k]));
}

SceneLoadOptions atTime(float time) {
  SceneLoadOptions options;
  options.animation = "0";
  options.animationTime = time;
  return options;
}

}  // namespace

TEST_CASE("conformance: SimpleMorph played at 1.5 s has the weights its keyframes give then" *
          doctest::skip(!haveConformance())) {
  const json document = readJson(modelPath("SimpleMorph"));
  const json& primitive = document["meshes"][0]["primitives"][0];
  const std::vector<float> weights =
      sampleLinear("SimpleMorph", document, document["animations"][0]["samplers"][0], 1.5f, 2,
                   [](const std::vector<float>& a, const std::vector<float>& b, float s) {
                     return std::vector<float>{a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])};
                   });
  std::vector<glm::vec3> expected = readVec3("SimpleMorph", document, primitive["attributes"]["POSITION"]);
  for (std::size_t target = 0; target < 2; ++target) {
    const std::vector<glm::vec3> deltas = readVec3("SimpleMorph", document, primitive["targets"][target]["POSITION"]);
    for (std::size_t v = 0; v < expected.size(); ++v) expected[v] += weights[target] * deltas[v];
  }
  const Scene scene = loadGltf(modelPath("SimpleMorph"), atTime(1.5f));
  const std::vector<glm::vec3>& positions = scene.primitives.at(0).positions;
  REQUIRE(positions.size() == expected.size());
  for (std::size_t v = 0; v < positions.size(); ++v) {
    CAPTURE(v);
    CHECK(glm::length(positions[v] - expected[v]) < 1e-5f);
  }
  CHECK(weights != std::vector<float>{0.5f, 0.5f});  // not the static pose's
  CHECK(scene.ignored.empty());                      // the animation is played, so not named
}

TEST_CASE("conformance: SimpleSkin played at 1.25 s bends by its joint's rotation then" *
          doctest::skip(!haveConformance())) {
  const json document = readJson(modelPath("SimpleSkin"));
  const fs::path folder = modelPath("SimpleSkin").parent_path();
  // Joint 1 (node 2, under node 1 at the origin) sits at y = 1 and turns by
  // the animated rotation; joint 0 (node 1) stays. v' = sum_j w_j world_j IBM_j v.
  const std::vector<float> q = sampleLinear("SimpleSkin", document, document["animations"][0]["samplers"][0], 1.25f, 4,
                                            [](const std::vector<float>& a, const std::vector<float>& b, float s) {
                                              glm::quat qa(a[3], a[0], a[1], a[2]), qb(b[3], b[0], b[1], b[2]);
                                              if (glm::dot(qa, qb) < 0.0f) qb = -qb;
                                              const glm::quat r = glm::normalize(glm::slerp(qa, qb, s));
                                              return std::vector<float>{r.x, r.y, r.z, r.w};
                                            });
  const glm::mat4 world[2] = {glm::mat4(1.0f), glm::translate(glm::mat4(1.0f), {0.0f, 1.0f, 0.0f}) *
                                                   glm::mat4_cast(glm::quat(q[3], q[0], q[1], q[2]))};
  const json& attributes = document["meshes"][0]["primitives"][0]["attributes"];
  const std::vector<glm::vec3> bind = readVec3("SimpleSkin", document, attributes["POSITION"]);
  const std::vector<float> weights = readFloatElements(folder, document, attributes["WEIGHTS_0"], 0, bind.size());
  const std::vector<float> inverseBind =
      readFloatElements(folder, document, document["skins"][0]["inverseBindMatrices"], 0, 2);
  // JOINTS_0: unsigned shorts, four a vertex, at the view's stride.
  const json& jointsAccessor = document["accessors"][attributes["JOINTS_0"].get<int>()];
  REQUIRE(jointsAccessor["componentType"].get<int>() == 5123);
  const json& view = document["bufferViews"][jointsAccessor["bufferView"].get<int>()];
  std::ifstream file(folder / document["buffers"][view["buffer"].get<int>()]["uri"].get<std::string>(),
                     std::ios::binary);
  std::vector<std::uint16_t> joints(bind.size() * 4);
  for (std::size_t v = 0; v < bind.size(); ++v) {
    file.seekg(static_cast<std::streamoff>(view.value("byteOffset", std::size_t(0)) +
                                           jointsAccessor.value("byteOffset", std::size_t(0)) +
                                           v * view.value("byteStride", std::size_t(8))));
    file.read(reinterpret_cast<char*>(&joints[v * 4]), 8);
  }
  REQUIRE(file.good());
  const Scene scene = loadGltf(modelPath("SimpleSkin"), atTime(1.25f));
  const std::vector<glm::vec3>& positions = scene.primitives.at(0).positions;
  REQUIRE(positions.size() == bind.size());
  bool bent = false;
  for (std::size_t v = 0; v < bind.size(); ++v) {
    glm::vec4 expected(0.0f);
    for (int k = 0; k < 4; ++k) {
      const std::uint16_t j = joints[v * 4 + std::size_t(k)];
      REQUIRE(j < 2);
      glm::mat4 ibm;
      for (int e = 0; e < 16; ++e) ibm[e / 4][e % 4] = inverseBind[std::size_t(j) * 16 + std::size_t(e)];
      expected += weights[v * 4 + std::size_t(k)] * (world[j] * ibm * glm::vec4(bind[v], 1.0f));
    }
    CAPTURE(v);
    CHECK(glm::length(positions[v] - glm::vec3(expected)) < 1e-5f);
    bent = bent || glm::length(positions[v] - bind[v]) > 0.05f;
  }
  CHECK(bent);
}

TEST_CASE("conformance: RecursiveSkeletons played at 0 s is its static pose, at 1 s another" *
          doctest::skip(!haveConformance())) {
  const Scene still = loadGltf(modelPath("RecursiveSkeletons"));
  const Scene start = loadGltf(modelPath("RecursiveSkeletons"), atTime(0.0f));
  const Scene moved = loadGltf(modelPath("RecursiveSkeletons"), atTime(1.0f));
  REQUIRE(start.primitives.size() == still.primitives.size());
  REQUIRE(moved.primitives.size() == still.primitives.size());
  float startDifference = 0.0f, movedDifference = 0.0f;
  for (std::size_t p = 0; p < still.primitives.size(); ++p)
    for (std::size_t v = 0; v < still.primitives[p].positions.size(); ++v) {
      startDifference =
          std::max(startDifference, glm::length(start.primitives[p].positions[v] - still.primitives[p].positions[v]));
      movedDifference =
          std::max(movedDifference, glm::length(moved.primitives[p].positions[v] - still.primitives[p].positions[v]));
    }
  CHECK(startDifference < 1e-4f);  // its 840 rotations start at the nodes' own
  CHECK(movedDifference > 0.01f);
}

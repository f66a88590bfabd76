// Animations are not played (issue 17): one is named only when its first
// keyframe leaves the static pose the nodes describe. One-triangle files
// made here, with the animation's keyframes in a second buffer.
#include <doctest/doctest.h>

#include <chrono>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include "gltf_test_files.hpp"
#include "headlight/scene_loader.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using namespace headlight;
using namespace headlight::test;

namespace {

template <typename T>
void append(std::vector<unsigned char>& bytes, std::initializer_list<T> values) {
  for (const T value : values) {
    const auto at = bytes.size();
    bytes.resize(at + sizeof(T));
    std::memcpy(bytes.data() + at, &value, sizeof(T));
  }
}

// The triangle (buffer 0, accessors 0 and 1) with node 0 animated from
// anim.bin (buffer 1, bufferView 2). Keyframe times are accessor 2: floats
// 0 and 1 at byte 0.
struct AnimatedTriangle {
  std::string node = R"("mesh":0)";  // node 0's members
  std::string mesh;                  // more members of mesh 0 ("weights")
  std::string primitive;             // more members of its primitive ("targets")
  std::vector<unsigned char> data;   // anim.bin after the two times
  std::string accessors;             // accessor 3 onward, each starting with a comma
  std::string animations;            // the animations array

  fs::path write(const TempFolder& folder) const {
    std::vector<unsigned char> bytes;
    append<float>(bytes, {0.0f, 1.0f});
    bytes.insert(bytes.end(), data.begin(), data.end());
    folder.write("triangle.bin", triangleBuffer());
    folder.write("anim.bin", bytes);
    return folder.write(
        "scene.gltf",
        R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{)" + node +
            R"(}],"meshes":[{"primitives":[{"attributes":{"POSITION":0},"indices":1)" + primitive + "}]" + mesh +
            R"(}],"buffers":[{"uri":"triangle.bin","byteLength":44},{"uri":"anim.bin","byteLength":)" +
            std::to_string(bytes.size()) +
            R"(}],"bufferViews":[{"buffer":0,"byteOffset":0,"byteLength":36},
              {"buffer":0,"byteOffset":36,"byteLength":6},{"buffer":1,"byteLength":)" +
            std::to_string(bytes.size()) +
            R"(}],"accessors":[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3"},
              {"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"},
              {"bufferView":2,"componentType":5126,"count":2,"type":"SCALAR"})" +
            accessors + R"(],"animations":)" + animations + "}");
  }
};

// An accessor on anim.bin: `count` elements of `type` from `byteOffset`
// (the times take bytes 0..8).
std::string accessor(std::size_t byteOffset, std::size_t count, const char* type, int componentType = 5126,
                     bool normalized = false) {
  return R"(,{"bufferView":2,"byteOffset":)" + std::to_string(byteOffset) + R"(,"componentType":)" +
         std::to_string(componentType) + (normalized ? R"(,"normalized":true)" : "") + R"(,"count":)" +
         std::to_string(count) + R"(,"type":")" + type + R"("})";
}

// One channel on node 0's `path`, sampled from times accessor 2 and `output`.
std::string animation(const std::string& name, const std::string& path, int output,
                      const std::string& interpolation = "LINEAR") {
  return R"({"name":")" + name + R"(","channels":[{"sampler":0,"target":{"node":0,"path":")" + path +
         R"("}}],"samplers":[{"input":2,"output":)" + std::to_string(output) + R"(,"interpolation":")" + interpolation +
         R"("}]})";
}

// What the file says of its animations: "" when none is named.
std::string namedAnimations(const fs::path& path) {
  const Scene scene = loadGltf(path);
  CHECK(scene.triangleCount() == 1);
  for (const IgnoredFeature& feature : scene.ignored) {
    if (feature.feature == "animation") return feature.describe();
  }
  return "";
}

const std::string kNamedZero =
    "1 animation (first: animation 0 'A') is not played (the static pose is drawn; --animation N|NAME --time SECONDS "
    "poses the file by one)";

// A translation animation of node 0 (translation 1 2 3) whose first two
// keyframes are `first` and 4 5 6.
std::string translationStartingAt(float x, float y, float z) {
  AnimatedTriangle file;
  file.node = R"("mesh":0,"translation":[1,2,3])";
  append<float>(file.data, {x, y, z, 4.0f, 5.0f, 6.0f});
  file.accessors = accessor(8, 2, "VEC3");
  file.animations = "[" + animation("A", "translation", 3) + "]";
  TempFolder folder;
  return namedAnimations(file.write(folder));
}

}  // namespace

TEST_CASE("glTF animation: a first keyframe at the node's translation is not named; one away from it is") {
  CHECK(translationStartingAt(1.0f, 2.0f, 3.0f).empty());
  CHECK(translationStartingAt(1.0f, 2.0f, 3.5f) == kNamedZero);
  // The tolerance: 1e-5 of the magnitude, at least 1e-5.
  CHECK(translationStartingAt(1.0f, 2.00001f, 3.0f).empty());
  CHECK(translationStartingAt(1.0f, 2.0f, 3.0001f) == kNamedZero);
}

TEST_CASE("glTF animation: only the animations that leave the pose are counted") {
  AnimatedTriangle file;
  file.node = R"("mesh":0,"translation":[1,2,3])";
  append<float>(file.data, {1, 2, 3, 4, 5, 6, /* accessor 4: */ 1, 2, 4, 4, 5, 6, /* accessor 5: */ 0, 0, 0, 0, 0, 0});
  file.accessors = accessor(8, 2, "VEC3") + accessor(32, 2, "VEC3") + accessor(56, 2, "VEC3");
  file.animations = "[" + animation("Still", "translation", 3) + "," + animation("Moves", "translation", 4) + "," +
                    animation("Shrinks", "scale", 5) + "]";
  TempFolder folder;
  CHECK(namedAnimations(file.write(folder)) ==
        "2 animations (first: animation 1 'Moves') are not played (the static pose is drawn; --animation N|NAME "
        "--time SECONDS poses the file by one)");
}

TEST_CASE("glTF animation: rotations compare as rotations (q and -q are one), quantized ones within half a step") {
  const auto rotationNamed = [](const std::string& nodeRotation, std::vector<unsigned char> keyframes,
                                const std::string& output) {
    AnimatedTriangle file;
    file.node = R"("mesh":0)" + nodeRotation;
    file.data = std::move(keyframes);
    file.accessors = output;
    file.animations = "[" + animation("A", "rotation", 3) + "]";
    TempFolder folder;
    return namedAnimations(file.write(folder));
  };
  std::vector<unsigned char> negated, other, negatedIdentity, shorts;
  append<float>(negated, {-0.0f, -0.6f, -0.0f, -0.8f, 0, 0, 0, 1});
  append<float>(other, {0.6f, 0.0f, 0.0f, 0.8f, 0, 0, 0, 1});
  append<float>(negatedIdentity, {0, 0, 0, -1, 0, 0, 0, 1});
  // 0.6 and 0.8 as normalized shorts: 19660 / 32767 is 1.2e-5 from 0.6, within half a step (1.5e-5).
  append<std::int16_t>(shorts, {0, 19660, 0, 26214, 0, 0, 0, 32767});
  const std::string node = R"(,"rotation":[0,0.6,0,0.8])";
  CHECK(rotationNamed(node, negated, accessor(8, 2, "VEC4")).empty());
  CHECK(rotationNamed(node, other, accessor(8, 2, "VEC4")) == kNamedZero);
  CHECK(rotationNamed("", negatedIdentity, accessor(8, 2, "VEC4")).empty());  // the default rotation, negated
  CHECK(rotationNamed(node, shorts, accessor(8, 2, "VEC4", 5122, true)).empty());
}

TEST_CASE("glTF animation: weights compare with the node's, else the mesh's, else zeros") {
  const auto weightsNamed = [](const std::string& node, const std::string& mesh, std::initializer_list<float> keys,
                               std::size_t count = 4) {
    AnimatedTriangle file;
    file.node = R"("mesh":0)" + node;
    file.mesh = mesh;
    file.primitive = R"(,"targets":[{"POSITION":0},{"POSITION":0}])";
    append<float>(file.data, keys);
    file.accessors = accessor(8, count, "SCALAR");
    file.animations = "[" + animation("A", "weights", 3) + "]";
    TempFolder folder;
    return namedAnimations(file.write(folder));
  };
  const std::string meshWeights = R"(,"weights":[0.25,0.75])";
  CHECK(weightsNamed("", meshWeights, {0.25f, 0.75f, 1, 0}).empty());
  CHECK(weightsNamed("", meshWeights, {0.75f, 0.25f, 1, 0}) == kNamedZero);
  CHECK(weightsNamed(R"(,"weights":[1,0])", meshWeights, {0.25f, 0.75f, 1, 0}) == kNamedZero);  // the node's win
  CHECK(weightsNamed(R"(,"weights":[1,0])", meshWeights, {1, 0, 0, 0}).empty());
  CHECK(weightsNamed("", "", {0, 0, 1, 1}).empty());
  CHECK(weightsNamed("", "", {0, 0.5f, 1, 1}) == kNamedZero);
  // 3 outputs for 2 times of 2 targets: malformed, named.
  CHECK(weightsNamed("", "", {0, 0, 1}, 3) == kNamedZero);
}

TEST_CASE("glTF animation: a CUBICSPLINE keyframe's value is compared, not its in-tangent") {
  const auto cubicNamed = [](std::initializer_list<float> keys) {
    AnimatedTriangle file;
    file.node = R"("mesh":0,"translation":[1,2,3])";
    append<float>(file.data, keys);
    file.accessors = accessor(8, 6, "VEC3");
    file.animations = "[" + animation("A", "translation", 3, "CUBICSPLINE") + "]";
    TempFolder folder;
    return namedAnimations(file.write(folder));
  };
  CHECK(cubicNamed({9, 9, 9, 1, 2, 3, 9, 9, 9, 0, 0, 0, 4, 5, 6, 0, 0, 0}).empty());
  CHECK(cubicNamed({1, 2, 3, 7, 7, 7, 1, 2, 3, 0, 0, 0, 4, 5, 6, 0, 0, 0}) == kNamedZero);
}

TEST_CASE("glTF animation: a malformed animation loads, named as not played") {
  // The animation is never read for drawing: the file draws its static pose,
  // and the animation is named rather than the file refused.
  const float nan = std::numeric_limits<float>::quiet_NaN();
  struct Case {
    const char* what;
    std::string node, accessors, animations;
    std::vector<float> keys;
  };
  const std::string translation = "[" + animation("A", "translation", 3) + "]";
  const std::vector<float> pose{0, 0, 0, 0, 0, 0};
  const Case cases[]{
      {"output past its bufferView", "", accessor(16, 2, "VEC3"), translation, pose},
      {"output of the wrong type", "", accessor(8, 2, "VEC4"), translation, pose},
      {"output not a multiple of the times", "", accessor(8, 1, "VEC3"), translation, pose},
      {"a non-finite keyframe", "", accessor(8, 2, "VEC3"), translation, {nan, 0, 0, 0, 0, 0}},
      {"output accessor out of range", "", "", translation, pose},
      {"sampler out of range", "", accessor(8, 2, "VEC3"),
       R"([{"name":"A","channels":[{"sampler":4,"target":{"node":0,"path":"translation"}}],"samplers":[]}])", pose},
      {"target node out of range", "", accessor(8, 2, "VEC3"),
       R"([{"name":"A","channels":[{"sampler":0,"target":{"node":7,"path":"translation"}}],
            "samplers":[{"input":2,"output":3}]}])",
       pose},
      {"no channels", "", accessor(8, 2, "VEC3"), R"([{"name":"A","channels":[],"samplers":[]}])", pose},
      {"a node with a matrix", R"(,"matrix":[1,0,0,0,0,1,0,0,0,0,1,0,0,0,0,1])", accessor(8, 2, "VEC3"), translation,
       pose},
  };
  for (const Case& c : cases) {
    CAPTURE(c.what);
    AnimatedTriangle file;
    file.node = R"("mesh":0)" + c.node;
    for (const float key : c.keys) append<float>(file.data, {key});
    file.accessors = c.accessors;
    file.animations = c.animations;
    TempFolder folder;
    CHECK(namedAnimations(file.write(folder)) == kNamedZero);
  }
}

TEST_CASE("glTF animation: a sparse output of a huge count is read at its first keyframe only") {
  // Times and output have no bufferView (zeros) and claim 4 * 10^9 elements;
  // one sparse value at element 0 says where the animation starts. Reading
  // either whole would need 48 GB.
  const auto sparseNamed = [](float x) {
    AnimatedTriangle file;
    file.node = R"("mesh":0,"translation":[1,2,3])";
    append<std::uint32_t>(file.data, {0});
    append<float>(file.data, {x, 2, 3});
    file.accessors = R"(,{"componentType":5126,"count":4000000000,"type":"SCALAR"},
      {"componentType":5126,"count":4000000000,"type":"VEC3","sparse":{"count":1,
        "indices":{"bufferView":2,"byteOffset":8,"componentType":5125},"values":{"bufferView":2,"byteOffset":12}}})";
    file.animations =
        R"([{"name":"A","channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}],
             "samplers":[{"input":3,"output":4}]}])";
    TempFolder folder;
    return namedAnimations(file.write(folder));
  };
  const auto start = std::chrono::steady_clock::now();
  CHECK(sparseNamed(1.0f).empty());
  CHECK(sparseNamed(5.0f) == kNamedZero);
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));
}

// ---- Playing an animation at a chosen time (issue 34, item 4) ----------------

namespace {

// The triangle's file with one animation "A" of `path` from `keys` (output
// accessor 3 of `count` elements of `type`), loaded posed at `time`.
Scene posedTriangle(const std::string& path, std::initializer_list<float> keys, std::size_t count, const char* type,
                    float time, const std::string& interpolation = "LINEAR", const std::string& node = "",
                    const std::string& primitive = "") {
  AnimatedTriangle file;
  file.node = R"("mesh":0)" + node;
  file.primitive = primitive;
  append<float>(file.data, keys);
  file.accessors = accessor(8, count, type);
  file.animations = "[" + animation("A", path, 3, interpolation) + "]";
  TempFolder folder;
  SceneLoadOptions options;
  options.animation = "A";
  options.animationTime = time;
  return loadGltf(file.write(folder), options);
}

glm::vec3 translationOf(const Scene& scene) { return glm::vec3(scene.instances.at(0).worldFromLocal[3]); }

}  // namespace

TEST_CASE("glTF animation played: LINEAR and STEP translations at, between, before and after the keyframes") {
  // Times 0 and 1; translation (0, 0, 0) -> (4, 8, 12).
  const std::initializer_list<float> keys{0, 0, 0, 4, 8, 12};
  CHECK(near(translationOf(posedTriangle("translation", keys, 2, "VEC3", 0.25f)), {1, 2, 3}));
  CHECK(near(translationOf(posedTriangle("translation", keys, 2, "VEC3", 1.0f)), {4, 8, 12}));
  CHECK(near(translationOf(posedTriangle("translation", keys, 2, "VEC3", -3.0f)), {0, 0, 0}));    // the first holds
  CHECK(near(translationOf(posedTriangle("translation", keys, 2, "VEC3", 100.0f)), {4, 8, 12}));  // the last holds
  CHECK(near(translationOf(posedTriangle("translation", keys, 2, "VEC3", 0.75f, "STEP")), {0, 0, 0}));
  CHECK(near(translationOf(posedTriangle("translation", keys, 2, "VEC3", 1.0f, "STEP")), {4, 8, 12}));
  // The played animation is not named as not played.
  const Scene scene = posedTriangle("translation", keys, 2, "VEC3", 0.5f);
  CHECK(std::none_of(scene.ignored.begin(), scene.ignored.end(),
                     [](const IgnoredFeature& f) { return f.feature == "animation"; }));
  REQUIRE(scene.animations.size() == 1);
  CHECK(scene.animations[0].name == "A");
}

TEST_CASE("glTF animation played: CUBICSPLINE is the Hermite spline of the tangents scaled by the interval") {
  // (in-tangent, value, out-tangent) per keyframe. Value 0 -> 1 with both
  // tangents 1 (the interval is 1) is the straight line: x(s) = s.
  const float line = translationOf(posedTriangle("translation", {0, 0, 0, 0, 0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 0, 0, 0},
                                                 6, "VEC3", 0.25f, "CUBICSPLINE"))
                         .x;
  CHECK(line == doctest::Approx(0.25f).epsilon(1e-6));
  // Zero tangents: smoothstep, 3 s^2 - 2 s^3 = 0.15625 at s = 0.25.
  const float eased = translationOf(posedTriangle("translation", {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0, 0},
                                                  6, "VEC3", 0.25f, "CUBICSPLINE"))
                          .x;
  CHECK(eased == doctest::Approx(0.15625f).epsilon(1e-6));
  // At a keyframe, its value (the middle of the three).
  CHECK(near(translationOf(posedTriangle("translation", {9, 9, 9, 1, 2, 3, 9, 9, 9, 9, 9, 9, 4, 5, 6, 9, 9, 9}, 6,
                                         "VEC3", 0.0f, "CUBICSPLINE")),
             {1, 2, 3}));
}

TEST_CASE("glTF animation played: rotations slerp the short way round") {
  // Identity -> 90 degrees about +Y, halfway: 45 degrees. The second
  // keyframe negated is the same rotation and must give the same pose.
  const float s = std::sqrt(0.5f);
  for (const float sign : {1.0f, -1.0f}) {
    const Scene scene = posedTriangle("rotation", {0, 0, 0, 1, 0, sign * s, 0, sign * s}, 2, "VEC4", 0.5f);
    const glm::mat4& m = scene.instances.at(0).worldFromLocal;
    CAPTURE(sign);
    // The local +X axis turned 45 degrees about +Y: (cos 45, 0, -sin 45).
    CHECK(near(glm::vec3(m[0]), {s, 0.0f, -s}, 1e-5f));
  }
}

TEST_CASE("glTF animation played: morph weights pose the mesh") {
  // Two targets whose POSITION deltas are the positions themselves
  // (accessor 0): weights (0, 0) -> (1, 0.5); at t = 0.5, (0.5, 0.25), so
  // every vertex is scaled by 1.75.
  const Scene still = posedTriangle("weights", {0, 0, 1, 0.5f}, 4, "SCALAR", 0.0f, "LINEAR", "",
                                    R"(,"targets":[{"POSITION":0},{"POSITION":0}])");
  const Scene posed = posedTriangle("weights", {0, 0, 1, 0.5f}, 4, "SCALAR", 0.5f, "LINEAR", "",
                                    R"(,"targets":[{"POSITION":0},{"POSITION":0}])");
  const auto& before = still.primitives.at(0).positions;
  const auto& after = posed.primitives.at(0).positions;
  REQUIRE(before.size() == after.size());
  for (std::size_t i = 0; i < before.size(); ++i) CHECK(near(after[i], before[i] * 1.75f));
}

TEST_CASE(
    "glTF animation played: a name or index the file lacks, a time without animations, and bad keyframes "
    "are refused naming them") {
  AnimatedTriangle file;
  file.node = R"("mesh":0)";
  append<float>(file.data, {0, 0, 0, 4, 8, 12});
  file.accessors = accessor(8, 2, "VEC3");
  file.animations = "[" + animation("Walk", "translation", 3) + "]";
  TempFolder folder;
  const fs::path path = file.write(folder);
  SceneLoadOptions options;
  options.animation = "Run";
  CHECK(loadError(path, options).find("animation 'Run' is not in the file: its animations are 0 'Walk'") !=
        std::string::npos);
  options.animation = "1";
  CHECK(loadError(path, options).find("animation '1' is not in the file") != std::string::npos);
  options.animation = "0";
  CHECK(loadError(path, options).empty());
  // A time alone plays animation 0.
  options.animation.clear();
  options.animationTime = 0.5f;
  CHECK(near(translationOf(loadGltf(path, options)), {2, 4, 6}));
  // Keyframe times 1 and 1 (glTF wants them increasing): up to the first
  // the first holds, after the last the last; no time falls between them.
  std::vector<unsigned char> bytes;
  append<float>(bytes, {1.0f, 1.0f, 0, 0, 0, 4, 8, 12});
  folder.write("anim.bin", bytes);
  options.animationTime = 1.0f;
  CHECK(near(translationOf(loadGltf(path, options)), {0, 0, 0}));
  options.animationTime = 1.5f;
  CHECK(near(translationOf(loadGltf(path, options)), {4, 8, 12}));
  // A NaN time is refused by the setting's row (a finite number); here,
  // times that are not finite are named.
  bytes.clear();
  append<float>(bytes, {0.0f, std::numeric_limits<float>::infinity(), 0, 0, 0, 4, 8, 12});
  folder.write("anim.bin", bytes);
  options.animationTime = 0.5f;
  CHECK(loadError(path, options).find("animation 0 'Walk' channel 0: keyframe time 1 is not finite") !=
        std::string::npos);
  SceneLoadOptions none;
  none.animationTime = 1.0f;
  TempFolder plain;
  CHECK(loadError(writeTriangleGltf(plain), none).find("time: the file has no animations") != std::string::npos);
}

TEST_CASE("glTF animation played: keyframes of a huge sparse count are found by a bounded search") {
  // Times and output have no bufferView and claim 4 * 10^9 elements: times
  // all 0 but the last (10 s), output all 0 but the last (8, 0, 0). At 5 s
  // the search narrows to the last interval in ~32 reads of one element,
  // halfway along it: (4, 0, 0). Reading either accessor whole would need 16-48 GB.
  AnimatedTriangle file;
  file.node = R"("mesh":0)";
  append<std::uint32_t>(file.data, {3999999999u});
  append<float>(file.data, {10.0f});
  append<std::uint32_t>(file.data, {3999999999u});
  append<float>(file.data, {8.0f, 0.0f, 0.0f});
  file.accessors = R"(,{"componentType":5126,"count":4000000000,"type":"SCALAR","sparse":{"count":1,
      "indices":{"bufferView":2,"byteOffset":8,"componentType":5125},"values":{"bufferView":2,"byteOffset":12}}},
    {"componentType":5126,"count":4000000000,"type":"VEC3","sparse":{"count":1,
      "indices":{"bufferView":2,"byteOffset":16,"componentType":5125},"values":{"bufferView":2,"byteOffset":20}}})";
  file.animations = R"([{"name":"A","channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}],
                         "samplers":[{"input":3,"output":4}]}])";
  TempFolder folder;
  SceneLoadOptions options;
  options.animation = "A";
  options.animationTime = 5.0f;
  const auto start = std::chrono::steady_clock::now();
  CHECK(near(translationOf(loadGltf(file.write(folder), options)), {4, 0, 0}));
  CHECK(std::chrono::steady_clock::now() - start < std::chrono::seconds(10));
}

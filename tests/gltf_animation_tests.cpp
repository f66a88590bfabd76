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

const std::string kNamedZero = "1 animation (first: animation 0 'A') is not played (the static pose is drawn)";

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
        "2 animations (first: animation 1 'Moves') are not played (the static pose is drawn)");
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

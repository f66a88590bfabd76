// EXT_lights_image_based (issue 18 item 2): the scene's image-based light
// becomes its environment map. Generated files with one colour per cube
// face check the face order and GL's face orientation, the RGBD decoding,
// the intensity and the rotation; malformed lights are refused, named.
#include <doctest/doctest.h>

#include <OpenImageIO/imageio.h>

#include <array>
#include <cmath>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "color/srgb.hpp"
#include "environment/equirect.hpp"
#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "support/encoding.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
using nlohmann::json;

namespace {

using Rgba = std::array<unsigned char, 4>;

// A size x size RGBA PNG whose top rows (the first half) are `top` and the rest `bottom`.
std::string writeFace(const test::TempFolder& folder, const std::string& name, int size, Rgba top, Rgba bottom) {
  std::vector<unsigned char> pixels;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) pixels.insert(pixels.end(), (y < size / 2 ? top : bottom).begin(),
                                                 (y < size / 2 ? top : bottom).end());
  const auto path = folder.path() / name;
  auto output = OIIO::ImageOutput::create(path.string());
  REQUIRE(output);
  REQUIRE(output->open(path.string(), OIIO::ImageSpec(size, size, 4, OIIO::TypeDesc::UINT8)));
  REQUIRE(output->write_image(OIIO::TypeDesc::UINT8, pixels.data()));
  REQUIRE(output->close());
  return name;
}

// The face colours: +X red, -X green, +Y top half yellow / bottom half blue,
// -Y cyan, +Z magenta in RGBD with A = 128 (twice as bright), -Z grey.
const Rgba kFaceColors[6] = {{255, 0, 0, 255},     {0, 255, 0, 255},   {255, 255, 0, 255},
                             {0, 255, 255, 255},   {255, 0, 255, 128}, {128, 128, 128, 255}};
const Rgba kPlusYBottom = {0, 0, 255, 255};

glm::vec3 linear(Rgba c) {
  return glm::vec3(srgbToLinear(c[0] / 255.0f), srgbToLinear(c[1] / 255.0f), srgbToLinear(c[2] / 255.0f)) /
         (c[3] / 255.0f);
}

// A triangle scene whose scene 0 names image-based light 0, `light` (its
// specularImages filled in with the six faces unless given).
json sceneWithLight(const test::TempFolder& folder, json light) {
  const float positions[] = {0, 0, 0, 1, 0, 0, 0, 1, 0};
  const auto* first = reinterpret_cast<const unsigned char*>(positions);
  const std::vector<unsigned char> bytes(first, first + sizeof positions);
  json images = json::array();
  for (int face = 0; face < 6; ++face)
    images.push_back({{"uri", writeFace(folder, "face" + std::to_string(face) + ".png", 4, kFaceColors[face],
                                        face == 2 ? kPlusYBottom : kFaceColors[face])}});
  images.push_back({{"uri", writeFace(folder, "wide.png", 2, kFaceColors[0], kFaceColors[0])}});
  if (!light.contains("specularImages")) light["specularImages"] = {{0, 1, 2, 3, 4, 5}};
  if (!light.contains("specularImageSize")) light["specularImageSize"] = 4;
  return {{"asset", {{"version", "2.0"}}},
          {"extensionsUsed", {"EXT_lights_image_based"}},
          {"extensions", {{"EXT_lights_image_based", {{"lights", {light}}}}}},
          {"buffers", {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + test::base64(bytes)}}}},
          {"bufferViews", {{{"buffer", 0}, {"byteLength", bytes.size()}}}},
          {"accessors",
           {{{"bufferView", 0}, {"componentType", 5126}, {"count", 3}, {"type", "VEC3"}, {"min", {0, 0, 0}}, {"max", {1, 1, 0}}}}},
          {"images", images},
          {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}}}}}}}}},
          {"nodes", {{{"mesh", 0}}}},
          {"scenes", {{{"nodes", {0}}, {"extensions", {{"EXT_lights_image_based", {{"light", 0}}}}}}}},
          {"scene", 0}};
}

Scene loadWithLight(const test::TempFolder& folder, const json& light) {
  return loadGltf(folder.write("scene.gltf", sceneWithLight(folder, light).dump()));
}

// The map's texel nearest world direction `d`.
glm::vec3 seen(const EnvironmentMap& map, glm::vec3 d) {
  const glm::vec2 uv = environment::directionToUv(glm::normalize(d));
  const int x = std::min(int(uv.x * map.width), map.width - 1), y = std::min(int(uv.y * map.height), map.height - 1);
  const float* texel = &map.rgb[(std::size_t(y) * std::size_t(map.width) + std::size_t(x)) * 3];
  return {texel[0], texel[1], texel[2]};
}

void checkNear(glm::vec3 actual, glm::vec3 expected) {
  INFO("actual ", actual.r, " ", actual.g, " ", actual.b, ", expected ", expected.r, " ", expected.g, " ", expected.b);
  for (int c = 0; c < 3; ++c) CHECK(actual[c] == doctest::Approx(expected[c]).epsilon(1e-4).scale(1.0));
}

}  // namespace

TEST_CASE("EXT_lights_image_based: each cube face lies where GL puts it, RGBD decoded, and nothing is named") {
  test::TempFolder folder;
  const Scene scene = loadWithLight(folder, json::object());
  REQUIRE(scene.environment);
  const EnvironmentMap& map = *scene.environment;
  CHECK(map.width == 16);  // four texels per face texel around the equator
  CHECK(map.height == 8);
  checkNear(seen(map, {1, 0, 0}), linear(kFaceColors[0]));
  checkNear(seen(map, {-1, 0, 0}), linear(kFaceColors[1]));
  checkNear(seen(map, {0, -1, 0}), linear(kFaceColors[3]));
  checkNear(seen(map, {0, 0, 1}), linear(kFaceColors[4]));
  CHECK(seen(map, {0, 0, 1}).r > 1.5f);  // A = 128: RGBD doubles the face's value
  checkNear(seen(map, {0, 0, -1}), linear(kFaceColors[5]));
  // +Y: GL's t = (z + 1) / 2 there, so the image's first rows face -Z.
  checkNear(seen(map, {0, 1, -0.6f}), linear(kFaceColors[2]));
  checkNear(seen(map, {0, 1, 0.6f}), linear(kPlusYBottom));
  for (const IgnoredFeature& ignored : scene.ignored) CHECK(ignored.feature != "EXT_lights_image_based");
}

TEST_CASE("EXT_lights_image_based: intensity scales the light, rotation turns it") {
  test::TempFolder folder;
  const Scene brighter = loadWithLight(folder, {{"intensity", 2.5}});
  checkNear(seen(*brighter.environment, {-1, 0, 0}), 2.5f * linear(kFaceColors[1]));
  // 90 degrees about +Y (x, y, z, w): the light's +X now lies at world -Z.
  const float h = std::sqrt(0.5f);
  const Scene turned = loadWithLight(folder, {{"rotation", {0, h, 0, h}}});
  checkNear(seen(*turned.environment, {0, 0, -1}), linear(kFaceColors[0]));
  checkNear(seen(*turned.environment, {1, 0, 0}), linear(kFaceColors[4]));
}

TEST_CASE("EXT_lights_image_based: a malformed light is refused, naming it and the problem") {
  test::TempFolder folder;
  const auto error = [&](const json& light) {
    try {
      loadWithLight(folder, light);
    } catch (const SceneError& e) {
      return std::string(e.what());
    }
    return std::string("(loaded)");
  };
  CHECK(error({{"specularImages", {{0, 1, 2, 3, 4}}}}).find(
            "EXT_lights_image_based light 0 specularImages[0] has 5 images, expected 6 cube faces") != std::string::npos);
  CHECK(error({{"specularImages", {{0, 1, 2, 3, 4, 6}}}}).find("face 5 is 2 wide, face 0 4") != std::string::npos);
  CHECK(error({{"specularImages", {{0, 1, 2, 3, 4, 9}}}}).find("specularImages[0][5] is not an image of the file") !=
        std::string::npos);
  CHECK(error({{"intensity", -1}}).find("EXT_lights_image_based light 0 intensity is -1") != std::string::npos);
  // Finite, and every texel it makes finite, but the tables' sums overflowed: lit was NaN (issue 32).
  const std::string blinding = error({{"intensity", 1e38}});
  CHECK(blinding.find("environment map") != std::string::npos);
  CHECK(blinding.find("(EXT_lights_image_based light 0)") != std::string::npos);
  CHECK(blinding.find("so that float rendering stays finite") != std::string::npos);
  CHECK(error({{"rotation", {0, 0, 0, 0}}}).find("rotation is not a quaternion") != std::string::npos);
  // Declared wrongly, though not read (issue 32: accepted in silence before).
  json notNumbers = json::array();
  for (int row = 0; row < 9; ++row) notNumbers.push_back(json::array({1, row == 4 ? json("y") : json(2), 3}));
  for (const json& coefficients : {json("x"), json::array({json::array({1, 2, 3})}), notNumbers}) {
    CAPTURE(coefficients.dump());
    CHECK(error({{"irradianceCoefficients", coefficients}}).find("irradianceCoefficients is not 9 rows of 3") !=
          std::string::npos);
  }
  for (const json& size : {json(0), json(-4), json(2.5), json("4")}) {
    CAPTURE(size.dump());
    CHECK(error({{"specularImageSize", size}}).find("specularImageSize is not an integer >= 1") != std::string::npos);
  }
  CHECK(error({{"specularImages", json::array()}}).find("has no specularImages level") != std::string::npos);
  CHECK(error(json::object()).find("(loaded)") != std::string::npos);
  CHECK(error({{"intensity", -1}}).find("scene.gltf") != std::string::npos);
}

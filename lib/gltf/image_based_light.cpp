#include "gltf/image_based_light.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <string_view>

#include <glm/gtc/quaternion.hpp>

#include "color/srgb.hpp"
#include "environment/equirect.hpp"
#include "io/fingerprint.hpp"

namespace headlight::gltf {

namespace {

constexpr const char* kExtension = "EXT_lights_image_based";
// The map's width: four texels per face texel around the equator, at most
// this (2048 x 1024 RGB floats: 24 MiB), enough for the prefiltered levels
// and the background at the images Headlight renders.
constexpr int kMaxMapWidth = 2048;

// One face's texels as linear radiance: the images are sRGB-encoded, and a
// 4-channel PNG holds RGBD (linear RGB = decoded RGB / A), of which a 3-channel
// image or a JPEG (A = 1) is the special case.
struct Face {
  int size = 0;
  const std::vector<std::uint8_t>* rgba = nullptr;
  glm::vec3 texel(int x, int y) const {
    const std::uint8_t* p = rgba->data() + (std::size_t(y) * std::size_t(size) + std::size_t(x)) * 4;
    const float divisor = std::max(float(p[3]), 1.0f) / 255.0f;
    return glm::vec3(srgbToLinear(p[0] / 255.0f), srgbToLinear(p[1] / 255.0f), srgbToLinear(p[2] / 255.0f)) / divisor;
  }
};

// GL's cube-map face selection (the OpenGL 4.5 specification, table 8.19),
// with each image's first row at t = 0, as a GL renderer uploads the
// extension's images: the face (+X, -X, +Y, -Y, +Z, -Z) and (s, t) in 0..1.
std::pair<int, glm::vec2> cubeFace(const glm::vec3& d) {
  const glm::vec3 a = glm::abs(d);
  int face;
  float sc, tc, ma;
  if (a.x >= a.y && a.x >= a.z) {
    face = d.x > 0 ? 0 : 1, ma = a.x, sc = d.x > 0 ? -d.z : d.z, tc = -d.y;
  } else if (a.y >= a.z) {
    face = d.y > 0 ? 2 : 3, ma = a.y, sc = d.x, tc = d.y > 0 ? d.z : -d.z;
  } else {
    face = d.z > 0 ? 4 : 5, ma = a.z, sc = d.z > 0 ? d.x : -d.x, tc = -d.y;
  }
  return {face, glm::vec2(sc / ma + 1.0f, tc / ma + 1.0f) * 0.5f};
}

// Bilinear within the face (edges clamped).
glm::vec3 sampleFace(const Face& face, glm::vec2 st) {
  const glm::vec2 p = glm::clamp(st * float(face.size) - 0.5f, glm::vec2(0.0f), glm::vec2(float(face.size - 1)));
  const int x0 = int(p.x), y0 = int(p.y);
  const int x1 = std::min(x0 + 1, face.size - 1), y1 = std::min(y0 + 1, face.size - 1);
  const float fx = p.x - float(x0), fy = p.y - float(y0);
  return glm::mix(glm::mix(face.texel(x0, y0), face.texel(x1, y0), fx),
                  glm::mix(face.texel(x0, y1), face.texel(x1, y1), fx), fy);
}

double numberIn(const Source& source, const tinygltf::Value& object, const char* key, double fallback,
                const std::string& user) {
  if (!object.Has(key)) return fallback;
  const tinygltf::Value& value = object.Get(key);
  if (!value.IsNumber() && !value.IsInt()) source.fail(user + " " + key + " is not a number");
  return value.GetNumberAsDouble();
}

glm::quat rotationOf(const Source& source, const tinygltf::Value& light, const std::string& user) {
  if (!light.Has("rotation")) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  const tinygltf::Value& array = light.Get("rotation");
  std::array<double, 4> q{};
  bool numbers = array.IsArray() && array.ArrayLen() == 4;
  for (int i = 0; numbers && i < 4; ++i) {
    numbers = array.Get(i).IsNumber() || array.Get(i).IsInt();
    if (numbers) q[std::size_t(i)] = array.Get(i).GetNumberAsDouble();
  }
  const double length = std::sqrt(q[0] * q[0] + q[1] * q[1] + q[2] * q[2] + q[3] * q[3]);
  if (!numbers || !std::isfinite(length) || length < 1e-6) {
    source.fail(user + " rotation is not a quaternion (4 finite numbers, not all 0)");
  }
  // glTF writes (x, y, z, w); glm's constructor takes w first.
  return glm::quat(float(q[3] / length), float(q[0] / length), float(q[1] / length), float(q[2] / length));
}

// The six images of the first level, checked: indices, square, one size.
std::array<Face, 6> firstLevel(const Source& source, const tinygltf::Value& light, const std::string& user,
                               const std::vector<ImageData>& images) {
  if (!light.Has("specularImages") || !light.Get("specularImages").IsArray() ||
      light.Get("specularImages").ArrayLen() == 0 || !light.Get("specularImages").Get(0).IsArray()) {
    source.fail(user + " has no specularImages level");
  }
  const tinygltf::Value& level = light.Get("specularImages").Get(0);
  if (level.ArrayLen() != 6) {
    source.fail(user + " specularImages[0] has " + std::to_string(level.ArrayLen()) + " images, expected 6 cube faces");
  }
  std::array<Face, 6> faces;
  for (int i = 0; i < 6; ++i) {
    const tinygltf::Value& entry = level.Get(i);
    const int index = entry.IsInt() ? entry.GetNumberAsInt() : -1;
    if (index < 0 || std::size_t(index) >= images.size()) {
      source.fail(user + " specularImages[0][" + std::to_string(i) + "] is not an image of the file (it has " +
                  std::to_string(images.size()) + ")");
    }
    const ImageData& image = images[std::size_t(index)];
    if (image.width != image.height || image.width < 1) {
      source.fail(user + " face " + std::to_string(i) + " (image " + std::to_string(index) + ") is " +
                  std::to_string(image.width) + "x" + std::to_string(image.height) + ", expected square");
    }
    if (i > 0 && image.width != faces[0].size) {
      source.fail(user + " face " + std::to_string(i) + " is " + std::to_string(image.width) + " wide, face 0 " +
                  std::to_string(faces[0].size));
    }
    faces[std::size_t(i)] = Face{image.width, &image.rgba};
  }
  return faces;
}

// irradianceCoefficients and specularImageSize, which the specification
// requires: the irradiance is computed from the cube and the size read from
// its images, so neither is used, but a file that declares them wrongly is
// malformed and is refused, named, not accepted in silence (issue 32).
void checkDeclaredTables(const Source& source, const tinygltf::Value& light, const std::string& user) {
  if (light.Has("irradianceCoefficients")) {
    const tinygltf::Value& rows = light.Get("irradianceCoefficients");
    bool wellFormed = rows.IsArray() && rows.ArrayLen() == 9;
    for (int row = 0; wellFormed && row < 9; ++row) {
      const tinygltf::Value& coefficients = rows.Get(row);
      wellFormed = coefficients.IsArray() && coefficients.ArrayLen() == 3;
      for (int channel = 0; wellFormed && channel < 3; ++channel) {
        const tinygltf::Value& value = coefficients.Get(channel);
        wellFormed = (value.IsNumber() || value.IsInt()) && std::isfinite(value.GetNumberAsDouble());
      }
    }
    if (!wellFormed)
      source.fail(user + " irradianceCoefficients is not 9 rows of 3 finite numbers (spherical harmonics to order 2)");
  }
  if (light.Has("specularImageSize")) {
    const tinygltf::Value& size = light.Get("specularImageSize");
    if (!size.IsInt() || size.GetNumberAsInt() < 1) source.fail(user + " specularImageSize is not an integer >= 1");
  }
}

}  // namespace

std::shared_ptr<const EnvironmentMap> readImageBasedLight(const Source& source, int sceneIndex,
                                                          const std::vector<ImageData>& images) {
  const tinygltf::Model& model = source.model;
  const int drawn = sceneIndex >= 0 ? sceneIndex : std::max(model.defaultScene, 0);
  if (std::size_t(drawn) >= model.scenes.size()) return nullptr;
  const auto named = model.scenes[std::size_t(drawn)].extensions.find(kExtension);
  if (named == model.scenes[std::size_t(drawn)].extensions.end()) return nullptr;
  const std::string sceneName = "scene " + std::to_string(drawn) + " " + kExtension;
  if (!named->second.Has("light") || !named->second.Get("light").IsInt())
    source.fail(sceneName + " has no light index");
  const int lightIndex = named->second.Get("light").GetNumberAsInt();
  const auto root = model.extensions.find(kExtension);
  const tinygltf::Value* lights =
      root != model.extensions.end() && root->second.Has("lights") ? &root->second.Get("lights") : nullptr;
  if (!lights || !lights->IsArray() || lightIndex < 0 || lightIndex >= int(lights->ArrayLen())) {
    source.fail(sceneName + " names light " + std::to_string(lightIndex) + ", but the file has " +
                std::to_string(lights && lights->IsArray() ? lights->ArrayLen() : 0) + " " + kExtension + " lights");
  }
  const tinygltf::Value& light = lights->Get(lightIndex);
  const std::string user = std::string(kExtension) + " light " + std::to_string(lightIndex);
  const double intensity = numberIn(source, light, "intensity", 1.0, user);
  if (!std::isfinite(intensity) || intensity < 0.0) {
    source.fail(user + " intensity is " + std::to_string(intensity) + ", expected a finite number >= 0");
  }
  checkDeclaredTables(source, light, user);
  const glm::quat toWorld = rotationOf(source, light, user);
  const std::array<Face, 6> faces = firstLevel(source, light, user, images);

  auto map = std::make_shared<EnvironmentMap>();
  map->source = source.file + " (" + user + ")";
  map->width = std::min(4 * faces[0].size, kMaxMapWidth);
  map->height = map->width / 2;
  map->rgb.resize(std::size_t(map->width) * std::size_t(map->height) * 3);
  // A world direction reads the light's cube where the rotation takes it back.
  const glm::quat toLight = glm::conjugate(toWorld);
  for (int y = 0; y < map->height; ++y) {
    for (int x = 0; x < map->width; ++x) {
      const glm::vec3 world = environment::uvToDirection((x + 0.5f) / map->width, (y + 0.5f) / map->height);
      const auto [face, st] = cubeFace(toLight * world);
      const glm::vec3 radiance = sampleFace(faces[std::size_t(face)], st) * float(intensity);
      std::copy_n(&radiance.x, 3, map->rgb.begin() + (std::ptrdiff_t(y) * map->width + x) * 3);
    }
  }
  map->sourceHash = textFingerprint(
      std::string_view(reinterpret_cast<const char*>(map->rgb.data()), map->rgb.size() * sizeof(float)));
  return map;
}

}  // namespace headlight::gltf

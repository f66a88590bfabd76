#pragma once
// Generated environment maps for the environment tests (unit, gl, hostile):
// equirectangular float images written through OpenImageIO into a test's
// temp folder, with radiance given per texel, so each test knows its map's
// integrals in closed form.
#include <OpenImageIO/imageio.h>

#include <filesystem>
#include <functional>
#include <stdexcept>
#include <vector>

#include <glm/glm.hpp>

#include "headlight/scene.hpp"

namespace headlight::test {

// Writes a width x height RGB float image (EXR, or HDR by the extension)
// whose texel (x, y) (rows top first) is radiance(x, y).
inline std::filesystem::path writeEnvironmentMap(const std::filesystem::path& path, int width, int height,
                                                 const std::function<glm::vec3(int x, int y)>& radiance) {
  std::vector<float> pixels(std::size_t(width) * std::size_t(height) * 3);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const glm::vec3 value = radiance(x, y);
      float* texel = &pixels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
      for (int c = 0; c < 3; ++c) texel[c] = value[c];
    }
  auto output = OIIO::ImageOutput::create(path.string());
  if (!output || !output->open(path.string(), OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT)) ||
      !output->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) || !output->close())
    throw std::runtime_error("cannot write test map " + path.string() + ": " + OIIO::geterror());
  return path;
}

// The three closed-form maps of the environment tests, all 64 x 32.
inline glm::vec3 uniformRadiance(int, int) { return glm::vec3(0.5f); }
inline glm::vec3 horizonSplitRadiance(int, int y) { return y < 16 ? glm::vec3(1.0f) : glm::vec3(0.0f); }
constexpr int kBrightTexelX = 40, kBrightTexelY = 10;
inline glm::vec3 brightTexelRadiance(int x, int y) {
  return x == kBrightTexelX && y == kBrightTexelY ? glm::vec3(1000.0f) : glm::vec3(0.0f);
}

// A directional light of intensity 0 that casts no shadow: a scene with it
// has no default key light, so only the ambient term (the map) lights it.
inline Light darkLight() {
  Light dark;
  dark.type = Light::Type::Directional;
  dark.intensity = 0.0f;
  dark.castsShadows = false;
  return dark;
}

}  // namespace headlight::test

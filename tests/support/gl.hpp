#pragma once
// What GL tests share: one context per process for the backend under test,
// small scenes built in code, and pixel lookups by world position.
#include <cstdlib>
#include <functional>
#include <string>

#include "headlight/context.hpp"
#include "headlight/frame.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene.hpp"
#include "headlight/shapes.hpp"

namespace headlight::test {

inline Backend backendUnderTest() {
  const char* name = std::getenv("HEADLIGHT_TEST_BACKEND");
  return parseBackend(name ? name : "auto");
}

// Errors throw (GlErrorPolicy::Throw): a GL error fails the test.
inline Context& sharedContext() {
  static Context context(ContextOptions{backendUnderTest(), -1, GlErrorPolicy::Throw});
  return context;
}

// A Lambertian-looking material for test scenes.
inline Material plainMaterial(glm::vec3 color, float metallic = 0.0f, float roughness = 0.8f) {
  Material material;
  material.baseColorFactor = glm::vec4(color, 1.0f);
  material.metallicFactor = metallic;
  material.roughnessFactor = roughness;
  return material;
}


// A camera at `eye` looking at `target`, perspective with yfov radians or
// orthographic with half height `orthoHalfHeight` if > 0.
Camera lookAtCamera(glm::vec3 eye, glm::vec3 target, float yfov, float orthoHalfHeight = 0.0f);

// Mean of `channel` of `image` over the pixels whose G-buffer position and
// normal pass `select`; sets `count` to how many there were.
double meanWhere(const Frame& frame, const ImageF& image, int channel,
                 const std::function<bool(glm::vec3 position, glm::vec3 normal)>& select, int& count);

// Settings for a small test render.
inline RenderSettings smallSettings(int width = 96, int height = 96) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  return settings;
}

}  // namespace headlight::test

// What the parity tests share (a GLSL pass against its CPU port in
// lib/reference/, pixel by pixel on a read-back frame): reading a pixel,
// the punctual lights summed through a BRDF, and the per-channel comparison
// with its tolerance. Header-only: the tests are in several programs.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "headlight/frame.hpp"
#include "headlight/scene.hpp"
#include "reference/shading.hpp"

namespace headlight::test {

inline glm::vec3 pixel3(const ImageF& image, int x, int y) {
  return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}
inline glm::vec4 pixel4(const ImageF& image, int x, int y) {
  return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2), image.at(x, y, 3)};
}

// The scene's punctual lights at `position`, as direct_light.frag sums them:
// brdf(toLight) (cos included) times colour, intensity and attenuation.
template <class Brdf>
glm::vec3 punctualLight(const Scene& scene, const glm::vec3& position, Brdf brdf) {
  glm::vec3 sum(0.0f);
  for (const Light& light : scene.lights) {
    glm::vec3 toLight;
    float distance = 0.0f;
    const float attenuation = reference::lightAttenuation(light, position, toLight, distance);
    if (attenuation <= 0.0f) continue;
    sum += brdf(toLight) * light.color * light.intensity * attenuation;
  }
  return sum;
}

// A GPU value passes when it is within relative * |cpu| + absolute of the
// CPU port's. Every channel outside is counted; only the first five are
// CHECKed with their pixel, so a port that no longer matches at all names a
// few pixels rather than thousands. The worst relative error (where the CPU
// value is above 1e-3) is kept for the test's MESSAGE.
struct ParityTally {
  float relative = 0.0f, absolute = 0.0f;
  int outside = 0;
  float worstRelative = 0.0f;

  void compare(int x, int y, const glm::vec3& gpu, const glm::vec3& cpu) {
    for (int c = 0; c < 3; ++c) {
      const float error = std::abs(gpu[c] - cpu[c]);
      if (cpu[c] > 1e-3f) worstRelative = std::max(worstRelative, error / cpu[c]);
      if (error <= relative * std::abs(cpu[c]) + absolute || ++outside > 5) continue;
      CAPTURE(x);
      CAPTURE(y);
      CAPTURE(c);
      CHECK(gpu[c] == doctest::Approx(cpu[c]).epsilon(relative));
    }
  }
};

}  // namespace headlight::test

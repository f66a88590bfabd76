// What the parity tests share (a GLSL pass against its CPU port in
// lib/reference/, pixel by pixel on a read-back frame): reading a pixel,
// the punctual lights summed through a BRDF, and the per-channel comparison
// with its tolerance. Header-only: the tests are in several programs.
#pragma once

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
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

// brdf_lut.frag's split-sum (scale, bias) at exactly (nDotV, roughness):
// the same 512 Hammersley samples, without the table's interpolation.
inline glm::vec2 splitSum(float nDotV, float roughness) {
  const float alpha = roughness * roughness;
  nDotV = std::max(nDotV, 1e-4f);
  const glm::vec3 view(std::sqrt(1.0f - nDotV * nDotV), 0.0f, nDotV);
  constexpr unsigned kSamples = 512;
  glm::vec2 sum(0.0f);
  for (unsigned i = 0; i < kSamples; ++i) {
    std::uint32_t bits = i;
    bits = (bits << 16u) | (bits >> 16u);
    bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
    bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
    bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
    bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
    const glm::vec3 halfVector =
        reference::importanceSampleGgx(float(i) / float(kSamples), float(bits) * 2.3283064365386963e-10f, alpha);
    const glm::vec3 light = 2.0f * glm::dot(view, halfVector) * halfVector - view;
    const float nDotL = light.z, nDotH = std::max(halfVector.z, 0.0f);
    const float vDotH = std::max(glm::dot(view, halfVector), 0.0f);
    if (nDotL <= 0.0f) continue;
    const float weight =
        4.0f * reference::smithGgxVisibility(nDotV, nDotL, alpha) * vDotH * nDotL / std::max(nDotH, 1e-7f);
    const float fresnel = std::pow(1.0f - vDotH, 5.0f);
    sum += glm::vec2((1.0f - fresnel) * weight, fresnel * weight);
  }
  return sum / float(kSamples);
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

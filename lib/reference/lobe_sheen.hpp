#pragma once
// CPU port of glsl/lobe_sheen.glsl (KHR_materials_sheen's Charlie lobe and
// its albedo scaling): same names, clamps and constants, held to the GLSL by
// tests/sheen_anisotropy_parity_tests.cpp. Pure functions of their inputs,
// and SheenLobe's hooks (reference/lobes.hpp).
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <numbers>
#include <optional>

#include "headlight/scene.hpp"
#include "reference/surface.hpp"

namespace headlight::reference {

inline constexpr float kSheenMinRoughness = 0.07f;  // lobe_sheen.glsl: the exponent 1 / alpha stays below 205

inline float sheenAlpha(float roughness) {
  const float r = std::clamp(roughness, kSheenMinRoughness, 1.0f);
  return r * r;
}

inline float sheenStrength(const glm::vec3& sheenColor) { return std::max({sheenColor.r, sheenColor.g, sheenColor.b}); }

inline float sheenDistribution(float alpha, float nDotH) {
  const float inverseAlpha = 1.0f / alpha;
  const float sinSquared = std::max(1.0f - nDotH * nDotH, 1e-7f);
  return (2.0f + inverseAlpha) * std::pow(sinSquared, 0.5f * inverseAlpha) / (2.0f * std::numbers::pi_v<float>);
}

inline float sheenLambdaFit(float x, float alpha) {
  const float t = (1.0f - alpha) * (1.0f - alpha);
  auto mix = [t](float atOne, float atZero) { return atOne + (atZero - atOne) * t; };
  const float a = mix(21.5473f, 25.3245f), b = mix(3.82987f, 3.32435f), c = mix(0.19823f, 0.16801f);
  const float d = mix(-1.97760f, -1.27393f), e = mix(-4.32054f, -4.85967f);
  return a / (1.0f + b * std::pow(x, c)) + d * x + e;
}

inline float sheenLambda(float cosTheta, float alpha) {
  return cosTheta < 0.5f ? std::exp(sheenLambdaFit(cosTheta, alpha))
                         : std::exp(2.0f * sheenLambdaFit(0.5f, alpha) - sheenLambdaFit(1.0f - cosTheta, alpha));
}

inline float sheenVisibility(float alpha, float nDotV, float nDotL) {
  return 1.0f / ((1.0f + sheenLambda(nDotV, alpha) + sheenLambda(nDotL, alpha)) * (4.0f * nDotV * nDotL));
}

inline float sheenAlbedo(float alpha, float cosTheta) {
  const float c = 1.0f - std::clamp(cosTheta, 0.0f, 1.0f);
  return 0.65584461f * c * c * c + 1.0f / (4.16526551f + std::exp(-7.97291361f * std::sqrt(alpha) + 6.33516894f));
}

inline glm::vec3 sheenReflected(const glm::vec3& sheenColor, float roughness, float nDotV, float nDotL, float nDotH) {
  const float alpha = sheenAlpha(roughness);
  return sheenColor * (sheenDistribution(alpha, nDotH) * sheenVisibility(alpha, nDotV, nDotL) * nDotL);
}

inline float sheenBaseScale(const glm::vec3& sheenColor, float roughness, float nDotV, float nDotL) {
  const float alpha = sheenAlpha(roughness), strength = sheenStrength(sheenColor);
  return std::min(1.0f - strength * sheenAlbedo(alpha, nDotV), 1.0f - strength * sheenAlbedo(alpha, nDotL));
}

// lobe_sheen.glsl's hooks: the lobe's value is the sheen colour (rgb;
// black: no layer) and roughness (a).
struct SheenLobe {
  static constexpr Lobe kLobe = Lobe::Sheen;
  // lobe_sheen_material.glsl sheenLobeOfMaterial (`texel(ref, srgb)`: white without a texture).
  template <class Texel>
  static std::optional<glm::vec4> ofMaterial(const Material& material, const Texel& texel) {
    if (!material.sheen) return std::nullopt;
    const MaterialSheen& sheen = *material.sheen;
    return glm::clamp(glm::vec4(sheen.sheenColorFactor * glm::vec3(texel(sheen.sheenColorTexture, true)),
                                sheen.sheenRoughnessFactor * texel(sheen.sheenRoughnessTexture, false).a),
                      0.0f, 1.0f);
  }
  static float layerScale(const Surface& s, const glm::vec4& sheen, float nDotL) {
    const glm::vec3 color(sheen);
    return color != glm::vec3(0.0f) ? sheenBaseScale(color, sheen.a, s.nDotV, nDotL) : 1.0f;
  }
  static glm::vec3 layerLight(const Surface& s, const glm::vec4& sheen, float nDotL, float nDotH) {
    const glm::vec3 color(sheen);
    return color != glm::vec3(0.0f) ? sheenReflected(color, sheen.a, s.nDotV, nDotL, nDotH) : glm::vec3(0.0f);
  }
};

}  // namespace headlight::reference

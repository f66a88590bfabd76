#pragma once
// CPU ports of the renderer's shading (glsl/brdf.glsl, glsl/sky.glsl,
// glsl/sampling.glsl) for the Embree reference, plus its random numbers.
// Each function keeps the GLSL one's name, clamps and constants, so that a
// difference between the reference and a render is the method's and never a
// transcription's. Pure functions: every input is a parameter.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <glm/glm.hpp>
#include <limits>

#include "headlight/scene.hpp"
#include "reference/lobes.hpp"
#include "reference/surface.hpp"

namespace headlight::reference {

constexpr float kPi = 3.14159265358979f;

// ---- Random numbers ----------------------------------------------------------

// SplitMix64 (Steele, Lea, Flood 2014): turns (seed, pixel) into a well-mixed
// PCG state, so neighbouring pixels' streams do not start correlated.
inline std::uint64_t splitMix64(std::uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}

// PCG32 (O'Neill 2014, pcg32_random_r / pcg32_srandom_r): 64-bit state,
// 32-bit output, one independent stream per `sequence`. Plain independent
// samples (no stratification), so the per-pixel standard errors the
// reference reports are the textbook ones and error falls as 1/sqrt(n).
class Pcg32 {
 public:
  Pcg32(std::uint64_t initialState, std::uint64_t sequence) : increment_((sequence << 1u) | 1u) {
    next();
    state_ += initialState;
    next();
  }
  std::uint32_t next() {
    const std::uint64_t old = state_;
    state_ = old * 6364136223846793005ull + increment_;
    const auto xorShifted = static_cast<std::uint32_t>(((old >> 18u) ^ old) >> 27u);
    const auto rotation = static_cast<std::uint32_t>(old >> 59u);
    return (xorShifted >> rotation) | (xorShifted << ((0u - rotation) & 31u));
  }
  // Uniform in [0, 1): the top 24 bits, exactly representable as a float.
  float uniform() { return float(next() >> 8u) * 0x1p-24f; }

 private:
  std::uint64_t state_ = 0;
  std::uint64_t increment_;
};

// The stream of pixel `pixelIndex` (row-major, top row first) for `seed`:
// a function of these two only, so results do not depend on threads.
inline Pcg32 pixelStream(unsigned seed, std::uint64_t pixelIndex) {
  return Pcg32(splitMix64(splitMix64(seed) ^ pixelIndex), pixelIndex ^ (std::uint64_t(seed) << 32u));
}

// ---- Directions ----------------------------------------------------------------

// sampling.glsl basisAround: an orthonormal frame with `normal` (unit) as
// its third axis, built from a helper axis (+Z, or +X where the normal is
// within 0.999 of +-Z) as the GLSL does, so that a direction drawn around a
// normal here is the one the shaders draw.
struct Basis {
  glm::vec3 tangent, bitangent, normal;
  glm::vec3 toWorld(const glm::vec3& local) const { return tangent * local.x + bitangent * local.y + normal * local.z; }
};
inline Basis basisAround(const glm::vec3& normal) {
  const glm::vec3 up = std::abs(normal.z) < 0.999f ? glm::vec3(0.0f, 0.0f, 1.0f) : glm::vec3(1.0f, 0.0f, 0.0f);
  const glm::vec3 tangent = glm::normalize(glm::cross(up, normal));
  return {tangent, glm::cross(normal, tangent), normal};
}

// sampling.glsl cosineSampleHemisphere: density cos(theta) / pi around +Z.
inline glm::vec3 cosineSampleHemisphere(float xi0, float xi1) {
  const float r = std::sqrt(xi0), phi = 2.0f * kPi * xi1;
  return {r * std::cos(phi), r * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - xi0))};
}

// sampling.glsl importanceSampleGgx: a half vector with density D(h) cos(h)
// around +Z for alpha = perceptual roughness squared. No clamp under the
// square root, as in the GLSL (cosTheta <= 1 in exact arithmetic).
inline glm::vec3 importanceSampleGgx(float xi0, float xi1, float alpha) {
  const float phi = 2.0f * kPi * xi0;
  const float cosTheta = std::sqrt((1.0f - xi1) / (1.0f + (alpha * alpha - 1.0f) * xi1));
  const float sinTheta = std::sqrt(1.0f - cosTheta * cosTheta);
  return {sinTheta * std::cos(phi), sinTheta * std::sin(phi), cosTheta};
}

// ---- BRDF (brdf.glsl) ------------------------------------------------------------

// sampling.glsl smithGgxVisibility: height-correlated Smith G / (4 N.L N.V).
inline float smithGgxVisibility(float nDotV, float nDotL, float alpha) {
  const float a2 = alpha * alpha;
  const float ggxV = nDotL * std::sqrt(nDotV * nDotV * (1.0f - a2) + a2);
  const float ggxL = nDotV * std::sqrt(nDotL * nDotL * (1.0f - a2) + a2);
  return 0.5f / std::max(ggxV + ggxL, 1e-7f);
}

// brdf.glsl cookTorrance: (diffuse + specular) * N.L toward a unit `toLight`,
// with the hooks of the surface's lobes (reference/lobes.hpp).
inline glm::vec3 cookTorrance(const Surface& s, const glm::vec3& toLight) {
  const float nDotL = glm::dot(s.normal, toLight);
  if (nDotL <= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 halfVector = glm::normalize(toLight + s.view);
  const float nDotH = std::max(glm::dot(s.normal, halfVector), 0.0f);
  const float vDotH = std::max(glm::dot(s.view, halfVector), 0.0f);
  const float alpha = s.roughness * s.roughness;
  const float a2 = alpha * alpha;
  const float d = (nDotH * nDotH) * (a2 - 1.0f) + 1.0f;
  const float distribution = a2 / (kPi * d * d);
  const glm::vec3 fresnel = surfaceFresnel(s, vDotH);
  const float specularTerm =
      lobesSpecularTerm(s, distribution * smithGgxVisibility(s.nDotV, nDotL, alpha), alpha, toLight, halfVector, nDotL);
  const glm::vec3 specular = specularTerm * fresnel;
  const glm::vec3 diffuse = (1.0f - fresnel) * (1.0f - s.metallic) * (1.0f - s.transmission) * s.albedo / kPi;
  const glm::vec3 base = (diffuse + specular) * (nDotL * baseLayerScale(s, nDotL));
  return base + layersLight(s, nDotL, nDotH);
}

// brdf.glsl lightAttenuation: inverse square, glTF's range window and the
// spot cone; sets `toLight` (unit) and `distance` (infinite for a
// directional light). Light::direction is normalised as packLights does.
inline float lightAttenuation(const Light& light, const glm::vec3& position, glm::vec3& toLight, float& distance) {
  if (light.type == Light::Type::Directional) {
    toLight = -glm::normalize(light.direction);
    distance = std::numeric_limits<float>::infinity();
    return 1.0f;
  }
  const glm::vec3 offset = light.position - position;
  const float distanceSquared = std::max(glm::dot(offset, offset), 1e-30f);
  distance = std::sqrt(distanceSquared);
  toLight = offset / distance;
  float attenuation = 1.0f / distanceSquared;
  if (light.range > 0.0f) attenuation *= std::clamp(1.0f - std::pow(distance / light.range, 4.0f), 0.0f, 1.0f);
  if (light.type == Light::Type::Spot) {
    const float cosOuter = std::cos(light.outerConeAngle), cosInner = std::cos(light.innerConeAngle);
    const float scale = 1.0f / std::max(cosInner - cosOuter, 1e-3f);
    const float t = std::clamp((glm::dot(glm::normalize(light.direction), -toLight) - cosOuter) * scale, 0.0f, 1.0f);
    attenuation *= t * t;
  }
  return attenuation;
}

// ---- Sky (sky.glsl) ----------------------------------------------------------------

// Radiance from `direction` (unit), before the sky intensity.
inline glm::vec3 skyRadiance(const Sky& sky, const glm::vec3& direction) {
  const float height = std::clamp(direction.y, -1.0f, 1.0f);
  if (height >= 0.0f) return glm::mix(sky.horizon, sky.zenith, std::sqrt(height));
  return glm::mix(sky.horizon, sky.ground, std::min(1.0f, -height * 4.0f));
}

}  // namespace headlight::reference

#pragma once
// CPU port of glsl/lobe_anisotropy.glsl (KHR_materials_anisotropy's
// stretched GGX lobe), plus what the Embree reference needs beyond it:
// half vectors drawn from the stretched distribution. Same names, clamps and
// constants as the GLSL, held to it by tests/sheen_anisotropy_parity_tests.cpp.
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>
#include <numbers>
#include <optional>

#include "reference/surface.hpp"

namespace headlight::reference {

inline float anisotropyAlphaT(float alpha, float strength) { return alpha + (1.0f - alpha) * strength * strength; }

inline float anisotropicDistribution(float alphaT, float alphaB, float tDotH, float bDotH, float nDotH) {
  const float a = alphaT * alphaB;
  const glm::vec3 stretched(alphaB * tDotH, alphaT * bDotH, a * nDotH);
  const float w = a / std::max(glm::dot(stretched, stretched), 1e-30f);
  return a * w * w / std::numbers::pi_v<float>;
}

// `atV`, `atL`: the directions in the frame (T, B, N).
inline float anisotropicVisibility(float alphaT, float alphaB, const glm::vec3& atV, const glm::vec3& atL) {
  const float lambdaV = atL.z * glm::length(glm::vec3(alphaT * atV.x, alphaB * atV.y, atV.z));
  const float lambdaL = atV.z * glm::length(glm::vec3(alphaT * atL.x, alphaB * atL.y, atL.z));
  return 0.5f / std::max(lambdaV + lambdaL, 1e-7f);
}

inline float anisotropicSpecular(const glm::vec3& tangent, float strength, float alpha, const glm::vec3& normal,
                                 const glm::vec3& view, const glm::vec3& toLight, const glm::vec3& halfVector,
                                 float nDotV, float nDotL) {
  const glm::vec3 bitangent = glm::cross(normal, tangent);
  const float alphaT = anisotropyAlphaT(alpha, strength);
  const float distribution =
      anisotropicDistribution(alphaT, alpha, glm::dot(tangent, halfVector), glm::dot(bitangent, halfVector),
                              std::max(glm::dot(normal, halfVector), 0.0f));
  const glm::vec3 atV(glm::dot(tangent, view), glm::dot(bitangent, view), nDotV);
  const glm::vec3 atL(glm::dot(tangent, toLight), glm::dot(bitangent, toLight), nDotL);
  return distribution * anisotropicVisibility(alphaT, alpha, atV, atL);
}

inline float anisotropicAlbedoRoughness(float roughness, float strength) {
  const float alpha = roughness * roughness;
  return std::sqrt(0.5f * (anisotropyAlphaT(alpha, strength) + alpha));
}

inline glm::vec3 anisotropicReflection(const glm::vec3& normal, const glm::vec3& view, const glm::vec3& tangent,
                                       float strength, float roughness) {
  const glm::vec3 bitangent = glm::cross(normal, tangent);
  const glm::vec3 grainNormal = glm::cross(glm::cross(bitangent, view), bitangent);
  const float bend = 1.0f - strength * (1.0f - roughness);
  const glm::vec3 bent = glm::mix(grainNormal, normal, bend * bend * bend * bend);
  return glm::reflect(-view, glm::dot(bent, bent) > 1e-12f ? glm::normalize(bent) : normal);
}

// A half vector in the frame (T, B, N) drawn with density D(h) N.H from the
// stretched distribution: GGX's slopes are those of alpha = 1 scaled by
// (alpha_t, alpha_b), so one isotropic draw, stretched.
inline glm::vec3 importanceSampleAnisotropicGgx(float xi0, float xi1, float alphaT, float alphaB) {
  const float phi = 2.0f * std::numbers::pi_v<float> * xi0;
  const float tanTheta = std::sqrt(xi1 / std::max(1.0f - xi1, 1e-7f));
  return glm::normalize(glm::vec3(alphaT * tanTheta * std::cos(phi), alphaB * tanTheta * std::sin(phi), 1.0f));
}

// lobe_anisotropy.glsl's hooks: the lobe's value is the world direction T
// (xyz) and the strength (w; 0: the isotropic lobe). stretchedGgx is the
// reference's own: its estimator draws half vectors from the stretched lobe.
struct AnisotropyLobe {
  static constexpr Lobe kLobe = Lobe::Anisotropy;
  static float specularTerm(const Surface& s, const glm::vec4& anisotropy, float term, float alpha,
                            const glm::vec3& toLight, const glm::vec3& halfVector, float nDotL) {
    if (anisotropy.w <= 0.0f) return term;
    return anisotropicSpecular(glm::vec3(anisotropy), anisotropy.w, alpha, s.normal, s.view, toLight, halfVector,
                               s.nDotV, nDotL);
  }
  static float albedoRoughness(const Surface& s, const glm::vec4& anisotropy, float roughness) {
    return anisotropy.w > 0.0f ? anisotropicAlbedoRoughness(s.roughness, anisotropy.w) : roughness;
  }
  static std::optional<StretchedGgx> stretchedGgx(const Surface&, const glm::vec4& anisotropy, float alpha) {
    if (anisotropy.w <= 0.0f) return std::nullopt;
    return StretchedGgx{glm::vec3(anisotropy), anisotropyAlphaT(alpha, anisotropy.w), alpha};
  }
};

}  // namespace headlight::reference

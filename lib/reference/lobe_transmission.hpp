#pragma once
// CPU ports of glsl/lobe_transmission.glsl (KHR_materials_transmission and
// KHR_materials_volume), with the GLSL's names, clamps and constants, for
// the Embree reference and the parity tests
// (tests/transmission_parity_tests.cpp). Pure functions: every input is a
// parameter.
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include "headlight/scene.hpp"
#include "reference/shading.hpp"

namespace headlight::reference {

// lobe_transmission.glsl transmissionRoughness: microfacet refraction blurs
// with ior - 1, not at all at ior 1.
inline float transmissionRoughness(float roughness, float ior) {
  return roughness * std::clamp(ior * 2.0f - 2.0f, 0.0f, 1.0f);
}

// GLSL's refract(I, N, eta) for unit I and N: 0 on total internal reflection.
inline glm::vec3 refractGlsl(const glm::vec3& incident, const glm::vec3& normal, float eta) {
  const float nDotI = glm::dot(normal, incident);
  const float k = 1.0f - eta * eta * (1.0f - nDotI * nDotI);
  if (k < 0.0f) return glm::vec3(0.0f);
  return eta * incident - (eta * nDotI + std::sqrt(k)) * normal;
}

// lobe_transmission.glsl volumeTransmissionRay: the refracted path through
// `thickness` (mesh units) scaled per axis by `modelScale`; 0 for thin walls.
inline glm::vec3 volumeTransmissionRay(const glm::vec3& normal, const glm::vec3& view, float thickness, float ior,
                                       const glm::vec3& modelScale) {
  const glm::vec3 refracted = refractGlsl(-view, normal, 1.0f / std::max(ior, 1.0f));
  const glm::vec3 direction = glm::dot(refracted, refracted) > 0.0f ? glm::normalize(refracted) : -view;
  return direction * thickness * modelScale;
}

// lobe_transmission.glsl volumeAttenuation: Beer-Lambert; distance 0 (the
// specification's infinity) or a zero path absorbs nothing.
inline glm::vec3 volumeAttenuation(float pathLength, const glm::vec3& attenuationColor, float attenuationDistance) {
  if (attenuationDistance <= 0.0f || pathLength <= 0.0f) return glm::vec3(1.0f);
  return glm::pow(attenuationColor, glm::vec3(pathLength / attenuationDistance));
}

// lobe_transmission.glsl specularBtdf: thin-walled GGX BTDF times |N.L| for
// light from behind (N.L < 0), 0 from the front.
inline float specularBtdf(const glm::vec3& normal, const glm::vec3& view, float nDotV, const glm::vec3& toLight,
                          float roughness) {
  const float nDotL = glm::dot(normal, toLight);
  if (nDotL >= 0.0f) return 0.0f;
  const glm::vec3 mirrored = toLight - 2.0f * nDotL * normal;
  const glm::vec3 halfVector = glm::normalize(mirrored + view);
  const float nDotH = std::max(glm::dot(normal, halfVector), 0.0f);
  const float clamped = std::max(roughness, 0.03f);
  const float alpha = clamped * clamped;
  const float a2 = alpha * alpha;
  const float d = (nDotH * nDotH) * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d) * smithGgxVisibility(nDotV, -nDotL, alpha) * -nDotL;
}

// lobe_transmission.glsl transmissiveCookTorrance: cookTorrance from the
// front (its diffuse lobe keeps 1 - s.transmission), the tinted BTDF under
// (1 - F) and the sheen layer from behind.
inline glm::vec3 transmissiveCookTorrance(const Surface& s, const glm::vec3& toLight,
                                          float transmissionRoughnessValue) {
  const float nDotL = glm::dot(s.normal, toLight);
  if (nDotL > 0.0f) return cookTorrance(s, toLight);
  const glm::vec3 mirrored = toLight - 2.0f * nDotL * s.normal;
  const glm::vec3 fresnel = surfaceFresnel(s, std::max(glm::dot(s.view, glm::normalize(mirrored + s.view)), 0.0f));
  return s.transmission * (1.0f - fresnel) * (1.0f - s.metallic) * s.albedo *
         (specularBtdf(s.normal, s.view, s.nDotV, toLight, transmissionRoughnessValue) * baseLayerScale(s, -nDotL));
}

// lobe_transmission.glsl transmissionThroughput.
inline glm::vec3 transmissionThroughput(const Surface& s, const glm::vec3& specularAlbedo,
                                        const glm::vec3& attenuation) {
  return s.transmission * (1.0f - specularAlbedo) * (1.0f - s.metallic) * s.albedo * attenuation *
         baseLayerScale(s, s.nDotV);
}

// transmission.glsl's dielectric reflectance from KHR_materials_ior.
inline glm::vec3 iorF0(float ior, const glm::vec3& albedo, float metallic) {
  const float r = (ior - 1.0f) / (ior + 1.0f);
  return glm::mix(glm::vec3(r * r), albedo, metallic);
}

// lobe_transmission.glsl transmissionSpread and transmissionLod.
inline constexpr float kTransmissionSpread = 1.1f;
inline float transmissionSpread(float transmissionRoughnessValue) {
  return std::min(kTransmissionSpread * std::pow(transmissionRoughnessValue, 1.5f), 1.732f);
}
inline float transmissionLod(float transmissionRoughnessValue, float distanceBehind, float pixelsPerUnit) {
  const float radius = transmissionSpread(transmissionRoughnessValue) * distanceBehind * pixelsPerUnit;
  return std::log2(std::max(2.0f * radius, 1.0f));
}

// glsl/shadow_transmittance.glsl, ported: what transmissive casters let
// through to what they shadow (the model is described there).
inline constexpr float kOpaqueOpticalDepth = 30.0f;

// shadow_transmittance.glsl shadowCrossing.
inline glm::vec3 shadowCrossing(const glm::vec3& baseColor, float metallic, float transmission, float ior, float cosine,
                                bool tints) {
  const float relative = (std::max(ior, 1.0f) - 1.0f) / (std::max(ior, 1.0f) + 1.0f);
  const float f0 = relative * relative;
  const float fresnel = f0 + (1.0f - f0) * std::pow(1.0f - std::clamp(std::abs(cosine), 0.0f, 1.0f), 5.0f);
  const float share =
      std::clamp(transmission, 0.0f, 1.0f) * (1.0f - std::clamp(metallic, 0.0f, 1.0f)) * (1.0f - fresnel);
  return share * (tints ? glm::clamp(baseColor, 0.0f, 1.0f) : glm::vec3(1.0f));
}

// shadow_transmittance.glsl crossingOpticalDepth.
inline glm::vec3 crossingOpticalDepth(const glm::vec3& crossing) {
  return glm::min(-glm::log(glm::max(crossing, glm::vec3(std::exp(-kOpaqueOpticalDepth)))),
                  glm::vec3(kOpaqueOpticalDepth));
}

// shadow_transmittance.glsl volumeExtinction.
inline glm::vec3 volumeExtinction(const glm::vec3& attenuationColor, float attenuationDistance) {
  if (attenuationDistance <= 0.0f) return glm::vec3(0.0f);
  return glm::min(-glm::log(glm::max(attenuationColor, glm::vec3(std::exp(-kOpaqueOpticalDepth)))),
                  glm::vec3(kOpaqueOpticalDepth)) /
         attenuationDistance;
}

// shadow_transmittance.glsl shadowLayerOpticalDepth.
inline glm::vec3 shadowLayerOpticalDepth(const glm::vec3& baseColor, float metallic, float transmission, float ior,
                                         float cosine, bool volume, const glm::vec3& extinction,
                                         float distanceFromLight) {
  const bool enters = cosine > 0.0f;
  const glm::vec3 crossing = shadowCrossing(baseColor, metallic, transmission, ior, cosine, !volume || enters);
  glm::vec3 depth = crossingOpticalDepth(crossing);
  if (volume) depth += (enters ? -1.0f : 1.0f) * extinction * distanceFromLight;
  return depth;
}

// shadow_transmittance.glsl shadowTransmittance.
inline glm::vec3 shadowTransmittance(const glm::vec3& opticalDepth) {
  return glm::exp(-glm::max(opticalDepth, glm::vec3(0.0f)));
}

}  // namespace headlight::reference

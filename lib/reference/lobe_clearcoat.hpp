#pragma once
// CPU port of the clearcoat lobe (KHR_materials_clearcoat):
// glsl/lobe_clearcoat.glsl's functions with the GLSL's names, clamps and
// constants (shading.hpp says why), and the coat's sky light with true
// visibility for the Embree reference (the renderer's split sum,
// lobe_clearcoat_ambient.glsl, has no port: the reference samples it).
#include <algorithm>
#include <cmath>

#include <glm/glm.hpp>

#include "headlight/scene.hpp"
#include "reference/shading.hpp"

namespace headlight::reference {

// lobe_clearcoat.glsl signNotZero, octahedralEncode, octahedralDecode.
inline glm::vec2 signNotZero(const glm::vec2& v) { return {v.x >= 0.0f ? 1.0f : -1.0f, v.y >= 0.0f ? 1.0f : -1.0f}; }

inline glm::vec2 octahedralEncode(const glm::vec3& n) {
  const glm::vec2 p = glm::vec2(n) / (std::abs(n.x) + std::abs(n.y) + std::abs(n.z));
  return n.z >= 0.0f ? p : (1.0f - glm::abs(glm::vec2(p.y, p.x))) * signNotZero(p);
}

inline glm::vec3 octahedralDecode(const glm::vec2& e) {
  glm::vec3 n(e, 1.0f - std::abs(e.x) - std::abs(e.y));
  if (n.z < 0.0f) {
    const glm::vec2 folded = (1.0f - glm::abs(glm::vec2(n.y, n.x))) * signNotZero(glm::vec2(n));
    n.x = folded.x, n.y = folded.y;
  }
  return glm::normalize(n);
}

struct Clearcoat {
  float factor = 0;     // c, 0..1
  float roughness = 0;  // perceptual, clamped as makeSurface's
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  float nDotV = 1;
  float weight = 0;  // c Fc: the coat's share; the base keeps 1 - weight
};

// lobe_clearcoat.glsl makeClearcoat: `lobe` is the attachment's value
// (factor, roughness, octahedral normal).
inline Clearcoat makeClearcoat(const glm::vec4& lobe, const glm::vec3& view) {
  Clearcoat c;
  c.factor = lobe.r;
  c.roughness = std::max(lobe.g, 0.03f);
  c.normal = octahedralDecode(glm::vec2(lobe.b, lobe.a));
  c.nDotV = std::max(glm::dot(c.normal, view), 1e-4f);
  const float fresnel = 0.04f + 0.96f * std::pow(1.0f - c.nDotV, 5.0f);
  c.weight = c.factor * fresnel;
  return c;
}

// lobe_clearcoat.glsl clearcoatSpecular: the coat's GGX lobe times N_coat . L.
inline float clearcoatSpecular(const Clearcoat& c, const glm::vec3& view, const glm::vec3& toLight) {
  const float nDotL = glm::dot(c.normal, toLight);
  if (nDotL <= 0.0f) return 0.0f;
  const glm::vec3 halfVector = glm::normalize(toLight + view);
  const float nDotH = std::max(glm::dot(c.normal, halfVector), 0.0f);
  const float alpha = c.roughness * c.roughness;
  const float a2 = alpha * alpha;
  const float d = (nDotH * nDotH) * (a2 - 1.0f) + 1.0f;
  return a2 / (kPi * d * d) * smithGgxVisibility(c.nDotV, nDotL, alpha) * nDotL;
}

// lobe_clearcoat.glsl clearcoatLayer.
inline glm::vec3 clearcoatLayer(const Clearcoat& c, const glm::vec3& base, const glm::vec3& coat) {
  return base * (1.0f - c.weight) + coat * c.weight;
}

// lobe_clearcoat_material.glsl clearcoatLobeOfMaterial, given the texels
// the coat's textures give at the point (white where it has none) and the
// coat's normal (the geometric normal where it has no normal map).
inline glm::vec4 clearcoatLobeOfMaterial(const MaterialClearcoat& clearcoat, const glm::vec4& clearcoatTexel,
                                         const glm::vec4& roughnessTexel, const glm::vec3& normal) {
  const glm::vec2 encoded = octahedralEncode(normal);
  return {std::clamp(clearcoat.clearcoatFactor * clearcoatTexel.r, 0.0f, 1.0f),
          std::clamp(clearcoat.clearcoatRoughnessFactor * roughnessTexel.g, 0.0f, 1.0f), encoded.x, encoded.y};
}

// The coat's reflection of the ambient light, before the sky intensity:
// `count` GGX-importance-sampled reflections about the coat's normal, each
// weighted by D Vis N.L / pdf = 4 Vis V.H N.L / N.H (no Fresnel: c Fc
// weighs the result, clearcoatLayer) times `arriving(direction)`, the
// radiance that reaches the point from there (0 where blocked).
template <class Arriving, class Random>
glm::vec3 clearcoatAmbient(const Clearcoat& c, const glm::vec3& view, int count, Random& random,
                           const Arriving& arriving) {
  const float alpha = c.roughness * c.roughness;
  const Basis basis = basisAround(c.normal);
  glm::dvec3 sum(0.0);
  for (int j = 0; j < count; ++j) {
    const float xi0 = random.uniform(), xi1 = random.uniform();
    const glm::vec3 halfVector = basis.toWorld(importanceSampleGgx(xi0, xi1, alpha));
    const float vDotH = glm::dot(view, halfVector);
    const glm::vec3 toLight = 2.0f * vDotH * halfVector - view;  // reflect(-V, H)
    const float nDotL = glm::dot(c.normal, toLight);
    if (nDotL <= 0.0f || vDotH <= 0.0f) continue;
    const float nDotH = std::max(glm::dot(c.normal, halfVector), 1e-7f);
    const float weight = 4.0f * smithGgxVisibility(c.nDotV, nDotL, alpha) * vDotH * nDotL / nDotH;
    sum += glm::dvec3(weight * arriving(glm::normalize(toLight)));
  }
  return glm::vec3(sum / double(std::max(count, 1)));
}

}  // namespace headlight::reference

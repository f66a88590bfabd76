#pragma once
// brdf.glsl's Surface and makeSurface for the CPU ports: a shading point and
// the lobes put on it, each lobe's value in its slot as the GLSL Surface
// holds it (lobes[<NAME>_LOBE_SLOT]; here one slot per Lobe, and a bit for
// the lobes the point has). The lobes' hooks (reference/lobes.hpp) read and
// change it.
#include <algorithm>
#include <array>
#include <cstdint>
#include <glm/glm.hpp>

#include "frame/lobe.hpp"

namespace headlight::reference {

struct Surface {
  glm::vec3 albedo{0.0f};
  float metallic = 0;
  float roughness = 0;
  glm::vec3 normal{0.0f};  // world, unit
  glm::vec3 view{0.0f};    // world, unit, toward the eye
  float nDotV = 0;
  glm::vec3 f0{0.0f};
  float f90 = 1.0f;  // brdf.glsl: 1, or less with the specular lobe's weight (lobe_specular.hpp)
  // KHR_materials_transmission's share: the part of the diffuse lobe its BTDF replaces (lobe_transmission.hpp).
  float transmission = 0.0f;
  // Each lobe's value as its Apply hook leaves it (reference/lobes.hpp
  // applyLobe), read only where `lobes` has the lobe's bit.
  std::array<glm::vec4, kLobeCount> lobeValues{};
  std::uint32_t lobes = 0;

  bool has(Lobe lobe) const { return (lobes & lobeBit(lobe)) != 0; }
  const glm::vec4& value(Lobe lobe) const { return lobeValues[std::size_t(lobe)]; }
};

// A GGX lobe stretched along `tangent` (world, unit, perpendicular to the
// normal): roughness alphaT along it, alphaB across (a lobe's
// stretchedGgx hook, reference/lobes.hpp).
struct StretchedGgx {
  glm::vec3 tangent{0.0f};
  float alphaT = 0.0f, alphaB = 0.0f;
};

// brdf.glsl makeSurface.
inline Surface makeSurface(const glm::vec3& albedo, float metallic, float roughness, const glm::vec3& normal,
                           const glm::vec3& view) {
  Surface s;
  s.albedo = albedo;
  s.metallic = metallic;
  s.roughness = std::max(roughness, 0.03f);  // brdf.glsl: GGX's peak outgrows half floats below 0.03
  s.normal = normal;
  s.view = view;
  s.nDotV = std::max(glm::dot(normal, view), 1e-4f);
  s.f0 = glm::mix(glm::vec3(0.04f), albedo, metallic);  // glTF's dielectric reflectance (IOR 1.5)
  s.f90 = 1.0f;
  return s;
}

}  // namespace headlight::reference

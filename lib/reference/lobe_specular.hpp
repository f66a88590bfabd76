#pragma once
// CPU port of the specular lobe (KHR_materials_specular, KHR_materials_ior):
// glsl/lobe_specular.glsl's hook and
// glsl/lobe_specular_material.glsl's value of a material, with the GLSL's
// names and clamps (shading.hpp says why).
#include <algorithm>
#include <optional>

#include <glm/glm.hpp>

#include "headlight/scene.hpp"
#include "reference/surface.hpp"

namespace headlight::reference {

// The dielectric F0 of `ior` (KHR_materials_ior): ((ior - 1) / (ior + 1))^2;
// 0.04 for glTF's default 1.5, 1 for the specification's 0.
inline float dielectricF0(float ior) {
  const float r = (ior - 1.0f) / (ior + 1.0f);
  return r * r;
}

// lobe_specular_material.glsl specularLobeOfMaterial, given the texels the
// material's textures give at the point (white where it has none).
inline glm::vec4 specularLobeOfMaterial(const Material& material, const glm::vec4& specularTexel,
                                        const glm::vec4& specularColorTexel) {
  const MaterialSpecular specular = material.specular.value_or(MaterialSpecular{});
  const glm::vec3 f0 = dielectricF0(material.ior) * specular.specularColorFactor * glm::vec3(specularColorTexel);
  return {glm::min(f0, glm::vec3(1.0f)), std::clamp(specular.specularFactor * specularTexel.a, 0.0f, 1.0f)};
}

// lobe_specular.glsl's hook: `lobe` is the attachment's value (rgb the
// dielectric F0 colour, a the specular weight); ofMaterial is the
// material's, where it has the lobe (`texel(ref, srgb)`: white without a texture).
struct SpecularLobe {
  static constexpr Lobe kLobe = Lobe::Specular;
  template <class Texel>
  static std::optional<glm::vec4> ofMaterial(const Material& material, const Texel& texel) {
    if (!material.specular && material.ior == 1.5f) return std::nullopt;
    const MaterialSpecular specular = material.specular.value_or(MaterialSpecular{});
    return specularLobeOfMaterial(material, texel(specular.specularTexture, false),
                                  texel(specular.specularColorTexture, true));
  }
  static glm::vec4 apply(Surface& s, const glm::vec4& lobe) {
    const float weight = lobe.a;
    s.f0 = glm::mix(glm::vec3(lobe) * weight, s.albedo, s.metallic);
    s.f90 = weight + (1.0f - weight) * s.metallic;  // GLSL mix(weight, 1.0, metallic)
    return lobe;
  }
};

}  // namespace headlight::reference

#pragma once
// The CPU ports' lobes composed as brdf.glsl and ambient.glsl compose the
// GLSL ones: each port (lobe_<name>.hpp) is a struct with the hooks of its
// GLSL file under the same names (apply, fresnel, specularTerm, layerScale,
// layerLight, albedoRoughness, specularAlbedo), plus what only the Embree reference asks
// (stretchedGgx: the half vectors its estimator draws), and LobePorts below
// is the one list of them. A composition calls a hook for every lobe of the
// surface whose port has it; a port without the hook is skipped at compile
// time (docs/PIPELINE.md, "What a lobe is made of").
#include <cmath>
#include <cstddef>
#include <glm/glm.hpp>
#include <optional>
#include <tuple>
#include <type_traits>

#include "reference/lobe_anisotropy.hpp"
#include "reference/lobe_iridescence.hpp"
#include "reference/lobe_sheen.hpp"
#include "reference/lobe_specular.hpp"
#include "reference/surface.hpp"

namespace headlight::reference {

// Every lobe with hooks, one row each (clearcoat, a layer with its own
// normal, is composed by the passes and the tracer themselves).
using LobePorts = std::tuple<SpecularLobe, SheenLobe, AnisotropyLobe, IridescenceLobe>;

// `visit(port)` for a value-initialised port of each type of LobePorts
// whose lobe the surface has.
template <class Visit>
void forEachLobe(const Surface& s, Visit&& visit) {
  std::apply([&](auto... ports) { ((s.has(decltype(ports)::kLobe) ? visit(ports) : void()), ...); }, LobePorts{});
}

// surface.glsl applyLobes for one lobe: its value in its slot, through its
// Apply hook where it has one. `value` is its G-buffer target's texel, or
// what its material gives (lobe_<name>_material.glsl).
inline void applyLobe(Surface& s, Lobe lobe, const glm::vec4& value) {
  s.lobes |= lobeBit(lobe);
  s.lobeValues[std::size_t(lobe)] = value;
  std::apply(
      [&](auto... ports) {
        auto one = [&](auto port) {
          using Port = decltype(port);
          if constexpr (requires { Port::apply(s, value); })
            if (Port::kLobe == lobe) s.lobeValues[std::size_t(lobe)] = Port::apply(s, value);
        };
        (one(ports), ...);
      },
      LobePorts{});
}

// surface.glsl applyMaterialLobes: each lobe's value from the material
// (its port's ofMaterial, lobe_<name>_material.glsl's) on the surface, for
// the lobes the material has. `texel(ref, srgb)`: the texture at the point,
// white where there is none. Anisotropy has no port of its material (its
// direction needs the tangent frame): a blended anisotropic hit is shaded
// isotropic (docs/ACCURACY.md).
template <class Texel>
void applyMaterialLobes(Surface& s, const Material& material, const Texel& texel) {
  std::apply(
      [&](auto... ports) {
        auto one = [&](auto port) {
          using Port = decltype(port);
          if constexpr (requires { Port::ofMaterial(material, texel); })
            if (const std::optional<glm::vec4> value = Port::ofMaterial(material, texel))
              applyLobe(s, Port::kLobe, *value);
        };
        (one(ports), ...);
      },
      LobePorts{});
}

// brdf.glsl's LOBES_FRESNEL: `fresnel` (Schlick's) as the lobes change it (an iridescent film's).
inline glm::vec3 lobesFresnel(const Surface& s, glm::vec3 fresnel) {
  forEachLobe(s, [&]<class Port>(Port) {
    if constexpr (requires { Port::fresnel(s, glm::vec4(), fresnel); })
      fresnel = Port::fresnel(s, s.value(Port::kLobe), fresnel);
  });
  return fresnel;
}

// brdf.glsl surfaceFresnel: Schlick's over f0 and f90, then the lobes'.
inline glm::vec3 surfaceFresnel(const Surface& s, float vDotH) {
  return lobesFresnel(s, s.f0 + (s.f90 - s.f0) * std::pow(1.0f - vDotH, 5.0f));
}

// brdf.glsl cookTorrance's D Vis, as the lobes replace GGX's (anisotropy).
inline float lobesSpecularTerm(const Surface& s, float term, float alpha, const glm::vec3& toLight,
                               const glm::vec3& halfVector, float nDotL) {
  forEachLobe(s, [&]<class Port>(Port) {
    if constexpr (requires { Port::specularTerm(s, glm::vec4(), term, alpha, toLight, halfVector, nDotL); })
      term = Port::specularTerm(s, s.value(Port::kLobe), term, alpha, toLight, halfVector, nDotL);
  });
  return term;
}

// brdf.glsl baseLayerScale: what the layers over the base (sheen) leave of
// the light it sends from a direction at `nDotL` (absolute); 1 without.
inline float baseLayerScale(const Surface& s, float nDotL) {
  float scale = 1.0f;
  forEachLobe(s, [&]<class Port>(Port) {
    if constexpr (requires { Port::layerScale(s, glm::vec4(), nDotL); })
      scale *= Port::layerScale(s, s.value(Port::kLobe), nDotL);
  });
  return scale;
}

// brdf.glsl cookTorrance's LOBES_LAYER_LIGHT: the layers' own light toward
// the eye from a direction at `nDotL` (> 0), N.L included.
inline glm::vec3 layersLight(const Surface& s, float nDotL, float nDotH) {
  glm::vec3 light(0.0f);
  forEachLobe(s, [&]<class Port>(Port) {
    if constexpr (requires { Port::layerLight(s, glm::vec4(), nDotL, nDotH); })
      light += Port::layerLight(s, s.value(Port::kLobe), nDotL, nDotH);
  });
  return light;
}

// Whether a lobe of the surface layers light of its own (its ambient share
// is then estimated over the hemisphere: Tracer::layersAmbient).
inline bool hasLayerLight(const Surface& s) {
  bool any = false;
  forEachLobe(s, [&]<class Port>(Port) {
    if constexpr (requires { Port::layerLight(s, glm::vec4(), 0.0f, 0.0f); }) any = true;
  });
  return any;
}

// ambient.glsl specularAlbedoOf's LOBES_ALBEDO_ROUGHNESS: the split-sum
// table's roughness for `roughness` (the renderer's; the reference samples
// the lobe itself and needs none).
inline float lobesAlbedoRoughness(const Surface& s, float roughness) {
  forEachLobe(s, [&]<class Port>(Port) {
    if constexpr (requires { Port::albedoRoughness(s, glm::vec4(), roughness); })
      roughness = Port::albedoRoughness(s, s.value(Port::kLobe), roughness);
  });
  return roughness;
}

// ambient.glsl specularAlbedoOf's LOBES_SPECULAR_ALBEDO: the split-sum
// result `albedo` (f0 scale + f90 bias) as the lobes change it.
inline glm::vec3 lobesSpecularAlbedo(const Surface& s, glm::vec3 albedo, const glm::vec2& scaleBias) {
  forEachLobe(s, [&]<class Port>(Port) {
    if constexpr (requires { Port::specularAlbedo(s, glm::vec4(), albedo, scaleBias); })
      albedo = Port::specularAlbedo(s, s.value(Port::kLobe), albedo, scaleBias);
  });
  return albedo;
}

// The GGX lobe the reference's estimator draws half vectors from, where a
// lobe stretches it (anisotropy); none: the isotropic one about the normal.
inline std::optional<StretchedGgx> lobesStretchedGgx(const Surface& s, float alpha) {
  std::optional<StretchedGgx> stretched;
  forEachLobe(s, [&]<class Port>(Port) {
    if constexpr (requires { Port::stretchedGgx(s, glm::vec4(), alpha); })
      if (!stretched) stretched = Port::stretchedGgx(s, s.value(Port::kLobe), alpha);
  });
  return stretched;
}

}  // namespace headlight::reference

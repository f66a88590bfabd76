#pragma once
// CPU port of glsl/lobe_iridescence.glsl (KHR_materials_iridescence's
// thin-film Fresnel, Belcour & Barla 2017 as the specification states it),
// for the Embree reference and the parity tests. Same names, constants and
// clamps as the GLSL; pure functions.
#include <algorithm>
#include <cmath>
#include <glm/glm.hpp>

#include <optional>

#include "headlight/frame.hpp"
#include "headlight/scene.hpp"
#include "reference/surface.hpp"
#include "shared_layout.h"

namespace headlight::reference {

// The iridescence lobe's G-buffer attachment, iridescence.exr's channels
// (glsl/lobe_iridescence_material.glsl writes it).
struct IridescenceInputs {
  float strength = 0.0f;     // iridescenceFactor x texture R: 0 = no film
  float thicknessNm = 0.0f;  // the film's thickness, nm
  float filmIor = 1.3f;      // iridescenceIor
  float baseIor = 1.5f;      // Material::ior
};

using gpu::kMaxFilmThicknessNm;
using gpu::kMaxIridescenceIor;

// Pixel (x, y) of frame.iridescence; no film where the frame has none.
inline IridescenceInputs iridescenceInputsAt(const Frame& frame, int x, int y) {
  const ImageF& image = frame.iridescence;
  if (image.empty() || image.channelCount() < 4) return {};
  return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2), image.at(x, y, 3)};
}

inline float thinFilmIorToFresnel0(float transmittedIor, float incidentIor) {
  const float r = (transmittedIor - incidentIor) / (transmittedIor + incidentIor);
  return r * r;
}

inline glm::vec3 thinFilmIorToFresnel0(const glm::vec3& transmittedIor, float incidentIor) {
  const glm::vec3 r = (transmittedIor - incidentIor) / (transmittedIor + incidentIor);
  return r * r;
}

inline glm::vec3 thinFilmFresnel0ToIor(const glm::vec3& f0) {
  const glm::vec3 root = glm::sqrt(f0);
  return (1.0f + root) / (1.0f - root);
}

inline glm::vec3 thinFilmSchlick(const glm::vec3& f0, float cosTheta) {
  return f0 + (1.0f - f0) * std::pow(std::max(1.0f - cosTheta, 0.0f), 5.0f);
}

// lobe_iridescence.glsl thinFilmSensitivity: one Fourier term through the
// CIE XYZ fits, as linear Rec.709.
inline glm::vec3 thinFilmSensitivity(float opdNm, const glm::vec3& shift) {
  constexpr float kTwoPi = 2.0f * 3.14159265358979f;
  const float phase = kTwoPi * opdNm * 1.0e-9f;
  const glm::vec3 amplitude(5.4856e-13f, 4.4201e-13f, 5.2481e-13f);
  const glm::vec3 mean(1.6810e+06f, 1.7953e+06f, 2.2084e+06f);
  const glm::vec3 variance(4.3278e+09f, 9.3046e+09f, 6.6121e+09f);
  glm::vec3 xyz = amplitude * glm::sqrt(kTwoPi * variance) * glm::cos(mean * phase + shift) *
                  glm::exp(-(phase * phase) * variance);
  xyz.x += 9.7470e-14f * std::sqrt(kTwoPi * 4.5282e+09f) * std::cos(2.2399e+06f * phase + shift.x) *
           std::exp(-4.5282e+09f * (phase * phase));
  xyz /= 1.0685e-7f;
  return {glm::dot(glm::vec3(3.2404542f, -1.5371385f, -0.4985314f), xyz),
          glm::dot(glm::vec3(-0.9692660f, 1.8760108f, 0.0415560f), xyz),
          glm::dot(glm::vec3(0.0556434f, -0.2040259f, 1.0572252f), xyz)};
}

inline float thinFilmSmoothstep(float edge0, float edge1, float x) {
  const float t = std::clamp((x - edge0) / (edge1 - edge0), 0.0f, 1.0f);
  return t * t * (3.0f - 2.0f * t);
}

// lobe_iridescence.glsl thinFilmFresnel: F_iridescence of the specification.
inline glm::vec3 thinFilmFresnel(float outsideIor, float filmIor, float cosTheta1, float thicknessNm,
                                 const glm::vec3& baseF0) {
  constexpr float kPiF = 3.14159265358979f;
  const float eta2 = glm::mix(outsideIor, filmIor, thinFilmSmoothstep(0.0f, 0.03f, thicknessNm));
  const float ratio = outsideIor / eta2;
  const float cosTheta2Squared = 1.0f - ratio * ratio * (1.0f - cosTheta1 * cosTheta1);
  if (cosTheta2Squared < 0.0f) return glm::vec3(1.0f);
  const float cosTheta2 = std::sqrt(cosTheta2Squared);

  const float r12 = thinFilmSchlick(glm::vec3(thinFilmIorToFresnel0(eta2, outsideIor)), cosTheta1).x;
  const float t121 = 1.0f - r12;
  const float phi21 = kPiF - (eta2 < outsideIor ? kPiF : 0.0f);
  const glm::vec3 baseIor = thinFilmFresnel0ToIor(glm::clamp(baseF0, 0.0f, 0.9999f));
  const glm::vec3 r23 = thinFilmSchlick(thinFilmIorToFresnel0(baseIor, eta2), cosTheta2);
  glm::vec3 phi23(0.0f);
  for (int c = 0; c < 3; ++c) phi23[c] = baseIor[c] < eta2 ? kPiF : 0.0f;

  const float opd = 2.0f * eta2 * thicknessNm * cosTheta2;
  const glm::vec3 phi = phi21 + phi23;
  const glm::vec3 r123Squared = glm::clamp(r12 * r23, 1e-5f, 0.9999f);
  const glm::vec3 r123 = glm::sqrt(r123Squared);
  const glm::vec3 rs = t121 * t121 * r23 / (1.0f - r123Squared);
  glm::vec3 reflectance = r12 + rs;
  glm::vec3 cm = rs - t121;
  for (int m = 1; m <= 2; ++m) {
    cm *= r123;
    reflectance += cm * 2.0f * thinFilmSensitivity(float(m) * opd, float(m) * phi);
  }
  return glm::max(reflectance, glm::vec3(0.0f));
}

// lobe_iridescence.glsl iridescenceFresnel: the film on glTF's dielectric
// and metal bases, mixed by metallic.
inline glm::vec3 iridescenceFresnel(const IridescenceInputs& inputs, const glm::vec3& albedo, float metallic,
                                    float nDotV) {
  const float thickness = std::clamp(inputs.thicknessNm, 0.0f, kMaxFilmThicknessNm);
  const float filmIor = std::clamp(inputs.filmIor, 1.0f, kMaxIridescenceIor);
  if (metallic >= 1.0f) return thinFilmFresnel(1.0f, filmIor, nDotV, thickness, albedo);
  const float baseF0 = thinFilmIorToFresnel0(std::clamp(inputs.baseIor, 0.0f, kMaxIridescenceIor), 1.0f);
  const glm::vec3 dielectric = thinFilmFresnel(1.0f, filmIor, nDotV, thickness, glm::vec3(baseF0));
  if (metallic <= 0.0f) return dielectric;
  return glm::mix(dielectric, thinFilmFresnel(1.0f, filmIor, nDotV, thickness, albedo), metallic);
}

// lobe_iridescence.glsl's hooks. The G-buffer holds the film (strength,
// thickness, film IOR, base IOR); apply turns it into what the Surface
// keeps: the film's Fresnel at N.V (rgb) and its strength (a).
struct IridescenceLobe {
  static constexpr Lobe kLobe = Lobe::Iridescence;
  // lobe_iridescence_material.glsl iridescenceLobeOfMaterial (`texel(ref,
  // srgb)`: white without a texture): strength, thickness, film IOR, base IOR.
  template <class Texel>
  static std::optional<glm::vec4> ofMaterial(const Material& material, const Texel& texel) {
    if (!material.iridescence) return std::nullopt;
    const MaterialIridescence& film = *material.iridescence;
    const float strength = film.iridescenceFactor * texel(film.iridescenceTexture, false).r;
    // Without a thickness texture the film is the maximum thick (the specification).
    const float thickness = film.iridescenceThicknessTexture.present()
                                ? glm::mix(film.iridescenceThicknessMinimum, film.iridescenceThicknessMaximum,
                                           texel(film.iridescenceThicknessTexture, false).g)
                                : film.iridescenceThicknessMaximum;
    return glm::vec4(std::clamp(strength, 0.0f, 1.0f), std::clamp(thickness, 0.0f, kMaxFilmThicknessNm),
                     std::min(film.iridescenceIor, kMaxIridescenceIor), std::min(material.ior, kMaxIridescenceIor));
  }
  static glm::vec4 apply(Surface& s, const glm::vec4& film) {
    const float strength = std::clamp(film.x, 0.0f, 1.0f);
    const IridescenceInputs inputs{film.x, film.y, film.z, film.w};
    return {strength > 0.0f ? iridescenceFresnel(inputs, s.albedo, s.metallic, s.nDotV) : glm::vec3(0.0f), strength};
  }
  static glm::vec3 fresnel(const Surface&, const glm::vec4& film, const glm::vec3& fresnel) {
    return glm::mix(fresnel, glm::vec3(film), film.a);
  }
  static glm::vec3 specularAlbedo(const Surface&, const glm::vec4& film, const glm::vec3& albedo,
                                  const glm::vec2& scaleBias) {
    return glm::mix(albedo, glm::vec3(film) * (scaleBias.x + scaleBias.y), film.a);
  }
};

// A film as the G-buffer's texel holds it (for applyLobe).
inline glm::vec4 filmValue(const IridescenceInputs& film) {
  return {film.strength, film.thicknessNm, film.filmIor, film.baseIor};
}

}  // namespace headlight::reference

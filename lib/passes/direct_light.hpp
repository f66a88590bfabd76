#pragma once
// The direct-light pass: every punctual light (glTF units and range falloff,
// PCF-filtered shadows where a map exists) plus emission, from the G-buffer.
//   target 0 GL_RGBA16F  radiance toward the eye (Cook-Torrance GGX)
//   target 1 GL_RGBA16F  Lambertian radiance leaving the surface, for the SSGI
//                        `radiance` method to gather; made only when asked
// Background pixels stay 0.
#include "gl/objects.hpp"
#include "passes/fullscreen.hpp"
#include "passes/gbuffer.hpp"
#include "passes/shadow.hpp"

namespace headlight {

struct DirectLightInputs {
  const GBuffer& gbuffer;     // position, normal, albedo, material; emissive if it has one
  const ShadowMaps& shadows;  // empty maps: no shadows
};

struct DirectLightTargets {
  gl::Texture towardEye;  // always
  gl::Texture diffuse;    // only for the SSGI radiance method; empty otherwise
};

struct DirectLightVariant {
  bool emissive, planarShadows, cubeShadows, diffuseTarget;
  auto operator<=>(const DirectLightVariant&) const = default;
};

class DirectLightPass : public FullscreenPass<DirectLightVariant> {
 public:
  using Variant = DirectLightVariant;
  // The one rule for which program a frame uses, whether the frame is here
  // (run) or predicted from the scene (the renderer's prepare).
  static Variant variantFor(bool emissive, const ShadowCasters& casters, bool diffuseTarget) {
    return {emissive, casters.planar > 0, casters.cube > 0, diffuseTarget};
  }

  DirectLightPass();
  // The lighting block (light count, PCF radius) and the light buffer must be
  // bound.
  void run(const DirectLightInputs& inputs, const DirectLightTargets& targets);
};

}  // namespace headlight

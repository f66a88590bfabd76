#pragma once
// The direct-light pass: every punctual light (glTF units and range falloff,
// PCF-filtered shadows where a map exists) plus emission, from the G-buffer.
//   towardEye GL_RGBA16F  radiance toward the eye (Cook-Torrance GGX)
//   diffuse   GL_RGBA16F  Lambertian radiance leaving the surface, for the SSGI
//                         methods to gather; made only when asked
// Background pixels are 0. Body: glsl/direct_light.glsl, in either form.
#include "frame/frame_plan.hpp"
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
  const gl::Texture& towardEye;
  const gl::Texture* diffuse;  // only for the SSGI methods that gather direct light (DirectLightVariant::diffuseTarget)
};

class DirectLightPass : public FullscreenPass<DirectLightVariant> {
 public:
  using Variant = DirectLightVariant;  // the frame plan's choice
  DirectLightPass();
  // The lighting block (light count, PCF radius) and the light buffer must be
  // bound.
  void run(const DirectLightInputs& inputs, const DirectLightTargets& targets, const Variant& variant, PassForm form);
};

}  // namespace headlight

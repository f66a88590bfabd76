#pragma once
// The direct-light pass: every punctual light (glTF units and range falloff,
// PCF-filtered shadows where a map exists) plus emission, from the G-buffer.
//   reads  the G-buffer's surface (position, normal, albedo, material, its
//          lobes), its emission where the scene glows; the shadow maps
//   writes direct.towardEye  radiance toward the eye (Cook-Torrance GGX)
//          direct.diffuse    Lambertian radiance leaving the surface, for the
//                            SSGI methods that gather it; only for them
// Background pixels are 0. Body: glsl/direct_light.glsl, in either form.
#include <optional>

#include "frame/frame_plan.hpp"
#include "passes/frame_pass.hpp"
#include "passes/fullscreen.hpp"

namespace headlight {

// Variants: the plan's DirectLightVariant. The lighting block (light count,
// PCF radius) and the light buffer must be bound.
class DirectLightPass final : public FramePass, FullscreenPass<DirectLightVariant> {
 public:
  DirectLightPass();
  void execute(const FrameInputs& inputs, const PassAttachments& attachments, PassForm form) override;
};

}  // namespace headlight

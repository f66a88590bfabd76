#pragma once
// The composite pass: direct light + image-based ambient from the procedural
// sky (split-sum, tables from EnvironmentPass), occluded by the material's
// occlusion and the SSGI's sky visibility, + the SSGI's indirect term:
//   ambient = (diffuse_ibl + specular_ibl) * material_ao * ssgi_sky + ssgi_indirect + ssgi_indirect_far
// (the seed's ssgi_ao there: the hemisphere and radiance methods write their
// AO within R as ssgi_sky, so their images are the seed's).
//   reads  the G-buffer's surface, direct.towardEye, the blurred SSGI (with
//          SSGI on), the ambient tables (with the sky term)
//   writes lit  linear radiance; background pixels get the sky, alpha 0
// Body: glsl/composite.glsl, in either form.
#include <optional>

#include "frame/frame_plan.hpp"
#include "passes/frame_pass.hpp"
#include "passes/fullscreen.hpp"

namespace headlight {

// Variants: the plan's CompositeVariant: with SSGI or without (ambient then
// unoccluded but for the material's occlusion); with the sky term or without
// (sky intensity 0: the image-based ambient and the background are then
// exactly 0, and the tables are not read). The lighting block must be bound.
class CompositePass final : public FramePass, FullscreenPass<CompositeVariant> {
 public:
  CompositePass();
  void execute(const FrameInputs& inputs, const PassAttachments& attachments, PassForm form) override;
};

}  // namespace headlight

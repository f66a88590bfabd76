#pragma once
// The composite pass: direct light + image-based ambient from the procedural
// sky (split-sum, tables from EnvironmentPass), occluded by the material's
// occlusion and the SSGI's sky visibility, + the SSGI's indirect term:
//   ambient = (diffuse_ibl + specular_ibl) * material_ao * ssgi_sky + ssgi_indirect + ssgi_indirect_far
// (the seed's ssgi_ao there: the hemisphere and radiance methods write their
// AO within R as ssgi_sky, so their images are the seed's).
// Output GL_RGBA16F linear radiance; background pixels get the sky, alpha 0.
// Body: glsl/composite.glsl, in either form.
#include "frame/frame_plan.hpp"
#include "gl/objects.hpp"
#include "passes/environment.hpp"
#include "passes/fullscreen.hpp"
#include "passes/gbuffer.hpp"
#include "passes/ssgi_textures.hpp"

namespace headlight {

struct CompositeInputs {
  const GBuffer& gbuffer;                // position, normal, albedo, material
  const gl::Texture& direct;             // DirectLightTargets::towardEye
  const SsgiTextures* ssgi;              // blurred SSGI; null with SSGI off (ambient then unoccluded but for
                                         // the material's occlusion)
  const EnvironmentTables& environment;  // read only by the variant with the sky term
};

class CompositePass : public FullscreenPass<CompositeVariant> {
 public:
  // With SSGI or without (ambient then unoccluded but for the material's
  // occlusion); with the sky term or without (sky intensity 0: the
  // image-based ambient and the background are then exactly 0, and the sky
  // tables are not read). The frame plan chooses.
  using Variant = CompositeVariant;
  CompositePass();
  // The lighting block must be bound (sky intensity).
  void run(const CompositeInputs& inputs, const gl::Texture& output, const Variant& variant, PassForm form);
};

}  // namespace headlight

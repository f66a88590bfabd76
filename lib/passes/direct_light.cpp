#include "passes/direct_light.hpp"

#include "shared_layout.h"

namespace headlight {

DirectLightPass::DirectLightPass()
    : FullscreenPass("direct_light.glsl", [](const Variant& variant) {
        std::vector<std::string> defines;
        if (variant.emissive) defines.emplace_back("HAS_EMISSIVE");
        if (variant.planarShadows) defines.emplace_back("HAS_PLANAR_SHADOWS");
        if (variant.cubeShadows) defines.emplace_back("HAS_CUBE_SHADOWS");
        if (variant.diffuseTarget) defines.emplace_back("WRITE_DIFFUSE_RADIANCE");
        for (std::string& define : lobeDefines(variant.lobes)) defines.push_back(std::move(define));
        return defines;
      }) {}

void DirectLightPass::run(const DirectLightInputs& inputs, const DirectLightTargets& targets, const Variant& variant,
                          PassForm form) {
  const GBuffer& gbuffer = inputs.gbuffer;
  const ShadowMaps& shadows = inputs.shadows;
  gbuffer.position.bind(gpu::kUnitGbufferPosition);
  gbuffer.normal.bind(gpu::kUnitGbufferNormal);
  gbuffer.albedo.bind(gpu::kUnitGbufferAlbedo);
  gbuffer.material.bind(gpu::kUnitGbufferMaterial);
  if (variant.emissive) gbuffer.emissive.bind(gpu::kUnitGbufferEmissive);
  if (variant.planarShadows) shadows.planar.bind(gpu::kUnitShadowMaps2D);
  if (variant.cubeShadows) shadows.cube.bind(gpu::kUnitShadowMapsCube);
  const PassOutput outputs[] = {{"towardEye", &targets.towardEye}, {"diffuse", targets.diffuse}};
  FullscreenPass::run("direct light", variant, form, std::span(outputs, variant.diffuseTarget ? 2 : 1));
}

}  // namespace headlight

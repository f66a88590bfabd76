#include "passes/composite.hpp"

#include "shared_layout.h"

namespace headlight {

CompositePass::CompositePass()
    : FullscreenPass("composite.glsl", [](const Variant& variant) {
        std::vector<std::string> defines;
        if (variant.ssgi) defines.emplace_back("HAS_SSGI");
        if (variant.sky) defines.emplace_back("HAS_SKY");
        if (variant.environment) defines.emplace_back("HAS_ENVIRONMENT");
        for (std::string& define : lobeDefines(variant.lobes)) defines.push_back(std::move(define));
        return defines;
      }) {}

void CompositePass::run(const CompositeInputs& inputs, const gl::Texture& output, const Variant& variant,
                        PassForm form) {
  inputs.gbuffer.position.bind(gpu::kUnitGbufferPosition);
  inputs.gbuffer.normal.bind(gpu::kUnitGbufferNormal);
  inputs.gbuffer.albedo.bind(gpu::kUnitGbufferAlbedo);
  inputs.gbuffer.material.bind(gpu::kUnitGbufferMaterial);
  inputs.direct.bind(gpu::kUnitDirect);
  if (variant.ssgi) {
    inputs.ssgi->occlusion.bind(gpu::kUnitSsgi);
    inputs.ssgi->sky.bind(gpu::kUnitSsgiSky);
    inputs.ssgi->specular.bind(gpu::kUnitSsgiSpecular);
  }
  bindAmbientTables(inputs.environment, variant.sky, variant.environment);
  const PassOutput outputs[] = {{"radiance", &output}};
  FullscreenPass::run("composite", variant, form, outputs);
}

}  // namespace headlight

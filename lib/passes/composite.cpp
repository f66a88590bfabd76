#include "passes/composite.hpp"

#include "shared_layout.h"

namespace headlight {

CompositePass::CompositePass()
    : FullscreenPass("composite.frag", [](bool withSsgi) {
        return withSsgi ? std::vector<std::string>{"HAS_SSGI"} : std::vector<std::string>{};
      }) {}

void CompositePass::run(const CompositeInputs& inputs, const gl::Texture& output) {
  inputs.gbuffer.position.bind(gpu::kUnitGbufferPosition);
  inputs.gbuffer.normal.bind(gpu::kUnitGbufferNormal);
  inputs.gbuffer.albedo.bind(gpu::kUnitGbufferAlbedo);
  inputs.gbuffer.material.bind(gpu::kUnitGbufferMaterial);
  inputs.direct.bind(gpu::kUnitDirect);
  if (inputs.ssgi) {
    inputs.ssgi->occlusion.bind(gpu::kUnitSsgi);
    inputs.ssgi->sky.bind(gpu::kUnitSsgiSky);
  }
  inputs.environment.brdfLut.bind(gpu::kUnitBrdfLut);
  inputs.environment.skyPrefiltered.bind(gpu::kUnitSkyPrefiltered);
  inputs.environment.skyIrradiance.bind(gpu::kUnitSkyIrradiance);
  draw("composite", inputs.ssgi != nullptr, output);
}

}  // namespace headlight

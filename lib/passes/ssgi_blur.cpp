#include "passes/ssgi_blur.hpp"

#include "shared_layout.h"

namespace headlight {

SsgiBlurPass::SsgiBlurPass()
    : program_(buildFullscreenProgram("ssgi_blur.frag")), block_(gl::Buffer::create(sizeof(gpu::SsgiBlurBlock))) {}

void SsgiBlurPass::run(const SsgiBlurInputs& inputs, const SsgiTextures& output) {
  gpu::SsgiBlurBlock block{};
  block.ssgiRadiusWorld = inputs.ssgiRadiusWorld;
  block.ssgiDownsample = inputs.ssgiDownsample;
  block_.update(block);
  block_.bindUniform(gpu::SsgiBlurBlock::kBinding);
  inputs.gbuffer.position.bind(gpu::kUnitGbufferPosition);
  inputs.gbuffer.normal.bind(gpu::kUnitGbufferNormal);
  inputs.rawSsgi.occlusion.bind(gpu::kUnitSsgi);
  inputs.rawSsgi.sky.bind(gpu::kUnitSsgiSky);
  inputs.rawSsgi.specular.bind(gpu::kUnitSsgiSpecular);
  const glm::vec4 background(1.0f, 0.0f, 0.0f, 0.0f);  // as the SSGI pass leaves it
  const gl::Texture* outputs[] = {&output.occlusion, &output.sky, &output.specular};
  draw_.draw("SSGI blur", program_, outputs, background);
}

}  // namespace headlight

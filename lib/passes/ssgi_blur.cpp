#include "passes/ssgi_blur.hpp"

#include "shared_layout.h"

namespace headlight {

SsgiBlurPass::SsgiBlurPass()
    : program_(buildFullscreenProgram("ssgi_blur.frag")), block_(gl::Buffer::create(sizeof(gpu::SsgiBlurBlock))) {}

void SsgiBlurPass::run(const SsgiBlurInputs& inputs, const gl::Texture& output) {
  gpu::SsgiBlurBlock block{};
  block.ssgiRadiusWorld = inputs.ssgiRadiusWorld;
  block.ssgiDownsample = inputs.ssgiDownsample;
  block_.update(block);
  block_.bindUniform(gpu::SsgiBlurBlock::kBinding);
  inputs.gbuffer.position.bind(gpu::kUnitGbufferPosition);
  inputs.gbuffer.normal.bind(gpu::kUnitGbufferNormal);
  inputs.rawSsgi.bind(gpu::kUnitSsgi);
  const glm::vec4 background(1.0f, 0.0f, 0.0f, 0.0f);  // as the SSGI pass leaves it
  draw_.draw("SSGI blur", program_, output, background);
}

}  // namespace headlight

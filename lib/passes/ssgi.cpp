#include "passes/ssgi.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "frame/frame_plan.hpp"
#include "gl/shader_library.hpp"
#include "headlight/error.hpp"
#include "settings/setting_fields.hpp"
#include "shared_layout.h"

namespace headlight {
namespace {

// Uniform in [0, 1) from the top 24 bits: std::uniform_real_distribution's
// output is not specified across standard libraries, this is.
float uniform01(std::mt19937& rng) { return float(rng() >> 8) * (1.0f / 16777216.0f); }

}  // namespace

std::vector<glm::vec3> makeSsgiKernel(int sampleCount, unsigned seed) {
  std::mt19937 rng(seed);
  std::vector<glm::vec3> kernel;
  kernel.reserve(std::size_t(sampleCount));
  for (int i = 0; i < sampleCount; ++i) {
    // Malley's method: a uniform point on the unit disc lifted to the
    // hemisphere gives directions with density cos(theta) / pi.
    const float u1 = uniform01(rng), u2 = uniform01(rng), u3 = uniform01(rng);
    const float discRadius = std::sqrt(u1), phi = 6.2831853f * u2;
    const glm::vec3 direction(discRadius * std::cos(phi), discRadius * std::sin(phi), std::sqrt(1.0f - u1));
    const float t = float(i) / float(sampleCount);
    const float scale = 0.1f + 0.9f * t * t;  // lerp(0.1, 1.0, t^2)
    kernel.push_back(direction * (u3 * scale));
  }
  return kernel;
}

std::array<glm::vec2, 16> makeSsgiNoise(unsigned seed) {
  std::mt19937 rng(seed ^ 0x9e3779b9u);  // not the kernel's stream
  std::array<glm::vec2, 16> noise;
  for (auto& rotation : noise) {
    const float angle = 6.2831853f * uniform01(rng);
    rotation = glm::vec2(std::cos(angle), std::sin(angle));
  }
  return noise;
}

SsgiPass::SsgiPass()
    : FullscreenPass("ssgi.glsl",
                     [](const SsgiMethod& method) {
                       const std::string_view define = ssgiMethodTraits(method).kernelDefine;
                       return define.empty() ? std::vector<std::string>{}
                                             : std::vector<std::string>{std::string(define)};
                     }),
      blockBuffer_(gl::Buffer::create(sizeof(gpu::SsgiBlock))),
      noise_(gl::Texture::create2D(GL_RG16F, 4, 4)) {}

void SsgiPass::updateKernel(int sampleCount, unsigned seed) {
  if (sampleCount == block_.sampleCount && seed == kernelSeed_) return;
  const auto kernel = makeSsgiKernel(sampleCount, seed);
  for (std::size_t i = 0; i < std::size(block_.kernel); ++i)
    block_.kernel[i] = i < kernel.size() ? glm::vec4(kernel[i], 0.0f) : glm::vec4(0.0f);
  const auto noise = makeSsgiNoise(seed);
  glTextureSubImage2D(noise_.id(), 0, 0, 0, 4, 4, GL_RG, GL_FLOAT, noise.data());
  block_.sampleCount = sampleCount;
  kernelSeed_ = seed;
}

void SsgiPass::execute(const FrameInputs& frame, const PassAttachments& attachments, PassForm form) {
  const SsgiStep& step = *frame.plan.ssgi;
  SsgiInputs inputs{frame.settings};
  inputs.downsample = step.downsample;
  inputs.farDownsample = step.farDownsample;
  if (step.virtualLights > 0) {
    inputs.virtualLights = &frame.virtualLights;
    if (step.lightFieldProbes > 0 && frame.lightField.grid.probeCount() > 0) inputs.lightField = &frame.lightField;
    inputs.shadows = &frame.shadows;
    inputs.emissive = attachments.declaresRead(Attachment::GbufferEmissive);
  }
  inputs.form = form;
  const SsgiTextures output =
      step.blur ? SsgiTextures{attachments.write(Attachment::SsgiRaw), attachments.write(Attachment::SsgiRawSky),
                               attachments.write(Attachment::SsgiRawSpecular)}
                : SsgiTextures{attachments.write(Attachment::Ssgi), attachments.write(Attachment::SsgiSky),
                               attachments.write(Attachment::SsgiSpecular)};
  for (int index = 0; index < step.frames; ++index) {
    inputs.frameIndex = index;
    if (step.frames > 1) inputs.accumulateWeight = index == 0 ? 0.0f : 1.0f / float(index + 1);
    run(inputs, output);
  }
}

void SsgiPass::run(const SsgiInputs& inputs, const SsgiTextures& output) {
  const SsgiSettings& settings = inputs.settings.ssgi;
  const SsgiMethodTraits& method = ssgiMethodTraits(settings.method);
  if (method.program == SsgiProgram::Bitmask) {
    if (!bitmask_) bitmask_.emplace();
    bitmask_->run(inputs, output);
    return;
  }
  updateKernel(settings.sampleCount, settings.seed);
  fillSettingFields(block_, inputs.settings);
  block_.downsample = inputs.downsample;
  blockBuffer_.update(block_);
  blockBuffer_.bindUniform(gpu::SsgiBlock::kBinding);
  noise_.bind(gpu::kUnitSsgiNoise);
  const PassOutput outputs[] = {{"nearField", &output.occlusion}, {"sky", &output.sky}, {"specular", &output.specular}};
  FullscreenPass::run("SSGI", settings.method, inputs.form, outputs, inputs.accumulateWeight);
}

}  // namespace headlight

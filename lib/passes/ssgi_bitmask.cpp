#include "passes/ssgi_bitmask.hpp"

#include "passes/ssgi.hpp"

#include "settings/setting_fields.hpp"
#include "shared_layout.h"

namespace headlight {

SsgiBitmaskPass::SsgiBitmaskPass()
    : FullscreenPass("ssgi_bitmask.glsl",
                     [](const SsgiBitmaskVariant& variant) {
                       std::vector<std::string> defines;
                       appendShadowDefines(variant.shadows, defines);
                       return defines;
                     }),
      block_(gl::Buffer::create(sizeof(gpu::SsgiBitmaskBlock))) {}

void SsgiBitmaskPass::run(const SsgiInputs& inputs, const SsgiTextures& output) {
  gpu::SsgiBitmaskBlock block{};
  fillSettingFields(block, inputs.settings);
  block.downsample = inputs.downsample;
  // The seed and the frame index together turn the slices and the step jitter.
  block.rotationIndex = int(inputs.settings.ssgi.seed % 65536u) + inputs.frameIndex;
  block.farLightSource = gpu::kFarLightDirect;
  SsgiBitmaskVariant variant;
  if (inputs.virtualLights) {
    // The virtual lights carry the direct light from beyond R; the marches
    // add what glows there.
    block.virtualLightCount = inputs.virtualLights->count;
    inputs.virtualLights->buffer.bindStorage(gpu::VirtualLightBuffer::kBinding);
    block.farLightSource = inputs.emissive ? gpu::kFarLightEmission : gpu::kFarLightNone;
    if (inputs.lightField) {
      const LightFieldGrid& grid = inputs.lightField->grid;
      block.lightFieldOrigin = glm::vec4(grid.origin, 0.0f);
      block.lightFieldSpacing = glm::vec4(grid.spacing, 0.0f);
      block.lightFieldCounts = glm::ivec4(grid.counts, 0);
      inputs.lightField->buffer.bindStorage(gpu::LightFieldBuffer::kBinding);
    }
    // The lights' shadow maps: a virtual light near its light is hidden
    // where the light is.
    if (inputs.shadows) {
      variant.shadows = inputs.shadows->lookups();
      bindShadowMaps(*inputs.shadows, variant.shadows);
    }
  }
  if (inputs.farDownsample <= inputs.downsample) {
    block.part = gpu::kBitmaskBoth;
    const PassOutput outputs[] = {
        {"nearField", &output.occlusion}, {"farField", &output.sky}, {"specular", &output.specular}};
    draw(inputs, variant, block, outputs);
    return;
  }
  // Two resolutions: the near field without sky steps, then the far field
  // at its divisor with its own slice count.
  gpu::SsgiBitmaskBlock nearField = block;
  nearField.part = gpu::kBitmaskNearField;
  nearField.skyStepCount = 0;
  const PassOutput nearOutputs[] = {{"nearField", &output.occlusion}};
  draw(inputs, variant, nearField, nearOutputs);
  gpu::SsgiBitmaskBlock farField = block;
  farField.part = gpu::kBitmaskFarField;
  farField.downsample = inputs.farDownsample;
  farField.sliceCount = inputs.settings.ssgi.farSliceCount;
  const PassOutput farOutputs[] = {{"farFieldOverNear", &output.sky}, {"specular", &output.specular}};
  draw(inputs, variant, farField, farOutputs);
}

void SsgiBitmaskPass::draw(const SsgiInputs& inputs, const SsgiBitmaskVariant& variant,
                           const gpu::SsgiBitmaskBlock& block, std::span<const PassOutput> outputs) {
  block_.update(block);
  block_.bindUniform(gpu::SsgiBitmaskBlock::kBinding);
  FullscreenPass::run("SSGI bitmask", variant, inputs.form, outputs, inputs.accumulateWeight);
}

}  // namespace headlight

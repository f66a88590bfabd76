#include "passes/ssgi_blur.hpp"

#include "headlight/error.hpp"
#include "shared_layout.h"

namespace headlight {
namespace {

// The far field's own blur: a line of 2 x 7 + 1 of its texels along rows,
// then along columns (sigma 14/3 texels), i.e. 30 taps for a 15x15 window.
// It is this wide because the far field's pass shades a quarter of the
// pixels (or fewer) with 2 slices: cornell's HDR-FLIP with a 7x7 / 11x11 /
// 15x15 window at half resolution 0.2508 / 0.2347 / 0.2294
// (docs/BENCHMARKS.md, "Two resolutions").
constexpr int kFarTapRadius = 7;
// The upsample of the far field so blurred: 3x3 of its texels (sigma 2/3).
constexpr int kUpsampleTapRadius = 1;
// The 7x7 window (sigma 2) of the SSGI's own resolution.
constexpr int kTapRadius = 3;

}  // namespace

SsgiBlurPass::SsgiBlurPass()
    : FullscreenPass("ssgi_blur.glsl", [](const std::monostate&) { return std::vector<std::string>{}; }),
      block_(gl::Buffer::create(sizeof(gpu::SsgiBlurBlock))) {}

void SsgiBlurPass::execute(const FrameInputs& inputs, const PassAttachments& attachments, PassForm form) {
  const SsgiStep& step = *inputs.plan.ssgi;
  const SsgiTextures raw{attachments.read(Attachment::SsgiRaw), attachments.read(Attachment::SsgiRawSky),
                         attachments.read(Attachment::SsgiRawSpecular)};
  const SsgiTextures blurred{attachments.write(Attachment::Ssgi), attachments.write(Attachment::SsgiSky),
                             attachments.write(Attachment::SsgiSpecular)};
  run({raw, *inputs.settings.ssgi.radius, step.downsample, step.farDownsample,
       step.splitsFarField() ? &attachments.write(Attachment::SsgiFarSky) : nullptr,
       step.splitsFarField() ? &attachments.write(Attachment::SsgiFarSpecular) : nullptr, form},
      blurred);
}

void SsgiBlurPass::run(const SsgiBlurInputs& inputs, const SsgiTextures& output) {
  gpu::SsgiBlurBlock block{};
  block.ssgiRadiusWorld = inputs.ssgiRadiusWorld;
  block.ssgiDownsample = inputs.ssgiDownsample;
  block.skyDownsample = inputs.ssgiDownsample;
  block.outputDownsample = 1;
  block.skyTapRadius = kTapRadius;
  if (inputs.skyDownsample > inputs.ssgiDownsample) {
    if (inputs.farSky == nullptr || inputs.farSpecular == nullptr)
      throw GlError("SSGI blur: a coarser sky and no target to blur it in");
    blurFarField(block, inputs);
    block.skyDownsample = inputs.skyDownsample;
    block.skyTapRadius = kUpsampleTapRadius;
  }
  // Bound by the runner, but the far field's line blur rebinds the units.
  inputs.rawSsgi.sky.bind(gpu::kUnitSsgiSky);
  inputs.rawSsgi.specular.bind(gpu::kUnitSsgiSpecular);
  const PassOutput outputs[] = {{"nearField", &output.occlusion}, {"sky", &output.sky}, {"specular", &output.specular}};
  draw(block, inputs.form, outputs);
}

// The raw sky and specular along rows into farSky and farSpecular, then
// those along columns back into the raw ones (their raw values are not read
// again). The specular needs the wide window as much as the sky: a polished
// metal's lobe is read by one slice of a pixel and the steps' jitter decides
// where a reflected occluder's edge falls, and the 3x3 upsample alone left
// that grain on mirrors (issue 33).
void SsgiBlurPass::blurFarField(const gpu::SsgiBlurBlock& block, const SsgiBlurInputs& inputs) {
  gpu::SsgiBlurBlock line = block;
  line.skyDownsample = line.outputDownsample = inputs.skyDownsample;
  line.skyOnly = 1;
  line.skyTapRadius = kFarTapRadius;
  line.skyAxisX = 1;
  inputs.rawSsgi.sky.bind(gpu::kUnitSsgiSky);
  inputs.rawSsgi.specular.bind(gpu::kUnitSsgiSpecular);
  const PassOutput rows[] = {{"skyLine", inputs.farSky}, {"specularLine", inputs.farSpecular}};
  draw(line, inputs.form, rows);
  line.skyAxisX = 0;
  line.skyAxisY = 1;
  inputs.farSky->bind(gpu::kUnitSsgiSky);
  inputs.farSpecular->bind(gpu::kUnitSsgiSpecular);
  const PassOutput columns[] = {{"skyLine", &inputs.rawSsgi.sky}, {"specularLine", &inputs.rawSsgi.specular}};
  draw(line, inputs.form, columns);
}

void SsgiBlurPass::draw(const gpu::SsgiBlurBlock& block, PassForm form, std::span<const PassOutput> outputs) {
  block_.update(block);
  block_.bindUniform(gpu::SsgiBlurBlock::kBinding);
  FullscreenPass::run("SSGI blur", {}, form, outputs);
}

}  // namespace headlight

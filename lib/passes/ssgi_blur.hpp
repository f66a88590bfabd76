#pragma once
// Removes the SSGI pass's noise: a 7x7 Gaussian window (about two of the
// bitmask pass's 4x4 noise tiles) weighted by how alike the neighbour's
// normal and depth are, so AO does not bleed across silhouettes.
// Below full resolution it is also the upsample, with the same weights.
// Input and output: SsgiTextures (both filtered with the same weights). A
// raw sky coarser than the raw SSGI (the bitmask method's far-field pass) is
// blurred at its own resolution with the specular visibility it carries (a
// wider window there, along rows into `farSky` and `farSpecular`, then along
// columns back), then both are upsampled from a 3x3 window of it with the
// same kind of weights. Body: glsl/ssgi_blur.glsl, in either form.
#include <optional>
#include <variant>

#include "frame/frame_plan.hpp"
#include "gl/objects.hpp"
#include "passes/frame_pass.hpp"
#include "passes/fullscreen.hpp"
#include "passes/ssgi_textures.hpp"
#include "shared_layout.h"

namespace headlight {

struct SsgiBlurInputs {
  SsgiTextures rawSsgi;          // the SSGI pass's output, at 1/ssgiDownsample of the G-buffer's size per side
  float ssgiRadiusWorld = 0.0f;  // the SSGI radius: depth differences are judged against it
  int ssgiDownsample = 1;        // 1, 2 or 4
  int skyDownsample = 1;         // rawSsgi.sky's divisor: ssgiDownsample, or above it with `farSky`
  // rawSsgi.sky's size, for the far field's blur along rows (skyDownsample >
  // ssgiDownsample); that blur overwrites rawSsgi.sky and rawSsgi.specular.
  const gl::Texture* farSky = nullptr;
  const gl::Texture* farSpecular = nullptr;
  PassForm form = PassForm::Fragment;
};

class SsgiBlurPass final : public FramePass, FullscreenPass<std::monostate> {
 public:
  SsgiBlurPass();
  // The frame block must be bound.
  void execute(const FrameInputs& inputs, const PassAttachments& attachments, PassForm form) override;

 private:
  // `output` has the G-buffer's size.
  void run(const SsgiBlurInputs& inputs, const SsgiTextures& output);
  void blurFarField(const gpu::SsgiBlurBlock& block, const SsgiBlurInputs& inputs);
  void draw(const gpu::SsgiBlurBlock& block, PassForm form, std::span<const PassOutput> outputs);

  gl::Buffer block_;
};

}  // namespace headlight

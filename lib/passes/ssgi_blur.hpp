#pragma once
// Removes the SSGI pass's noise: a 7x7 Gaussian window (about two of the
// bitmask pass's 4x4 noise tiles) weighted by how alike the neighbour's
// normal and depth are, so AO does not bleed across silhouettes.
// Below full resolution it is also the upsample, with the same weights.
// Input and output: SsgiTextures (both filtered with the same weights).
#include "gl/objects.hpp"
#include "passes/fullscreen.hpp"
#include "passes/gbuffer.hpp"
#include "passes/ssgi_textures.hpp"

namespace headlight {

struct SsgiBlurInputs {
  const GBuffer& gbuffer;        // position, normal
  SsgiTextures rawSsgi;          // the SSGI pass's output, at 1/ssgiDownsample of the G-buffer's size per side
  float ssgiRadiusWorld = 0.0f;  // the SSGI radius: depth differences are judged against it
  int ssgiDownsample = 1;        // 1, 2 or 4
};

class SsgiBlurPass {
 public:
  SsgiBlurPass();
  // The frame block must be bound. `output` has the G-buffer's size.
  void run(const SsgiBlurInputs& inputs, const SsgiTextures& output);

 private:
  gl::Program program_;
  gl::Buffer block_;
  FullscreenDraw draw_;
};

}  // namespace headlight

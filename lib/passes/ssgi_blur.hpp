#pragma once
// Removes the SSGI pass's 4x4 noise pattern: a 4x4 box (the noise tile, so
// every rotation is averaged once) weighted by how alike the neighbour's
// normal and depth are, so AO does not bleed across silhouettes.
// Below full resolution it is also the upsample, with the same weights.
// Input and output GL_RGBA16F, same layout as the SSGI output.
#include "gl/objects.hpp"
#include "passes/gbuffer.hpp"

namespace headlight {

class SsgiBlurPass {
 public:
  SsgiBlurPass();
  // `radius` is the SSGI radius in world units: depth differences are
  // judged against it. The frame block must be bound.
  // `input` is the raw SSGI at 1/divisor of the G-buffer's size per side.
  void run(const GBuffer& gbuffer, const gl::Texture& input, const gl::Texture& output, float radius, int divisor);

 private:
  gl::Program program_;
  gl::Buffer block_;
  gl::Framebuffer framebuffer_;
  gl::VertexArray emptyVertexArray_;
};

}  // namespace headlight

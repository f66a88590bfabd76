#pragma once
// Screen-space global illumination. Per pixel, a cosine-weighted hemisphere
// kernel around the view-space normal, rotated by a 4x4 tiled noise; each
// sample is projected, compared with the G-buffer's surface there (with a
// bias) and weighted by a range check; an occluding sample darkens ambient
// occlusion and adds to the indirect term: its albedo (the seed's
// `hemisphere` method) or its direct Lambertian radiance (`radiance`,
// docs/ACCURACY.md). Output GL_RGBA16F: R = AO (1 = open), GBA = indirect.
#include <array>
#include <map>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.hpp"
#include "headlight/settings.hpp"
#include "passes/gbuffer.hpp"

namespace headlight {

// The kernel in tangent space (+Z = normal): `sampleCount` points with z >= 0
// and length <= 1, directions cosine-weighted toward +Z, lengths uniform
// times lerp(0.1, 1, (i / sampleCount)^2) so that they crowd near the centre.
// The same seed always gives the same kernel.
std::vector<glm::vec3> makeSsgiKernel(int sampleCount, unsigned seed);

// 16 unit vectors in the xy plane: random rotations of the kernel about the
// normal, tiled every 4x4 pixels.
std::array<glm::vec2, 16> makeSsgiNoise(unsigned seed);

class SsgiPass {
 public:
  SsgiPass();
  void prepare(SsgiMethod method) { programFor(method); }
  // Reads gbuffer (position, normal, albedo; material for the radiance
  // method), `directDiffuse` (the direct-light pass's Lambertian target;
  // required by the radiance method, ignored by hemisphere) and the frame
  // block; writes `output` (GL_RGBA16F, the G-buffer's size divided by
  // settings.downsample, rounded up). `settings` must be
  // resolved (radius > 0, bias >= 0, indirectStrength >= 0).
  void run(const GBuffer& gbuffer, const gl::Texture* directDiffuse, const gl::Texture& output,
           const SsgiSettings& settings);

 private:
  void updateKernel(const SsgiSettings& settings);
  const gl::Program& programFor(SsgiMethod method);
  std::map<SsgiMethod, gl::Program> programs_;
  gl::Buffer block_;
  gl::Texture noise_;
  gl::Framebuffer framebuffer_;
  gl::VertexArray emptyVertexArray_;  // a fullscreen triangle needs no vertices, but core GL needs a VAO bound
  int kernelSampleCount_ = 0;
  unsigned kernelSeed_ = 0;
};

}  // namespace headlight

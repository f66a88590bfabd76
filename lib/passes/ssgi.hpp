#pragma once
// Screen-space global illumination. Per pixel, a cosine-weighted hemisphere
// kernel around the view-space normal, rotated by a 4x4 tiled noise; each
// sample is projected, compared with the G-buffer's surface there (with a
// bias) and weighted by a range check; an occluding sample darkens ambient
// occlusion and adds to the indirect term: its albedo (the seed's
// `hemisphere` method) or its direct Lambertian radiance (`radiance`,
// docs/ACCURACY.md). Output: SsgiTextures; these kernels see no farther
// than R, so they write their AO within R as the sky visibility.
#include <array>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.hpp"
#include "headlight/settings.hpp"
#include "passes/fullscreen.hpp"
#include "passes/gbuffer.hpp"
#include "passes/ssgi_bitmask.hpp"
#include "shared_layout.h"

namespace headlight {

// The kernel in tangent space (+Z = normal): `sampleCount` points with z >= 0
// and length <= 1, directions cosine-weighted toward +Z, lengths uniform
// times lerp(0.1, 1, (i / sampleCount)^2) so that they crowd near the centre.
// The same seed always gives the same kernel.
std::vector<glm::vec3> makeSsgiKernel(int sampleCount, unsigned seed);

// 16 unit vectors in the xy plane: random rotations of the kernel about the
// normal, tiled every 4x4 pixels.
std::array<glm::vec2, 16> makeSsgiNoise(unsigned seed);

// Everything one SSGI frame reads. Values are resolved (no "auto"): the
// renderer fills them from the frame's settings.
struct SsgiInputs {
  const GBuffer& gbuffer;            // position, normal, albedo; material for the radiance method
  const gl::Texture* directDiffuse;  // DirectLightTargets::diffuse: required by radiance and bitmask
  SsgiMethod method = SsgiMethod::Hemisphere;
  int sampleCount = 0;            // kernel samples, 1..gpu::kMaxKernelSamples
  unsigned seed = 0;              // kernel and noise
  float radiusWorld = 0.0f;       // kernel radius, world units, > 0
  float biasWorld = 0.0f;         // occlusion depth bias, world units, >= 0
  float intensity = 0.0f;         // AO = 1 - intensity * mean occlusion, >= 0
  float indirectStrength = 0.0f;  // scale of the indirect term, >= 0
  int downsample = 1;             // 1, 2 or 4: the output is the G-buffer's size / downsample, rounded up
  // The bitmask method's own (the others ignore them).
  int sliceCount = 0;             // screen-space directions per pixel, >= 1
  int stepCount = 0;              // depth samples per direction and side, >= 1
  float thicknessWorld = 0.0f;    // assumed depth behind each depth sample, world units, >= 0
  int skyStepCount = 0;           // long-range samples per direction for the sky visibility, >= 0
  int frameIndex = 0;             // rotates the slices and step jitter between accumulated frames
  float accumulateWeight = 0.0f;  // 0: overwrite the output; else blend in as (1 - w) output + w result
};

// Variants: one per kernel method (ssgi.frag); the bitmask method is its
// own pass (ssgi_bitmask.frag), built on first use.
class SsgiPass : public FullscreenPass<SsgiMethod> {
 public:
  SsgiPass();
  // Builds `method`'s program ahead of its first frame.
  void prepare(SsgiMethod method);
  // Reads `inputs` and the frame block; writes `output` (the size
  // SsgiInputs::downsample says).
  void run(const SsgiInputs& inputs, const SsgiTextures& output);

 private:
  void updateKernel(int sampleCount, unsigned seed);
  gpu::SsgiBlock block_{};  // the CPU copy: the kernel (and sampleCount) changes rarely, the rest every frame
  gl::Buffer blockBuffer_;
  gl::Texture noise_;
  unsigned kernelSeed_ = 0;  // with block_.sampleCount, what the kernel and noise were made from
  std::optional<SsgiBitmaskPass> bitmask_;
};

}  // namespace headlight

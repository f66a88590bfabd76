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
#include "passes/frame_pass.hpp"
#include "passes/fullscreen.hpp"
#include "passes/gbuffer.hpp"
#include "passes/light_field.hpp"
#include "passes/shadow.hpp"
#include "passes/ssgi_bitmask.hpp"
#include "passes/virtual_lights.hpp"
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

// Everything one SSGI frame reads besides its declared attachments. The
// settings are the frame's resolved ones (Renderer::resolve: no "auto"
// left); each method's pass fills its block from them directly, so a setting
// that reaches a shader is its settings row, its block field and the
// shader, with no copy in between.
struct SsgiInputs {
  const RenderSettings& settings;  // resolved: the block members that carry settings are filled from it
  int downsample = 1;              // 1, 2 or 4: the output is the G-buffer's size / downsample, rounded up
  // The bitmask method's far field (SsgiTextures::sky): above `downsample`,
  // its own pass at this divisor (SsgiStep::farDownsample); else `downsample`.
  int farDownsample = 1;
  // The bitmask method's far field: the light from beyond R from these
  // (VirtualLightPass), or null: from what its marches find.
  const VirtualLights* virtualLights = nullptr;
  const LightField* lightField = nullptr;  // with virtual lights: the probes they filled, or null
  const ShadowMaps* shadows = nullptr;  // the lights' maps: what hides a virtual light near its light
  bool emissive = false;                // the G-buffer has emission (bound): what glows beyond R with virtual lights
  int frameIndex = 0;                   // rotates the slices and step jitter between accumulated frames
  // Accumulated frames (SsgiStep::frames > 1): 0 overwrites the output, w
  // blends in as (1 - w) output + w result; none: a single frame.
  std::optional<float> accumulateWeight;
  PassForm form = PassForm::Fragment;  // fragment or compute (lib/passes/fullscreen.hpp)
};

// Variants: one per kernel method (glsl/ssgi.glsl); the bitmask method is
// its own program (glsl/ssgi_bitmask.glsl). Programs are built on first use.
// Accumulated frames (SsgiStep::frames) are a running mean of rotated slice
// sets, in the entry.
class SsgiPass final : public FramePass, FullscreenPass<SsgiMethod> {
 public:
  SsgiPass();
  // The frame block must be bound.
  void execute(const FrameInputs& inputs, const PassAttachments& attachments, PassForm form) override;

 private:
  // Writes `output` (the size SsgiInputs::downsample says).
  void run(const SsgiInputs& inputs, const SsgiTextures& output);
  void updateKernel(int sampleCount, unsigned seed);
  gpu::SsgiBlock block_{};  // the CPU copy: the kernel (and sampleCount) changes rarely, the rest every frame
  gl::Buffer blockBuffer_;
  gl::Texture noise_;
  unsigned kernelSeed_ = 0;  // with block_.sampleCount, what the kernel and noise were made from
  std::optional<SsgiBitmaskPass> bitmask_;
};

}  // namespace headlight

#pragma once
// The `bitmask` SSGI method (Therrien, Levesque and Gilet 2023, with the
// cosine-weighted slice integral of Jimenez et al. 2016): screen-space
// slices marched over the G-buffer's depth, a 32-sector visibility mask per
// slice with a thickness behind every depth sample, AO as the reference
// defines it and indirect light gathered from the occluders' direct
// Lambertian radiance. docs/ACCURACY.md §3.3 has the formulas.
// The same slices, marched on beyond R to the screen edge with a few
// geometrically spaced samples, give the sky visibility at any distance and
// the indirect light from beyond R (sectors only those samples cover).
// Output: SsgiTextures, the same layout as the other methods.
#include "gl/objects.hpp"
#include "passes/fullscreen.hpp"
#include "passes/gbuffer.hpp"
#include "passes/ssgi_textures.hpp"

namespace headlight {

struct SsgiBitmaskInputs {
  const GBuffer& gbuffer;            // depth, normal, albedo, material
  const gl::Texture& directDiffuse;  // DirectLightTargets::diffuse: the occluders' light
  float radiusWorld = 0.0f;          // R, world units, > 0
  float thicknessWorld = 0.0f;       // depth of every sample's slab behind its surface, world units, >= 0
  float intensity = 0.0f;            // AO = 1 - intensity * (1 - visible fraction), >= 0
  float indirectStrength = 0.0f;     // scale of the indirect term, >= 0
  int sliceCount = 0;                // directions per pixel, >= 1
  int stepCount = 0;                 // depth samples per direction and side, >= 1
  int skyStepCount = 0;              // samples per direction and side beyond R, to the screen edge, >= 0
  int downsample = 1;                // 1, 2 or 4
  int rotationIndex = 0;             // rotates slices and step jitter (the seed + the frame index), >= 0
  // 0: `output` is overwritten. In (0, 1]: the result is blended in as
  // output = (1 - w) output + w result (frame k of an accumulation: 1 / (k + 1)).
  float accumulateWeight = 0.0f;
};

class SsgiBitmaskPass {
 public:
  SsgiBitmaskPass();
  // The frame block must be bound. Writes `output` (the G-buffer's size /
  // downsample, rounded up).
  void run(const SsgiBitmaskInputs& inputs, const SsgiTextures& output);

 private:
  gl::Program program_;
  gl::Buffer block_;
  FullscreenDraw draw_;
};

}  // namespace headlight

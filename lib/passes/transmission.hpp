#pragma once
// The transmission pass: KHR_materials_transmission (and _volume) surfaces,
// drawn after the composite has lit the opaque surfaces, before the blend
// pass. Three steps, one timed pass ("transmission"):
//  1. lit (the opaque surfaces and the background, nothing transmissive yet:
//     the G-buffer pass left these surfaces out, GBufferVariant::
//     deferTransmissive) is copied into a mip-mapped texture, the
//     background the surfaces refract;
//  2. the transmissive surfaces are drawn into the G-buffer by the G-buffer
//     pass's own programs (GBufferPass::drawTransmissive), so every G-buffer
//     target (and depth) then holds the nearest surface, transmissive or not;
//  3. they are drawn again, depth-equal (so only the nearest, once per
//     pixel), with gbuffer.frag built with TRANSMISSION_FORWARD: the
//     material evaluated as for the G-buffer, shaded by
//     glsl/transmission.glsl (lights, shadows, ambient, and the background
//     through the surface: lobe_transmission.glsl), replacing lit; the
//     transmission target gets the throughput (how much of the background
//     came through, per channel) and the path length through the volume.
//
// Why before the blend pass: a blended surface in front of a transmissive
// one then blends over its final colour (the blend pass tests the G-buffer
// depth, which step 2 filled); the other order would lose it under step 3's
// depth-equal overwrite. The price: blended surfaces are not seen through
// transmissive ones (the background copy predates them).
//
// What screen-space refraction cannot show (docs/PIPELINE.md): what is
// off-screen (the copy is clamped at its edges), what is hidden behind
// another opaque surface, and any transmissive surface behind the nearest
// one (only opaque surfaces are in the copy). The surfaces get no SSGI.
#include <cstdint>

#include "frame/frame_plan.hpp"
#include "gl/gpu_scene.hpp"
#include "gl/objects.hpp"
#include "passes/environment.hpp"
#include "passes/gbuffer.hpp"
#include "passes/program_cache.hpp"
#include "passes/shadow.hpp"

namespace headlight {

// GPU memory the pass adds per pixel, for the renderer's pre-flight
// (--max-memory): lit's copy with its mip chain (RGBA32F under
// radiance-precision float: 16 bytes x 4/3), the positions' copy (RGBA32F,
// 16) and the transmission target (RGBA32F, 16), rounded up.
inline constexpr std::uint64_t kTransmissionBytesPerPixel = 56;

struct TransmissionInputs {
  const GpuScene& scene;
  GBufferPass& gbuffer;                  // step 2 draws with its programs
  const GBufferTargets& gbufferTargets;  // the frame's G-buffer attachments, depth included
  const GBufferVariant& gbufferVariant;
  const ShadowMaps& shadows;             // read by the variant's shadow flags
  const EnvironmentTables& environment;  // the BRDF table always; the sky's with the sky term
};

struct TransmissionTargets {
  const gl::Texture& lit;           // the composite's output: copied, then written over
  const gl::Texture& transmission;  // cleared to 0 here: RGB throughput, A path length (world units)
  int width = 0;
  int height = 0;
};

class TransmissionPass {
 public:
  TransmissionPass();
  // Builds the programs `scene`'s transmissive draws need for `variant`.
  void prepare(const GpuScene& scene, const TransmissionVariant& variant);
  void run(const TransmissionInputs& inputs, const TransmissionTargets& targets, const TransmissionVariant& variant);

 private:
  void copyBackground(const gl::Texture& lit, const gl::Texture& position);
  void shade(const TransmissionInputs& inputs, const TransmissionTargets& targets, const TransmissionVariant& variant);

  struct ProgramKey {
    FeatureBits features;  // GBufferFeature bits of the draw
    TransmissionVariant variant;
    auto operator<=>(const ProgramKey&) const = default;
  };
  ProgramCache<ProgramKey> programs_;
  gl::Framebuffer framebuffer_ = gl::Framebuffer::create();
  gl::Texture background_;  // lit's copy with its mip chain, remade when lit's size or format changes
  // The G-buffer's positions before step 2: where each pixel of background_
  // lies, so the blur can follow the distance behind the surface.
  gl::Texture backgroundPosition_;
  gl::Sampler backgroundSampler_ = gl::Sampler::create();
};

}  // namespace headlight

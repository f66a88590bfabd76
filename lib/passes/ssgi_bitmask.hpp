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
// The far field (the sky texture) is low-frequency: with a coarser far
// divisor (SsgiInputs::farDownsample) it is its own pass there, with
// ssgi-far-slices directions and the within-R slabs only as far as they
// shadow the sky, and the near pass marches no sky steps. The near texture
// is then exactly what a run with ssgi-sky-steps 0 writes.
#include "gl/objects.hpp"
#include "passes/fullscreen.hpp"
#include "passes/gbuffer.hpp"
#include "passes/ssgi_textures.hpp"
#include "shared_layout.h"

namespace headlight {

struct SsgiInputs;  // passes/ssgi.hpp: the SSGI pass's inputs, whichever method

// The program's variant: the shadow maps its virtual lights' visibility
// reads (none without virtual lights).
struct SsgiBitmaskVariant {
  ShadowLookups shadows;
  auto operator<=>(const SsgiBitmaskVariant&) const = default;
};

class SsgiBitmaskPass : FullscreenPass<SsgiBitmaskVariant> {
 public:
  SsgiBitmaskPass();
  // The frame block must be bound. Writes `output` (the G-buffer's size /
  // downsample, rounded up; the sky's / farDownsample).
  void run(const SsgiInputs& inputs, const SsgiTextures& output);

 private:
  void draw(const SsgiInputs& inputs, const SsgiBitmaskVariant& variant, const gpu::SsgiBitmaskBlock& block,
            std::span<const PassOutput> outputs);

  gl::Buffer block_;
};

}  // namespace headlight

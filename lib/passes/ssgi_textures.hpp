#pragma once
// The three textures an SSGI pass writes, its blur reads and writes, and the
// composite reads: the ssgi frame target's channels 0..3, 4..7 and 8
// (headlight/targets.hpp), all GL_RGBA16F and of one size.
#include "gl/objects.hpp"

namespace headlight {

struct SsgiTextures {
  const gl::Texture& occlusion;  // R = AO within R (1 = open), GBA = indirect light gathered within R
  const gl::Texture& sky;        // R = sky visibility at any distance (1 = open), GBA = indirect light
                                 // gathered beyond R (bitmask; 0 for the kernel methods)
  const gl::Texture& specular;   // R = the specular lobe's sky visibility (1 = open; the kernel methods: their
                                 // AO), G = its weight for the blur (internal)
};

}  // namespace headlight

#pragma once
// The reference's texture lookups: what the renderer's sampler returns for
// one texture coordinate, computed on the CPU from the scene's decoded
// RGBA8 images. Needs no Embree and no GL.
#include <cstdint>

#include <glm/glm.hpp>

#include "headlight/scene.hpp"

namespace headlight::reference {

// A texel index `i` of an axis `size` texels long, wrapped as `mode` says
// (kGlRepeat, kGlClampToEdge or kGlMirroredRepeat; any other value repeats).
int wrapTexel(int i, int size, int mode);

// Samples level 0 of `ref`'s image at `uv` (bilinear, or nearest when the
// magnification filter is kGlNearest), wrapping as the sampler says; RGB
// decoded from sRGB when `srgb`, as GL_SRGB8_ALPHA8 does before filtering.
// Mip maps are not used: one hit per ray has no footprint to choose a level
// from, and the mean over many rays is the filtered value anyway. An image
// with no texels reads as white. `ref.image` must index scene.images.
glm::vec4 sampleTexture(const Scene& scene, const TextureRef& ref, glm::vec2 uv, bool srgb);

// The UV `ref` samples at barycentrics (u, v) of the triangle whose three
// vertex indices start at `corner`, as gbuffer.frag's textureUv computes it:
// TEXCOORD_1 for texCoord 1, else TEXCOORD_0 ((0, 0) where the primitive has
// no such set), then KHR_texture_transform's matrix.
glm::vec2 textureUv(const Primitive& primitive, const TextureRef& ref, const std::uint32_t* corner, float u, float v);

}  // namespace headlight::reference

#pragma once
// The GL internal format of each frame target's GPU texture: the G-buffer
// pass and the renderer allocate these, the readback reads them. One row per
// frame target (headlight/targets.hpp); a target with more than 4 channels
// (ssgi) is held in ceil(n / 4) textures of its format, channels 4k..4k+3 in
// texture k.
#include <glad/gl.h>

#include "headlight/error.hpp"
#include "headlight/frame.hpp"

namespace headlight::gl {

struct TargetGpuFormat {
  ImageF Frame::*image;
  GLenum internalFormat;
};

inline constexpr TargetGpuFormat kTargetGpuFormats[] = {
    {&Frame::position, GL_RGBA32F},  // float32: half's 11 bits are too few far from the origin
    {&Frame::normal, GL_RGBA16F},
    {&Frame::albedo, GL_SRGB8_ALPHA8},  // 8-bit sRGB like the textures it comes from
    {&Frame::material, GL_RGBA8},       // 8-bit like the textures it comes from
    {&Frame::depth, GL_DEPTH_COMPONENT32F},
    {&Frame::emissive, GL_RGBA16F},
    {&Frame::ssgi, GL_RGBA16F},
    {&Frame::lit, GL_RGBA16F},
};

// The format of the target Frame keeps in `image`.
inline GLenum targetFormat(ImageF Frame::*image) {
  for (const TargetGpuFormat& row : kTargetGpuFormats)
    if (row.image == image) return row.internalFormat;
  throw GlError("no GPU format for this frame target (lib/gl/target_formats.hpp)");
}

// Depth targets are read back as view depth, the rest as colour.
inline bool isDepthTarget(ImageF Frame::*image) { return targetFormat(image) == GL_DEPTH_COMPONENT32F; }

}  // namespace headlight::gl

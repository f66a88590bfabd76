#pragma once
// GL-free, so the frame plan names its attachments' formats without GL;
// gl/target_formats.hpp maps each to a GL internal format.

namespace headlight {

// How the GPU stores an attachment.
enum class GpuFormat {
  Rgba32F,      // float32: position, where half's 11 bits are too few far from the origin
  Rgba16F,      // half: normals and HDR radiance
  Srgb8Alpha8,  // 8-bit sRGB: albedo, like the textures it comes from
  Rgba8,        // 8-bit: material factors, like the textures they come from
  Depth32F,     // depth, read back as view depth
  Rgba32Ui,     // unsigned integers: the ids target, exact
};

}  // namespace headlight

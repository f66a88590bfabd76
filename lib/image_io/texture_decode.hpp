#pragma once
// Decoding a glTF image's encoded bytes (PNG, JPEG, ...) into RGBA8. Lives
// in the image module (lib/image_io/image_module.hpp) with the rest of the
// OpenImageIO code.
#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace headlight::detail {

struct DecodedTexture {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgba;  // width * height * 4, rows top first, straight alpha
};

struct TextureDecodeLimits {
  int maxSide = 16384;           // per side
  std::int64_t texelBudget = 0;  // texels still allowed for this image and those after it
  // Bytes still allowed (max-memory): an image costs kDecodeBytesPerTexel a
  // texel while it decodes, and its share of the scene estimate after.
  std::uint64_t byteBudget = ~std::uint64_t(0);
  const char* refusedBy = nullptr;  // set with overBudget: "max-texels" or "max-memory"
};

// Peak bytes a texel costs while decoding: the decoder's own RGBA buffer, the
// read (up to 4 channels) and the RGBA copy kept (4 each). At least the 32/3
// bytes the scene estimate counts a kept texel (RGBA with mipmaps, CPU and
// GPU: estimateSceneBytes), so a texture that passes here passes that too.
inline constexpr std::uint64_t kDecodeBytesPerTexel = 12;

// Fills `texture` and returns "" on success, else says why, in words that
// follow "image N: ". The header's size is checked against `limits` before
// any pixel is decoded; `overBudget` is set when the budget refused it.
// On success `limits.texelBudget` is reduced by the image's texels.
std::string decodeTexture(const unsigned char* bytes, std::size_t size, TextureDecodeLimits& limits,
                          DecodedTexture& texture, bool& overBudget);

}  // namespace headlight::detail

#pragma once
// Decoding an environment map file (.hdr, .exr: whatever OpenImageIO reads)
// into linear float RGB. Lives in the image module with the rest of the
// OpenImageIO code; the core's loadEnvironmentMap (lib/environment/) checks
// the file's kind first and turns a refusal into an error naming the file.
#include <cstdint>
#include <string>
#include <vector>

namespace headlight::detail {

struct DecodedEnvironment {
  int width = 0, height = 0;
  std::vector<float> rgb;  // width * height * 3, rows top first
};

// Bytes one texel of an environment map costs while it is loaded and drawn:
// the decode buffer (up to 4 float channels), the kept RGB floats and the
// GPU's RGBA16F background texture. What max-memory is checked against
// before any pixel is decoded.
inline constexpr std::uint64_t kEnvironmentBytesPerTexel = 16 + 12 + 8;

// Fills `map` and returns "" on success, else says why, in words that follow
// "<file>: environment map ". The header's declared size is checked (2:1
// aspect, at most `maxSide` wide, kEnvironmentBytesPerTexel x texels within
// `maxBytes`) before any pixel is decoded; then every value must be finite
// and >= 0.
std::string decodeEnvironment(const char* path, std::uint64_t maxBytes, int maxSide, DecodedEnvironment& map);

}  // namespace headlight::detail

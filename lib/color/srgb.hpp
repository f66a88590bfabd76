#pragma once
// The sRGB transfer curve (IEC 61966-2-1), the one copy for the C++ side:
// the G-buffer's albedo readback, the reference's texture sampler and the
// preview's encoding use these. (GL applies the same curve itself to
// GL_SRGB8_ALPHA8 textures and framebuffers; no shader writes it.)
#include <cmath>

namespace headlight {

// An encoded value in 0..1 to linear.
inline float srgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

// A linear value in 0..1 to encoded (values outside 0..1 follow the curve's formulas).
inline float linearToSrgb(float linear) {
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

}  // namespace headlight

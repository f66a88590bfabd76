#pragma once
// Colour measures the iridescence tests read a film's tint with.
#include <algorithm>

#include <glm/glm.hpp>

#include "headlight/frame.hpp"

namespace headlight::test {

// The first three channels of `image` at (x, y).
inline glm::vec3 rgbAt(const ImageF& image, int x, int y) {
  return {image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2)};
}

// (max - min) / mean of a colour: 0 for grey.
inline float chroma(const glm::vec3& c) {
  const float mean = (c.r + c.g + c.b) / 3.0f;
  return mean > 0.0f ? (std::max({c.r, c.g, c.b}) - std::min({c.r, c.g, c.b})) / mean : 0.0f;
}

// The index of the largest channel (0 red, 1 green, 2 blue).
inline int dominantChannel(const glm::vec3& c) { return c.r >= c.g && c.r >= c.b ? 0 : c.g >= c.b ? 1 : 2; }

}  // namespace headlight::test

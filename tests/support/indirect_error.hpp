#pragma once
// The SSGI's indirect light against the reference's, as GL tests judge it:
// ssgi.exr's indirect (channels 1..3, within R) plus indirectFar (5..7,
// beyond it) against indirect_ref's unlimited indirect (3..5), compared as
// means over 8x8 blocks of geometry pixels (per pixel, a few hundred rays'
// noise is most of the difference).
#include <doctest/doctest.h>

#include <glm/glm.hpp>

#include <cmath>

#include "headlight/frame.hpp"
#include "headlight/reference.hpp"

namespace headlight::test {

struct IndirectError {
  double relativeRmse = 0.0;  // the blocks' RMSE over the reference's mean per pixel and channel
  double ratio = 0.0;         // ours over the reference's, summed over the geometry pixels
};

inline IndirectError blockIndirectError(const Frame& frame, const ReferenceImages& truth) {
  REQUIRE(truth.indirect.channels.at(3) == "indirect.R");
  constexpr int kBlock = 8;
  double squared = 0.0, ours = 0.0, theirs = 0.0;
  long pixelCount = 0, blockCount = 0;
  for (int by = 0; by + kBlock <= frame.ssgi.height; by += kBlock)
    for (int bx = 0; bx + kBlock <= frame.ssgi.width; bx += kBlock) {
      glm::dvec3 a(0.0), b(0.0);
      int pixels = 0;
      for (int y = by; y < by + kBlock; ++y)
        for (int x = bx; x < bx + kBlock; ++x) {
          if (frame.position.at(x, y, 3) == 0.0f) continue;
          for (int c = 0; c < 3; ++c) {
            a[c] += frame.ssgi.at(x, y, 1 + c) + frame.ssgi.at(x, y, 5 + c);
            b[c] += truth.indirect.at(x, y, 3 + c);
          }
          ++pixels;
        }
      if (pixels == 0) continue;
      for (int c = 0; c < 3; ++c) {
        squared += (a[c] - b[c]) * (a[c] - b[c]) / (double(pixels) * pixels);
        ours += a[c];
        theirs += b[c];
      }
      pixelCount += pixels;
      ++blockCount;
    }
  REQUIRE(theirs > 0.0);
  return {std::sqrt(squared / (3.0 * double(blockCount))) / (theirs / (3.0 * double(pixelCount))), ours / theirs};
}

}  // namespace headlight::test

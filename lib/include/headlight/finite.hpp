#pragma once
// Finite checks on a rendered frame: every value an output file holds must be
// finite. The renderer keeps values finite for scenes that pass
// checkSceneRanges (headlight/limits.hpp); these checks are the last line,
// run by whatever writes a frame (writeFrame) before the first byte is written.
//
//   for (const TargetNonFinite& t : countNonFinite(frame)) print(t.target, t.count);
//   requireFinite(frame);                  // throws NonFiniteError naming each target and its count
//   std::size_t clamped = clampNonFinite(frame);   // only when the user asked
#include <cstddef>
#include <string>
#include <vector>

#include "headlight/export.hpp"
#include "headlight/error.hpp"
#include "headlight/frame.hpp"

namespace headlight HEADLIGHT_PUBLIC {

// A frame holds NaN or infinite values; the message names every target with
// its count and the first pixel and channel.
class NonFiniteError : public Error {
 public:
  using Error::Error;
};

struct TargetNonFinite {
  std::string target;            // file stem: "depth", "lit", ...
  std::size_t count = 0;         // non-finite values (not pixels) in the target
  std::size_t values = 0;        // all values in the target
  int firstX = -1, firstY = -1;  // the first non-finite value's pixel (rows top first)
  std::string firstChannel;      // and its channel ("depth.Z")
};

// Non-finite values in one image.
TargetNonFinite countNonFinite(const ImageF& image, std::string target);
// One entry per non-empty target of frame.targets(), in that order, zero
// counts included (for a summary that prints them).
std::vector<TargetNonFinite> countNonFinite(const Frame& frame);
// Throws NonFiniteError when any target holds a non-finite value:
// "<scene>: non-finite values in the frame: depth 16384 of 16384 (first at 0,0 depth.Z), ...".
void requireFinite(const Frame& frame);
// Replaces NaN by 0 and +-inf by +-FLT_MAX in every target; returns how many
// values it replaced. For a user who asked for clamping; print the count.
std::size_t clampNonFinite(Frame& frame);

}  // namespace headlight

#pragma once
// Images made in code, for tests that feed the library synthetic frames.
#include <string>
#include <vector>

#include "headlight/frame.hpp"

namespace headlight::test {

// width x height pixels of `channels`, every value `value`.
ImageF makeImage(int width, int height, std::vector<std::string> channels, float value = 0.0f);

}  // namespace headlight::test

// The parts of headlight/output.hpp that need no image library: names and
// tone curves, used by option tables and help without loading the image
// module (lib/image_io/image_module.hpp).
#include <algorithm>

#include "headlight/output.hpp"
#include "headlight/targets.hpp"
#include "output/tonemap.hpp"

namespace headlight {
namespace {

constexpr std::string_view kCompressionNames[] = {"none", "rle", "zips", "zip", "piz"};

}  // namespace

std::span<const std::string_view> exrCompressionNames() { return kCompressionNames; }
std::string_view exrCompressionName(ExrCompression compression) { return kCompressionNames[int(compression)]; }

std::vector<std::string_view> outputTargetNames() {
  std::vector<std::string_view> names;
  for (const FrameTarget& target : frameTargets()) names.push_back(target.name);
  names.push_back("preview");
  return names;
}

float tonemapAces(float x) {
  const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
  return std::clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0f, 1.0f);
}

float tonemapReinhard(float x) { return x / (1.0f + x); }

}  // namespace headlight

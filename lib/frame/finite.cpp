#include "headlight/finite.hpp"

#include "headlight/targets.hpp"

#include <cmath>
#include <limits>

namespace headlight {

TargetNonFinite countNonFinite(const ImageF& image, std::string target) {
  TargetNonFinite result;
  result.target = std::move(target);
  result.values = image.pixels.size();
  const std::size_t channels = image.channels.size();
  for (std::size_t at = 0; at < image.pixels.size(); ++at) {
    if (std::isfinite(image.pixels[at])) continue;
    if (result.count++ == 0 && channels > 0 && image.width > 0) {
      const std::size_t pixel = at / channels;
      result.firstX = int(pixel % std::size_t(image.width));
      result.firstY = int(pixel / std::size_t(image.width));
      result.firstChannel = image.channels[at % channels];
    }
  }
  return result;
}

std::vector<TargetNonFinite> countNonFinite(const Frame& frame) {
  std::vector<TargetNonFinite> counts;
  for (const auto& [name, image] : frame.targets()) counts.push_back(countNonFinite(*image, name));
  return counts;
}

void requireFinite(const Frame& frame) {
  std::string list;
  for (const TargetNonFinite& target : countNonFinite(frame)) {
    if (target.count == 0) continue;
    list += (list.empty() ? "" : ", ") + target.target + " " + std::to_string(target.count) + " of " +
            std::to_string(target.values) + " (first at " + std::to_string(target.firstX) + "," +
            std::to_string(target.firstY) + " " + target.firstChannel + ")";
  }
  if (!list.empty()) {
    throw NonFiniteError(frame.sceneSource + ": non-finite values in the frame: " + list + "; nothing was written");
  }
}

std::size_t clampNonFinite(Frame& frame) {
  std::size_t replaced = 0;
  for (const FrameTarget& target : frameTargets()) {
    for (float& value : (frame.*target.image).pixels) {
      if (std::isfinite(value)) continue;
      value = std::isnan(value) ? 0.0f : std::copysign(std::numeric_limits<float>::max(), value);
      ++replaced;
    }
  }
  return replaced;
}

}  // namespace headlight

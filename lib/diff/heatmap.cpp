#include "diff/heatmap.hpp"

#include <algorithm>
#include <cmath>

namespace headlight {

HeatmapScale heatmapScale(const DiffResult& result) {
  if (result.metric == DiffMetric::Flip) return {"magma", 1.0, false};
  const double twiceFail = 2.0 * result.thresholds.fail;
  if (twiceFail > 0 && std::isfinite(twiceFail)) return {"inferno", twiceFail, true};
  const ImageF& diff = result.difference;
  double largest = 0;
  if (!diff.channels.empty())
    for (std::size_t p = diff.channels.size() - 1; p < diff.pixels.size(); p += diff.channels.size())
      if (std::isfinite(diff.pixels[p])) largest = std::max(largest, double(diff.pixels[p]));
  return {"inferno", largest > 0 ? largest : 1.0, false};
}

}  // namespace headlight

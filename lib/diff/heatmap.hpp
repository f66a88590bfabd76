// How a comparison's `error` channel becomes its heatmap: the colour map and
// the error drawn at full scale. writeDiffImages draws the heatmap and its
// colour scale with it; diff's HTML report labels that scale with it.
#pragma once

#include <string_view>

#include "headlight/diff.hpp"

namespace headlight {

struct HeatmapScale {
  std::string_view colorMap;  // an OpenImageIO colour map: "magma" for FLIP, else "inferno"
  double fullScale = 1;       // the error at the ramp's end; larger errors saturate
  bool failAtMiddle = false;  // the fail threshold is half of fullScale
};

// FLIP maps as FLIP's papers show them (0..1 through magma); any other metric
// scaled so the fail threshold sits mid-ramp and twice it saturates, or, with
// no positive finite threshold, so the largest finite error does.
HeatmapScale heatmapScale(const DiffResult& result);

}  // namespace headlight

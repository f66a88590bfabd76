#include "image_io/color_maps.hpp"

#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <vector>

#include "color/srgb.hpp"
#include "headlight/error.hpp"

namespace headlight {

OIIO::ImageBuf displayColorMap(const OIIO::ImageBuf& values, const std::string& map) {
  OIIO::ImageBuf colors = OIIO::ImageBufAlgo::color_map(values, 0, map);
  if (colors.has_error()) throw IoError("colour map " + map + ": " + colors.geterror());
  std::vector<float> pixels(colors.roi().npixels() * std::size_t(colors.nchannels()));
  colors.get_pixels(colors.roi(), OIIO::TypeDesc::FLOAT, pixels.data());
  for (float& v : pixels) v = linearToSrgb(std::clamp(v, 0.0f, 1.0f));
  colors.set_pixels(colors.roi(), OIIO::TypeDesc::FLOAT, pixels.data());
  return colors;
}

}  // namespace headlight

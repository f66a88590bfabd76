// Environment map files through OpenImageIO (lib/image_io/environment_decode.hpp).
#include "image_io/environment_decode.hpp"

#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>

#include "io/message_text.hpp"

namespace headlight::detail {
namespace {

std::string sizeText(int width, int height) { return std::to_string(width) + "x" + std::to_string(height); }

std::string mebibytes(std::uint64_t bytes) { return std::to_string((bytes + (1u << 20) - 1) >> 20) + " MiB"; }

// The first value that is not a finite radiance (NaN, infinite or
// negative), named by texel and channel; "" when all are.
std::string firstBadValue(const DecodedEnvironment& map) {
  static constexpr const char* kChannel[] = {"R", "G", "B"};
  for (std::size_t i = 0; i < map.rgb.size(); ++i) {
    const float value = map.rgb[i];
    if (std::isfinite(value) && value >= 0.0f) continue;
    const std::size_t texel = i / 3;
    const std::string where = "texel (" + std::to_string(texel % std::size_t(map.width)) + ", " +
                              std::to_string(texel / std::size_t(map.width)) + ") " + kChannel[i % 3];
    const std::string what = std::isnan(value) ? "nan" : std::isinf(value) ? (value > 0 ? "inf" : "-inf")
                                                                           : std::to_string(value);
    return "has " + where + " = " + what + "; radiance must be finite and >= 0";
  }
  return {};
}

}  // namespace

// Rows read at a time (decodeEnvironment).
constexpr int kBandRows = 64;

std::string decodeEnvironment(const char* path, std::uint64_t maxBytes, int maxSide, DecodedEnvironment& map) {
  auto input = OIIO::ImageInput::open(path);
  if (!input) return "cannot be read by OpenImageIO: " + oneLine(OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  const int width = spec.width, height = spec.height;
  if (width < 2 || height < 1 || spec.nchannels < 1)
    return "is " + sizeText(width, height) + " with " + std::to_string(spec.nchannels) +
           " channel(s); expected an equirectangular image of at least 2x1";
  if (std::int64_t(width) != 2 * std::int64_t(height))
    return "is " + sizeText(width, height) + ", not equirectangular: its width must be twice its height (2:1)";
  if (width > maxSide) return "is " + sizeText(width, height) + ", wider than " + std::to_string(maxSide) + " texels";
  const std::uint64_t bytes = std::uint64_t(width) * std::uint64_t(height) * kEnvironmentBytesPerTexel;
  if (bytes > maxBytes)
    return "is " + sizeText(width, height) + " and needs about " + mebibytes(bytes) +
           ", more than max-memory allows (" + mebibytes(maxBytes) + "); raise max-memory";
  const int channels = std::min(spec.nchannels, 3);
  const std::size_t texels = std::size_t(width) * std::size_t(height);
  // Scanline files are read in bands of rows, the map growing as they
  // arrive: one whose header declares more than its data holds (a 52-byte
  // .hdr declaring 16384x8192) fails at its first band, before the map's
  // memory is taken (1.7 GB was). Tiled files are read whole.
  const int bandRows = spec.tile_width > 0 ? height : std::min(height, kBandRows);
  std::vector<float> band(std::size_t(width) * std::size_t(bandRows) * std::size_t(channels));
  map.rgb.clear();
  for (int y = 0; y < height; y += bandRows) {
    const int rows = std::min(bandRows, height - y);
    const bool read = spec.tile_width > 0 ? input->read_image(0, 0, 0, channels, OIIO::TypeDesc::FLOAT, band.data())
                                          : input->read_scanlines(0, 0, spec.y + y, spec.y + y + rows, 0, 0, channels,
                                                                  OIIO::TypeDesc::FLOAT, band.data());
    if (!read) return "is truncated or corrupt: OpenImageIO failed reading its pixels: " + oneLine(input->geterror());
    const std::size_t bandTexels = std::size_t(width) * std::size_t(rows);
    const std::size_t start = map.rgb.size();
    map.rgb.resize(start + bandTexels * 3);
    for (std::size_t texel = 0; texel < bandTexels; ++texel)
      for (int c = 0; c < 3; ++c)  // grey (and grey + alpha) spread to RGB
        map.rgb[start + texel * 3 + std::size_t(c)] =
            band[texel * std::size_t(channels) + std::size_t(channels < 3 ? 0 : c)];
  }
  if (map.rgb.size() != texels * 3) return "is truncated or corrupt: fewer rows than its header declares";
  map.width = width;
  map.height = height;
  return firstBadValue(map);
}

}  // namespace headlight::detail

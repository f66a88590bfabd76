// The difference images headlight diff --out writes: diff.exr (the raw
// differences and the error channel), its heatmap, and for the Flip metric
// the two images as FLIP saw them; the heatmap's colour scale.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>

#include "color/srgb.hpp"
#include "diff/flip.hpp"
#include "diff/heatmap.hpp"
#include "headlight/diff.hpp"
#include "headlight/error.hpp"
#include "image_io/atomic_image.hpp"
#include "image_io/color_maps.hpp"
#include "image_io/image_files.hpp"

namespace headlight {
namespace {

namespace fs = std::filesystem;
using diffio::checkOk;
using diffio::loadImage;
using diffio::rgbChannels;

// An image as the Flip metric saw it, as an 8-bit sRGB PNG at `path`: an
// integer (display) image as it is, a float one at the middle of the
// HDR-FLIP exposures, ACES tone mapped.
void writeFlipView(const fs::path& source, const DiffResult& result, const fs::path& path) {
  std::string problem;
  bool integer = false;
  const std::optional<OIIO::ImageBuf> image = loadImage(source, problem, integer);
  if (!image) throw IoError(path.string() + ": cannot show " + problem);
  const std::vector<int> rgb = rgbChannels(image->spec().channelnames);
  if (rgb.empty()) throw IoError(path.string() + ": " + source.string() + " has no R, G, B channels to show");
  const OIIO::ImageBuf picked = OIIO::ImageBufAlgo::channels(*image, 3, rgb);
  checkOk(picked, "channels");
  std::vector<float> pixels(picked.roi().npixels() * 3);
  picked.get_pixels(picked.roi(), OIIO::TypeDesc::FLOAT, pixels.data());
  const bool hdr = !result.flip || result.flip->hdr;
  const float scale =
      hdr && result.flip ? float(std::exp2(0.5 * (result.flip->startExposure + result.flip->stopExposure))) : 1.0f;
  for (float& v : pixels) {
    const float shown = hdr ? linearToSrgb(std::clamp(flip::acesToneMap(std::max(v, 0.0f) * scale), 0.0f, 1.0f)) : v;
    v = std::isfinite(shown) ? std::clamp(shown, 0.0f, 1.0f) : 0.0f;
  }
  OIIO::ImageSpec spec(picked.spec().width, picked.spec().height, 3, OIIO::TypeDesc::FLOAT);
  spec.channelnames = {"R", "G", "B"};
  OIIO::ImageBuf view(spec);
  view.set_pixels(view.roi(), OIIO::TypeDesc::FLOAT, pixels.data());
  OIIO::ImageSpec pngSpec = spec;
  pngSpec.set_format(OIIO::TypeDesc::UINT8);
  pngSpec.attribute("oiio:ColorSpace", "sRGB");
  detail::writeImageAtomically(path, view, pngSpec, "png");
}

}  // namespace

std::vector<fs::path> writeDiffImages(const DiffResult& result, const fs::path& exrPath) {
  namespace iba = OIIO::ImageBufAlgo;
  const ImageF& diff = result.difference;
  if (diff.empty())
    throw Error("writeDiffImages: " + exrPath.string() + ": the comparison ended in '" +
                std::string(statusName(result.status)) + "', so there is no difference image");
  OIIO::ImageSpec spec(diff.width, diff.height, diff.channelCount(), OIIO::TypeDesc::FLOAT);
  spec.channelnames = diff.channels;
  OIIO::ImageBuf buffer(spec);
  buffer.set_pixels(buffer.roi(), OIIO::TypeDesc::FLOAT, diff.pixels.data());
  OIIO::ImageSpec exrSpec = spec;
  exrSpec.attribute("compression", "zip");
  exrSpec.attribute("headlight:diff:a", result.a.string());
  exrSpec.attribute("headlight:diff:b", result.b.string());
  exrSpec.attribute("headlight:diff:target", result.target);
  exrSpec.attribute("headlight:diff:metric", std::string(metricName(result.metric)));
  exrSpec.attribute("headlight:diff:fail", float(result.thresholds.fail));
  exrSpec.attribute("headlight:diff:status", std::string(statusName(result.status)));

  // Heatmap: the error channel over the scale's full range through its
  // colour map (diff/heatmap.hpp); +inf (NaN/Inf inputs) saturates.
  const HeatmapScale scale = heatmapScale(result);
  const std::string colorMap(scale.colorMap);
  const int errorChannel = diff.channelCount() - 1;
  const OIIO::ImageBuf error = iba::channels(buffer, 1, OIIO::cspan<int>(&errorChannel, 1));
  const OIIO::ImageBuf scaled = iba::clamp(iba::mul(error, float(1.0 / scale.fullScale)), 0.0f, 1.0f);
  const OIIO::ImageBuf heat = displayColorMap(scaled, colorMap);
  OIIO::ImageSpec pngSpec = heat.spec();
  pngSpec.set_format(OIIO::TypeDesc::UINT8);
  pngSpec.attribute("oiio:ColorSpace", "sRGB");
  // The colour scale: 0 at the left to fullScale at the right, through the same map.
  OIIO::ImageBuf ramp(OIIO::ImageSpec(256, 12, 1, OIIO::TypeDesc::FLOAT));
  const float left = 0.0f, right = 1.0f;
  iba::fill(ramp, {&left, 1}, {&right, 1}, {&left, 1}, {&right, 1});
  const OIIO::ImageBuf rampColors = displayColorMap(ramp, colorMap);
  OIIO::ImageSpec rampSpec = rampColors.spec();
  rampSpec.set_format(OIIO::TypeDesc::UINT8);
  rampSpec.attribute("oiio:ColorSpace", "sRGB");

  fs::path pngPath = exrPath;
  pngPath.replace_extension(".png");
  detail::writeImageAtomically(exrPath, buffer, exrSpec, "openexr");
  detail::writeImageAtomically(pngPath, heat, pngSpec, "png");
  fs::path scalePath = exrPath;
  scalePath.replace_filename(exrPath.stem().string() + "_scale.png");
  detail::writeImageAtomically(scalePath, rampColors, rampSpec, "png");
  std::vector<fs::path> written{exrPath, pngPath, scalePath};
  if (result.metric == DiffMetric::Flip) {
    // What FLIP compared, for a report to show beside the map.
    for (const auto& [source, suffix] : {std::pair{result.a, "_a.png"}, std::pair{result.b, "_b.png"}}) {
      fs::path path = exrPath;
      path.replace_filename(exrPath.stem().string() + suffix);
      writeFlipView(source, result, path);
      written.push_back(path);
    }
  }
  return written;
}

}  // namespace headlight

#include "image_io/target_pngs.hpp"

#include <OpenImageIO/imagebuf.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>
#include <vector>

#include "color/srgb.hpp"
#include "headlight/error.hpp"
#include "image_io/atomic_image.hpp"
#include "image_io/color_maps.hpp"
#include "output/tonemap.hpp"
#include "settings/preview_background.hpp"

namespace headlight {
namespace {

namespace fs = std::filesystem;

std::uint8_t toByte(float display) {
  return std::uint8_t(std::clamp(std::isfinite(display) ? display : 0.0f, 0.0f, 1.0f) * 255.0f + 0.5f);
}

// Linear radiance to display: the frame's exposure and tone curve, then sRGB.
float radianceToDisplay(float linear, const RenderSettings& settings) {
  float v = linear * std::exp2(settings.exposure);
  v = std::isfinite(v) ? std::max(0.0f, v) : 0.0f;
  return linearToSrgb(std::clamp(settings.tonemap == Tonemap::Aces ? tonemapAces(v) : tonemapReinhard(v), 0.0f, 1.0f));
}

// Pixels of `image` that show geometry: where its "A" channel (coverage) is
// above 0, every pixel for an image without one.
std::vector<bool> geometryMask(const ImageF& image) {
  const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height), count = image.channels.size();
  const auto alpha = std::find(image.channels.begin(), image.channels.end(), "A");
  std::vector<bool> mask(pixels, true);
  if (alpha != image.channels.end())
    for (std::size_t p = 0; p < pixels; ++p)
      mask[p] = image.pixels[p * count + std::size_t(alpha - image.channels.begin())] > 0.0f;
  return mask;
}

// Display values (0..1, three a pixel) of `image` through `look`.
std::vector<float> displayValues(const Frame& frame, const ImageF& image, PngLook look) {
  const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height), count = image.channels.size();
  const auto value = [&](std::size_t p, std::size_t c) { return c < count ? image.pixels[p * count + c] : 0.0f; };
  std::vector<float> shown(pixels * 3, 0.0f);
  switch (look) {
    case PngLook::Radiance:
      for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < 3; ++c) shown[p * 3 + c] = radianceToDisplay(value(p, c), frame.settings);
      break;
    case PngLook::Color:
      for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < 3; ++c) shown[p * 3 + c] = linearToSrgb(std::clamp(value(p, c), 0.0f, 1.0f));
      break;
    case PngLook::Signed:
      for (std::size_t p = 0; p < pixels; ++p) {
        const float x = value(p, 0), y = value(p, 1), z = value(p, 2);
        if (x * x + y * y + z * z > 1e-12f)
          for (std::size_t c = 0; c < 3; ++c) shown[p * 3 + c] = 0.5f * value(p, c) + 0.5f;
      }
      break;
    case PngLook::Grey:
      for (std::size_t p = 0; p < pixels; ++p) shown[p * 3] = shown[p * 3 + 1] = shown[p * 3 + 2] = value(p, 0);
      break;
    case PngLook::Values:
      for (std::size_t p = 0; p < pixels; ++p)
        for (std::size_t c = 0; c < 3; ++c) shown[p * 3 + c] = value(p, c);
      break;
    case PngLook::Range: {
      const std::vector<bool> geometry = geometryMask(image);
      for (std::size_t c = 0; c < 3 && c < count; ++c) {
        float low = std::numeric_limits<float>::max(), high = -low;
        for (std::size_t p = 0; p < pixels; ++p)
          if (geometry[p] && std::isfinite(value(p, c)))
            low = std::min(low, value(p, c)), high = std::max(high, value(p, c));
        const float span = high > low ? high - low : 1.0f;
        for (std::size_t p = 0; p < pixels; ++p)
          if (geometry[p]) shown[p * 3 + c] = (value(p, c) - low) / span;
      }
      break;
    }
    case PngLook::Depth: {
      // Background holds the far plane (targets.cpp); near is bright (viridis' yellow).
      const float background = frame.view.farPlane * (1.0f - 1e-6f);
      float low = std::numeric_limits<float>::max(), high = 0.0f;
      for (std::size_t p = 0; p < pixels; ++p)
        if (const float z = value(p, 0); std::isfinite(z) && z < background)
          low = std::min(low, z), high = std::max(high, z);
      OIIO::ImageBuf ramp(OIIO::ImageSpec(image.width, image.height, 1, OIIO::TypeDesc::FLOAT));
      std::vector<float> t(pixels, 0.0f);
      for (std::size_t p = 0; p < pixels; ++p)
        if (const float z = value(p, 0); std::isfinite(z) && z < background)
          t[p] = high > low ? (high - z) / (high - low) : 1.0f;
      ramp.set_pixels(ramp.roi(), OIIO::TypeDesc::FLOAT, t.data());
      const OIIO::ImageBuf colors = displayColorMap(ramp, "viridis");
      colors.get_pixels(colors.roi(), OIIO::TypeDesc::FLOAT, shown.data());
      for (std::size_t p = 0; p < pixels; ++p)
        if (const float z = value(p, 0); !(std::isfinite(z) && z < background))
          shown[p * 3] = shown[p * 3 + 1] = shown[p * 3 + 2] = 0.0f;
      break;
    }
  }
  return shown;
}

WrittenFile writePng(const fs::path& path, int width, int height, int channels, const std::vector<std::uint8_t>& bytes,
                     const std::string& description) {
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  if (channels == 4) spec.alpha_channel = 3;
  detail::writePixelsAtomically(path, bytes.data(), OIIO::TypeDesc::UINT8, spec, "png");
  WrittenFile file{
      path, path.string() + ": " + std::to_string(width) + "x" + std::to_string(height) + " " + description, 0, 0, 0};
  std::error_code error;
  file.bytes = std::size_t(fs::file_size(path, error));
  return file;
}

std::string_view lookName(PngLook look) {
  switch (look) {
    case PngLook::Radiance:
      return "tone mapped like preview.png";
    case PngLook::Color:
      return "linear colour, sRGB-encoded";
    case PngLook::Signed:
      return "vectors as (v + 1) / 2";
    case PngLook::Range:
      return "each channel over its range on geometry";
    case PngLook::Depth:
      return "viridis, near yellow to far purple";
    case PngLook::Grey:
      return "first channel as grey";
    case PngLook::Values:
      return "first three channels as they are";
  }
  return "";
}

}  // namespace

WrittenFile writeTargetPng(const Frame& frame, const FrameTarget& target, const fs::path& path) {
  const ImageF& image = frame.*target.image;
  const std::vector<float> shown = displayValues(frame, image, target.png);
  std::vector<std::uint8_t> bytes(shown.size());
  std::transform(shown.begin(), shown.end(), bytes.begin(), toByte);
  return writePng(path, image.width, image.height, 3, bytes,
                  "8-bit PNG of " + std::string(target.name) + " (" + std::string(lookName(target.png)) + ")");
}

WrittenFile writePreview(const Frame& frame, const fs::path& path) {
  const ImageF& lit = frame.lit;
  const PreviewBackground background = parsePreviewBackground(frame.settings.previewBackground);
  const std::vector<float> shown = displayValues(frame, lit, PngLook::Radiance);
  const std::size_t pixels = std::size_t(lit.width) * std::size_t(lit.height), count = lit.channels.size();
  const auto alphaAt = std::find(lit.channels.begin(), lit.channels.end(), "A");
  const auto coverage = [&](std::size_t p) {
    return alphaAt == lit.channels.end()
               ? 1.0f
               : std::clamp(lit.pixels[p * count + std::size_t(alphaAt - lit.channels.begin())], 0.0f, 1.0f);
  };
  const bool transparent = background.kind == PreviewBackground::Kind::Transparent;
  const std::size_t channels = transparent ? 4 : 3;
  std::vector<std::uint8_t> bytes(pixels * channels);
  for (std::size_t p = 0; p < pixels; ++p) {
    const float a = coverage(p);
    for (std::size_t c = 0; c < 3; ++c) {
      float v = shown[p * 3 + c];
      if (background.kind == PreviewBackground::Kind::Color) v = a * v + (1.0f - a) * background.color[c];
      if (transparent && a == 0.0f) v = 0.0f;  // nothing shows there: no sky colour under alpha 0
      bytes[p * channels + c] = toByte(v);
    }
    if (transparent) bytes[p * 4 + 3] = toByte(a);
  }
  std::ostringstream description;
  description << (transparent ? "8-bit sRGB preview with alpha" : "8-bit sRGB preview") << " ("
              << (frame.settings.tonemap == Tonemap::Aces ? "ACES" : "Reinhard") << ", exposure "
              << frame.settings.exposure << " EV"
              << (background.kind == PreviewBackground::Kind::Sky ? ""
                                                                  : ", background " + frame.settings.previewBackground)
              << ")";
  return writePng(path, lit.width, lit.height, int(channels), bytes, description.str());
}

}  // namespace headlight

#include "image_io/target_pngs.hpp"

#include <OpenImageIO/imagebuf.h>

#include <algorithm>
#include <array>
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

// Label k's colour: hues a golden-ratio turn apart, so neighbouring ids (a
// mesh's instances, numbered in file order) differ most; three brightness
// levels in turn tell apart ids whose hues come close.
std::array<float, 3> labelColor(std::uint32_t id) {
  const float hue = float(std::fmod(double(id) * 0.6180339887, 1.0)) * 6.0f;
  const float value = 1.0f - 0.25f * float(id % 3), saturation = 0.7f;
  const float f = hue - std::floor(hue), p = value * (1.0f - saturation), q = value * (1.0f - saturation * f),
              t = value * (1.0f - saturation * (1.0f - f));
  switch (int(hue) % 6) {
    case 0:
      return {value, t, p};
    case 1:
      return {q, value, p};
    case 2:
      return {p, value, t};
    case 3:
      return {p, q, value};
    case 4:
      return {t, p, value};
    default:
      return {value, p, q};
  }
}

// How `image` shows through `look`, one pixel at a time, so that encoding
// needs no image-sized buffer beside the 8-bit one (an 8192x8192 preview
// would take 805 MB of floats): what the whole image decides is computed
// first (Range's per-channel bounds, Depth's near and far), once.
class Look {
 public:
  Look(const Frame& frame, const ImageF& image, PngLook look)
      : frame_(frame), image_(image), look_(look), count_(image.channels.size()) {
    const std::size_t pixels = std::size_t(image.width) * std::size_t(image.height);
    if (look == PngLook::Range) {
      const auto alpha = std::find(image.channels.begin(), image.channels.end(), "A");
      if (alpha != image.channels.end()) alpha_ = std::size_t(alpha - image.channels.begin());
      for (std::size_t c = 0; c < 3; ++c) {
        low_[c] = std::numeric_limits<float>::max();
        high_[c] = -low_[c];
        for (std::size_t p = 0; p < pixels; ++p)
          if (geometry(p) && std::isfinite(value(p, c)))
            low_[c] = std::min(low_[c], value(p, c)), high_[c] = std::max(high_[c], value(p, c));
      }
    }
    if (look == PngLook::Depth) {
      // Background holds the far plane (targets.cpp); near is viridis' yellow end.
      background_ = frame.view.farPlane * (1.0f - 1e-6f);
      low_[0] = std::numeric_limits<float>::max();
      high_[0] = 0.0f;
      for (std::size_t p = 0; p < pixels; ++p)
        if (const float z = value(p, 0); std::isfinite(z) && z < background_)
          low_[0] = std::min(low_[0], z), high_[0] = std::max(high_[0], z);
      // viridis in 256 steps, display-encoded (displayColorMap).
      OIIO::ImageBuf ramp(OIIO::ImageSpec(256, 1, 1, OIIO::TypeDesc::FLOAT));
      std::vector<float> steps(256);
      for (std::size_t k = 0; k < steps.size(); ++k) steps[k] = float(k) / 255.0f;
      ramp.set_pixels(ramp.roi(), OIIO::TypeDesc::FLOAT, steps.data());
      palette_.resize(256 * 3);
      displayColorMap(ramp, "viridis")
          .get_pixels(OIIO::ROI(0, 256, 0, 1, 0, 1, 0, 3), OIIO::TypeDesc::FLOAT, palette_.data());
    }
  }

  // Pixel p's display values, 0..1.
  std::array<float, 3> operator()(std::size_t p) const {
    std::array<float, 3> shown{};
    switch (look_) {
      case PngLook::Radiance:
        for (std::size_t c = 0; c < 3; ++c) shown[c] = radianceToDisplay(value(p, c), frame_.settings);
        break;
      case PngLook::Color:
        for (std::size_t c = 0; c < 3; ++c) shown[c] = linearToSrgb(std::clamp(value(p, c), 0.0f, 1.0f));
        break;
      case PngLook::Signed:
        if (const float x = value(p, 0), y = value(p, 1), z = value(p, 2); x * x + y * y + z * z > 1e-12f)
          for (std::size_t c = 0; c < 3; ++c) shown[c] = 0.5f * value(p, c) + 0.5f;
        break;
      case PngLook::Grey:
        shown.fill(value(p, 0));
        break;
      case PngLook::Values:
        for (std::size_t c = 0; c < 3; ++c) shown[c] = value(p, c);
        break;
      case PngLook::Range:
        if (geometry(p))
          for (std::size_t c = 0; c < 3 && c < count_; ++c)
            shown[c] = (value(p, c) - low_[c]) / (high_[c] > low_[c] ? high_[c] - low_[c] : 1.0f);
        break;
      case PngLook::Depth:
        if (const float z = value(p, 0); std::isfinite(z) && z < background_) {
          const float t = high_[0] > low_[0] ? (high_[0] - z) / (high_[0] - low_[0]) : 1.0f;
          const std::size_t step = std::size_t(std::clamp(t, 0.0f, 1.0f) * 255.0f + 0.5f);
          for (std::size_t c = 0; c < 3; ++c) shown[c] = palette_[step * 3 + c];
        }
        break;
      case PngLook::Labels:
        if (const float id = value(p, 0); id > 0.0f) shown = labelColor(std::uint32_t(id));
        break;
    }
    return shown;
  }

 private:
  float value(std::size_t p, std::size_t c) const { return c < count_ ? image_.pixels[p * count_ + c] : 0.0f; }
  // Geometry where the image's "A" channel (coverage) is above 0; every pixel without one.
  bool geometry(std::size_t p) const { return alpha_ == kNoAlpha || image_.pixels[p * count_ + alpha_] > 0.0f; }

  static constexpr std::size_t kNoAlpha = std::size_t(-1);
  const Frame& frame_;
  const ImageF& image_;
  PngLook look_;
  std::size_t count_, alpha_ = kNoAlpha;
  std::array<float, 3> low_{}, high_{};
  float background_ = 0.0f;
  std::vector<float> palette_;  // Depth: 256 viridis colours, display values
};

WrittenFile writePng(const fs::path& path, int width, int height, int channels, const std::vector<std::uint8_t>& bytes,
                     const std::string& description) {
  OIIO::ImageSpec spec(width, height, channels, OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  if (channels == 4) spec.alpha_channel = 3;
  // The bytes are straight alpha, as PNG stores it: OpenImageIO otherwise
  // takes them as premultiplied and divides by alpha on write, brightening
  // every pixel of fractional coverage (an antialiased or blended edge).
  spec.attribute("oiio:UnassociatedAlpha", 1);
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
    case PngLook::Labels:
      return "each instance id a colour, background black";
  }
  return "";
}

}  // namespace

WrittenFile writeTargetPng(const Frame& frame, const FrameTarget& target, const fs::path& path) {
  const ImageF& image = frame.*target.image;
  const Look look(frame, image, target.png);
  std::vector<std::uint8_t> bytes(std::size_t(image.width) * std::size_t(image.height) * 3);
  for (std::size_t p = 0; p < bytes.size() / 3; ++p) {
    const std::array<float, 3> shown = look(p);
    for (std::size_t c = 0; c < 3; ++c) bytes[p * 3 + c] = toByte(shown[c]);
  }
  return writePng(path, image.width, image.height, 3, bytes,
                  "8-bit PNG of " + std::string(target.name) + " (" + std::string(lookName(target.png)) + ")");
}

namespace {

// What preview.png shows of an antialiased frame over a colour or
// transparent: the samples' foreground (Frame::litForeground, RGB x A and A)
// unpremultiplied, so a silhouette's edge pixel is the surface's colour at
// its coverage, without the sky that lit's RGB mixes in there.
ImageF foregroundOf(const Frame& frame) {
  ImageF image = frame.litForeground;
  for (std::size_t p = 0; p + 3 < image.pixels.size(); p += 4) {
    const float a = image.pixels[p + 3];
    for (std::size_t c = 0; c < 3; ++c) image.pixels[p + c] = a > 0.0f ? image.pixels[p + c] / a : 0.0f;
  }
  return image;
}

}  // namespace

WrittenFile writePreview(const Frame& frame, const fs::path& path) {
  const PreviewBackground background = parsePreviewBackground(frame.settings.previewBackground);
  const bool overBackground = background.kind != PreviewBackground::Kind::Sky && !frame.litForeground.empty() &&
                              frame.litForeground.width == frame.lit.width &&
                              frame.litForeground.height == frame.lit.height &&
                              frame.litForeground.channels.size() == 4;
  const ImageF foreground = overBackground ? foregroundOf(frame) : ImageF{};
  const ImageF& lit = overBackground ? foreground : frame.lit;
  const Look look(frame, lit, PngLook::Radiance);
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
    const std::array<float, 3> shown = look(p);
    for (std::size_t c = 0; c < 3; ++c) {
      float v = shown[c];
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

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "headlight/targets.hpp"
#include "output/atomic_file.hpp"

namespace headlight {
namespace {

namespace fs = std::filesystem;

OIIO::ImageBuf toImageBuf(const ImageF& image) {
  OIIO::ImageSpec spec(image.width, image.height, image.channelCount(), OIIO::TypeDesc::FLOAT);
  spec.channelnames = image.channels;
  spec.alpha_channel = -1;
  for (int c = 0; c < image.channelCount(); ++c)
    if (image.channels[std::size_t(c)] == "A") spec.alpha_channel = c;
  OIIO::ImageBuf buffer(spec);
  buffer.set_pixels(OIIO::ROI::All(), OIIO::TypeDesc::FLOAT, image.pixels.data());
  return buffer;
}

void addMatrix(OIIO::ImageSpec& spec, const char* name, const glm::mat4& columnMajor) {
  // glm stores column vectors column by column; OpenEXR's M44f multiplies
  // row vectors (p * M), whose matrix is the transpose, stored row by row:
  // the same sixteen floats in the same order.
  spec.attribute(name, OIIO::TypeDesc::TypeMatrix44, &columnMajor[0][0]);
}

void addMetadata(OIIO::ImageSpec& spec, const Frame& frame) {
  addMatrix(spec, "worldToCamera", frame.view.view);
  addMatrix(spec, "worldToNDC", frame.view.projection * frame.view.view);
  spec.attribute("headlight:near", frame.view.nearPlane);
  spec.attribute("headlight:far", frame.view.farPlane);
  spec.attribute("headlight:projection", frame.view.orthographic ? "orthographic" : "perspective");
  spec.attribute("headlight:renderer", frame.glRenderer);
  spec.attribute("headlight:glVersion", frame.glVersion);
  spec.attribute("headlight:backend", frame.backend);
  spec.attribute("headlight:scene", frame.sceneSource);
  spec.attribute("headlight:sceneHash", frame.sceneHash);
  spec.attribute("headlight:conventions",
                 "right-handed world, +Y up; camera looks down -Z; rows top first; depth.Z = view-space depth");
  // As used: "auto" values appear as the numbers they resolved to.
  for (const auto& [name, value] : settingsAsText(frame.settings))
    spec.attribute(std::string(kSettingAttributePrefix) + name, value);
}

std::string summarize(const fs::path& path, const ImageF& image, const char* type) {
  std::ostringstream line;
  line << path.string() << ": " << image.width << "x" << image.height << " " << type << " ";
  const OIIO::ImageBufAlgo::PixelStats stats = OIIO::ImageBufAlgo::computePixelStats(toImageBuf(image));
  for (int c = 0; c < image.channelCount(); ++c)
    line << (c ? ", " : "") << image.channels[std::size_t(c)] << " [" << stats.min[std::size_t(c)] << ", "
         << stats.max[std::size_t(c)] << "]";
  return line.str();
}

}  // namespace

float tonemapAces(float x) {
  const float a = 2.51f, b = 0.03f, c = 2.43f, d = 0.59f, e = 0.14f;
  return std::clamp((x * (a * x + b)) / (x * (c * x + d) + e), 0.0f, 1.0f);
}

float tonemapReinhard(float x) { return x / (1.0f + x); }

WrittenFile writeExr(const Frame& frame, const ImageF& image, const fs::path& path, bool halfFloat,
                     const ExrAttributes& extra) {
  OIIO::ImageBuf buffer = toImageBuf(image);
  OIIO::ImageSpec spec = buffer.spec();
  spec.set_format(halfFloat ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT);
  spec.attribute("compression", "zip");
  addMetadata(spec, frame);
  for (const auto& [name, value] : extra) spec.attribute(name, value);
  detail::writeImageAtomically(path, buffer, spec, "openexr");
  return {path, summarize(path, image, halfFloat ? "half" : "float")};
}

WrittenFile writePreview(const Frame& frame, const fs::path& path) {
  const ImageF& lit = frame.lit;
  const float scale = std::exp2(frame.settings.exposure);
  auto curve = frame.settings.tonemap == Tonemap::Aces ? tonemapAces : tonemapReinhard;
  ImageF display;
  display.width = lit.width;
  display.height = lit.height;
  display.channels = {"R", "G", "B"};
  display.pixels.reserve(std::size_t(lit.width) * std::size_t(lit.height) * 3);
  for (std::size_t p = 0; p < lit.pixels.size(); p += 4)
    for (int c = 0; c < 3; ++c) display.pixels.push_back(curve(std::max(0.0f, lit.pixels[p + std::size_t(c)] * scale)));
  // The sRGB transfer function, through OpenImageIO's colour management.
  OIIO::ImageBuf linear = toImageBuf(display);
  OIIO::ImageBuf encoded = OIIO::ImageBufAlgo::colorconvert(linear, "linear", "sRGB");
  if (encoded.has_error()) throw IoError(path.string() + ": sRGB conversion failed: " + encoded.geterror());
  OIIO::ImageSpec spec = encoded.spec();
  spec.set_format(OIIO::TypeDesc::UINT8);
  spec.attribute("oiio:ColorSpace", "sRGB");
  detail::writeImageAtomically(path, encoded, spec, "png");
  std::ostringstream line;
  line << path.string() << ": " << lit.width << "x" << lit.height << " 8-bit sRGB preview ("
       << (frame.settings.tonemap == Tonemap::Aces ? "ACES" : "Reinhard") << ", exposure " << frame.settings.exposure
       << " EV)";
  return {path, line.str()};
}

std::vector<WrittenFile> writeFrame(const Frame& frame, const fs::path& outDir) {
  std::error_code error;
  fs::create_directories(outDir, error);
  if (error) throw IoError(outDir.string() + ": cannot create the output folder: " + error.message());
  std::vector<WrittenFile> written;
  for (const FrameTarget& target : frameTargets()) {
    const ImageF& image = frame.*target.image;
    if (!image.empty())
      written.push_back(
          writeExr(frame, image, outDir / (std::string(target.name) + ".exr"), target.storage == ExrStorage::Half));
  }
  written.push_back(writePreview(frame, outDir / "preview.png"));
  // A target this frame lacks (ssgi with SSGI off, emissive for a scene
  // without glow) must not survive from an earlier render into the folder,
  // where a diff would take it for this one's.
  for (const FrameTarget& target : frameTargets()) {
    std::error_code ignored;
    if ((frame.*target.image).empty()) fs::remove(outDir / (std::string(target.name) + ".exr"), ignored);
  }
  return written;
}

std::map<std::string, std::string> readSettingAttributes(const fs::path& exr) {
  auto input = OIIO::ImageInput::open(exr.string());
  if (!input) throw IoError(exr.string() + ": cannot read: " + OIIO::geterror());
  std::map<std::string, std::string> settings;
  for (const OIIO::ParamValue& attribute : input->spec().extra_attribs) {
    const std::string name = attribute.name().string();
    if (name.rfind(kSettingAttributePrefix, 0) == 0)
      settings[name.substr(kSettingAttributePrefix.size())] = attribute.get_string();
  }
  return settings;
}

}  // namespace headlight

// glTF images through OpenImageIO (lib/image_io/texture_decode.hpp).
#include "image_io/texture_decode.hpp"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cctype>
#include <cstring>
#include <string_view>

#include "io/message_text.hpp"

namespace headlight::detail {
namespace {

// OpenImageIO picks its reader by file extension; embedded images have none,
// so the signature bytes name the format: "png", "jpg", "gif", "bmp",
// "webp", or "" for none of them.
std::string_view signatureFormat(const unsigned char* bytes, std::size_t size) {
  auto startsWith = [&](std::string_view magic, std::size_t at = 0) {
    return size >= at + magic.size() && std::memcmp(bytes + at, magic.data(), magic.size()) == 0;
  };
  if (startsWith("\x89PNG")) return "png";
  if (startsWith("\xFF\xD8\xFF")) return "jpg";
  if (startsWith("GIF8")) return "gif";
  if (startsWith("BM")) return "bmp";
  if (startsWith("RIFF") && startsWith("WEBP", 8)) return "webp";
  return "";
}

// Why OpenImageIO could not open `bytes` (signature format `format`), in the
// user's terms: what their signature says they are (where there is none,
// OpenImageIO's "Not a PNG file" named a format the bytes never claimed)
// and, for a WebP, whether its RIFF header declares more bytes than there are.
std::string undecodable(const unsigned char* bytes, std::size_t size, std::string_view format) {
  if (format.empty())
    return "OpenImageIO cannot decode it: its " + std::to_string(size) +
           " bytes start with no PNG, JPEG, GIF, BMP or WebP signature";
  std::string name(format);
  for (char& c : name) c = char(std::toupper(static_cast<unsigned char>(c)));
  std::string why = "OpenImageIO cannot decode it as the " + name + " its signature says it is";
  if (format == "webp" && size >= 8) {
    const std::uint64_t declared = std::uint64_t(bytes[4]) | std::uint64_t(bytes[5]) << 8 |
                                   std::uint64_t(bytes[6]) << 16 | std::uint64_t(bytes[7]) << 24;
    if (declared + 8 > size)
      why += " (truncated: " + std::to_string(size) + " of the " + std::to_string(declared + 8) +
             " bytes its RIFF header declares)";
  }
  return why;
}

// Any 1..4 channel image becomes RGBA: grey is copied to RGB, and a missing
// alpha is opaque.
std::vector<std::uint8_t> expandToRgba(const std::vector<std::uint8_t>& pixels, int channels, std::size_t pixelCount) {
  std::vector<std::uint8_t> rgba(pixelCount * 4);
  for (std::size_t pixel = 0; pixel < pixelCount; ++pixel) {
    const std::uint8_t* in = &pixels[pixel * static_cast<std::size_t>(channels)];
    std::uint8_t* out = &rgba[pixel * 4];
    const bool grey = channels <= 2;
    out[0] = in[0];
    out[1] = grey ? in[0] : in[1];
    out[2] = grey ? in[0] : in[2];
    out[3] = channels == 2 ? in[1] : channels == 4 ? in[3] : 255;
  }
  return rgba;
}

}  // namespace

std::string decodeTexture(const unsigned char* bytes, std::size_t size, TextureDecodeLimits& limits,
                          DecodedTexture& texture, bool& overBudget) {
  OIIO::Filesystem::IOMemReader reader(bytes, size);
  OIIO::ImageSpec config;
  // glTF colours are unassociated (straight) alpha; OIIO's PNG reader would
  // otherwise premultiply them.
  config.attribute("oiio:UnassociatedAlpha", 1);
  // OIIO 2.4 ignores open()'s ioproxy argument whenever a config is given;
  // the proxy must travel inside the config instead.
  void* proxy = &reader;
  config.attribute("oiio:ioproxy", OIIO::TypeDesc::PTR, &proxy);
  const std::string_view format = signatureFormat(bytes, size);
  auto input = OIIO::ImageInput::open("embedded." + std::string(format.empty() ? "png" : format), &config);
  if (!input) return undecodable(bytes, size, format) + ": " + oneLine(OIIO::geterror());
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.width < 1 || spec.height < 1 || spec.width > limits.maxSide || spec.height > limits.maxSide) {
    return "it is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + ", expected 1.." +
           std::to_string(limits.maxSide) + " per side";
  }
  const std::int64_t texels = std::int64_t(spec.width) * spec.height;
  if (texels > limits.texelBudget) {
    overBudget = true;
    limits.refusedBy = "max-texels";
    return "it is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " (" + std::to_string(texels) +
           " texels), more than the " + std::to_string(limits.texelBudget) +
           " texels max-texels leaves for it; raise max-texels";
  }
  // Before a pixel is decoded: a 50-byte WebP may declare 16383^2 (2.75 GB at its peak).
  if (const std::uint64_t bytes = std::uint64_t(texels) * kDecodeBytesPerTexel; bytes > limits.byteBudget) {
    overBudget = true;
    limits.refusedBy = "max-memory";
    return "it is " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + " and needs about " +
           std::to_string(bytes >> 20) + " MiB to decode and keep, more than the " +
           std::to_string(limits.byteBudget >> 20) + " MiB max-memory leaves for it; raise max-memory";
  }
  limits.texelBudget -= texels;
  limits.byteBudget -= std::uint64_t(texels) * kDecodeBytesPerTexel;
  const int channels = std::min(spec.nchannels, 4);
  const std::size_t pixelCount = static_cast<std::size_t>(spec.width) * static_cast<std::size_t>(spec.height);
  std::vector<std::uint8_t> pixels(pixelCount * static_cast<std::size_t>(std::max(channels, 0)));
  // OIIO returns rows top first, which is what ImageData promises.
  if (channels < 1 || !input->read_image(0, 0, 0, channels, OIIO::TypeDesc::UINT8, pixels.data()))
    return "OpenImageIO failed reading its pixels: " + oneLine(input->geterror());
  texture.width = spec.width;
  texture.height = spec.height;
  texture.rgba = expandToRgba(pixels, channels, pixelCount);
  return {};
}

}  // namespace headlight::detail

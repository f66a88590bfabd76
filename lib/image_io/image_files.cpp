#include "image_io/image_files.hpp"

#include <algorithm>
#include <cstdint>

#include "headlight/error.hpp"
#include "io/bounded_read.hpp"

namespace headlight::diffio {

namespace fs = std::filesystem;

// Opens an image file for its header: only a regular file (a FIFO or a
// /dev/zero link named lit.exr would block or never end).
std::unique_ptr<OIIO::ImageInput> openImage(const fs::path& path, std::string& problem) {
  std::error_code error;
  if (!fs::exists(path, error)) {
    problem = path.string() + ": no such file";
    return nullptr;
  }
  if (const std::string kind = detail::nonRegularKind(path); !kind.empty()) {
    problem = path.string() + ": is " + kind + ", expected an image file";
    return nullptr;
  }
  auto input = OIIO::ImageInput::open(path.string());
  if (!input) {
    problem = path.string() + ": cannot read: " + OIIO::geterror();
    return nullptr;
  }
  const OIIO::ImageSpec& spec = input->spec();
  if (spec.deep || spec.depth > 1) {
    problem = path.string() + ": deep and volume images are not supported";
    return nullptr;
  }
  if (spec.width <= 0 || spec.height <= 0 || spec.nchannels <= 0) {
    problem = path.string() + ": declares " + std::to_string(spec.width) + "x" + std::to_string(spec.height) + "x" +
              std::to_string(spec.nchannels) + " pixels";
    return nullptr;
  }
  return input;
}

// Bytes of the image as float, from its header (no overflow: each factor < 2^31).
double declaredFloatBytes(const OIIO::ImageSpec& spec) {
  return double(spec.width) * double(spec.height) * double(spec.nchannels) * sizeof(float);
}

// Reads subimage 0 into memory as float through ImageInput (not ImageBuf's
// shared ImageCache, which may hand back an older copy of a file that was
// rewritten under the same name, as regression suites do).
// 32-bit unsigned channels (ids.exr) hold integers and come back as those
// integers: read as float, OpenImageIO would scale them to 0..1.
std::optional<OIIO::ImageBuf> readImage(OIIO::ImageInput& input, const fs::path& path, std::string& problem) {
  OIIO::ImageSpec spec = input.spec();
  const bool integers = spec.format == OIIO::TypeDesc::UINT && spec.channelformats.empty();
  spec.set_format(OIIO::TypeDesc::FLOAT);
  spec.channelformats.clear();
  OIIO::ImageBuf buffer(spec);
  bool read = false;
  if (integers) {
    std::vector<std::uint32_t> values(std::size_t(spec.width) * std::size_t(spec.height) * std::size_t(spec.nchannels));
    read = input.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT, values.data());
    std::vector<float> floats(values.begin(), values.end());
    if (read) buffer.set_pixels(buffer.roi(), OIIO::TypeDesc::FLOAT, floats.data());
  } else {
    read = input.read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, buffer.localpixels());
  }
  if (!read) {
    problem = path.string() + ": cannot read the pixels: " + input.geterror();
    return std::nullopt;
  }
  return buffer;
}

// openImage then readImage; `integer`: whether the file stores integer pixels.
std::optional<OIIO::ImageBuf> loadImage(const fs::path& path, std::string& problem, bool& integer) {
  const std::unique_ptr<OIIO::ImageInput> input = openImage(path, problem);
  if (!input) return std::nullopt;
  integer = !input->spec().format.is_floating_point();
  return readImage(*input, path, problem);
}

void checkOk(const OIIO::ImageBuf& image, const char* operation) {
  if (image.has_error()) throw Error(std::string("diff: ImageBufAlgo::") + operation + " failed: " + image.geterror());
}

// The indices of R, G and B among `channels` (by name, last component: "R"
// or "<layer>.R"), or empty when one is missing.
std::vector<int> rgbChannels(const std::vector<std::string>& channels) {
  std::vector<int> rgb;
  for (const char* wanted : {"R", "G", "B"}) {
    const auto found = std::find_if(channels.begin(), channels.end(), [&](const std::string& name) {
      const auto dot = name.rfind('.');
      return (dot == std::string::npos ? name : name.substr(dot + 1)) == wanted;
    });
    if (found == channels.end()) return {};
    rgb.push_back(int(found - channels.begin()));
  }
  return rgb;
}

}  // namespace headlight::diffio

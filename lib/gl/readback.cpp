#include "gl/readback.hpp"

#include "color/srgb.hpp"
#include "shared_layout.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <utility>

#include <glm/gtc/packing.hpp>

#include "headlight/error.hpp"

namespace headlight {
namespace {

// An 8-bit sRGB code's linear value, for each of the 256.
const std::array<float, 256>& srgbDecodeTable() {
  static const std::array<float, 256> table = [] {
    std::array<float, 256> values{};
    for (std::size_t k = 0; k < values.size(); ++k) values[k] = srgbToLinear(float(k) / 255.0f);
    return values;
  }();
  return table;
}

// Every half float's value (IEEE 754 binary16; exact in float).
const std::array<float, 65536>& halfDecodeTable() {
  static const std::array<float, 65536> table = [] {
    std::array<float, 65536> values{};
    for (std::size_t bits = 0; bits < values.size(); ++bits) values[bits] = glm::unpackHalf1x16(std::uint16_t(bits));
    return values;
  }();
  return table;
}

std::size_t componentBytes(ComponentType type) {
  return type == ComponentType::Half ? 2 : type == ComponentType::Unorm8 ? 1 : 4;  // Float, Uint32: 4
}

// Components first..last-1 of an image of `count` channels from one texture's
// rows (`components` a pixel: 4 for colour, 1 for depth; bottom-up as GL has them) into
// the image's rows (top-down): GL row y is image row height - 1 - y.
// decode(stored, component within the texture) gives the float.
template <class Stored, class Decode>
void interleaveRows(const Stored* from, std::size_t components, int width, int height, std::size_t count,
                    std::size_t first, std::size_t last, float* image, Decode decode) {
  const std::size_t rowPixels = std::size_t(width);
  for (int y = 0; y < height; ++y) {
    const Stored* row = from + std::size_t(y) * rowPixels * components;
    float* to = image + std::size_t(height - 1 - y) * rowPixels * count;
    for (std::size_t x = 0; x < rowPixels; ++x)
      for (std::size_t c = first; c < last; ++c) to[x * count + c] = decode(row[x * components + c - first], c - first);
  }
}

}  // namespace

gl::Buffer ReadbackBuffers::acquire(std::size_t bytes) {
  for (auto it = kept_.begin(); it != kept_.end(); ++it)
    if (it->size() == bytes) {
      gl::Buffer buffer = std::move(*it);
      kept_.erase(it);
      return buffer;
    }
  return gl::Buffer::createReadback(bytes);
}

void ReadbackBuffers::release(gl::Buffer buffer) {
  if (!buffer) return;
  releasedSinceTrim_ += buffer.size();
  kept_.push_back(std::move(buffer));
}

void ReadbackBuffers::trim() {
  while (keptBytes() > releasedSinceTrim_) kept_.erase(kept_.begin());
  releasedSinceTrim_ = 0;
}

std::size_t ReadbackBuffers::keptBytes() const {
  std::size_t bytes = 0;
  for (const gl::Buffer& buffer : kept_) bytes += buffer.size();
  return bytes;
}

ComponentType transferType(GLenum internalFormat) {
  switch (internalFormat) {
    case GL_RGBA16F:
      return ComponentType::Half;
    case GL_RGBA8:
    case GL_SRGB8_ALPHA8:
      return ComponentType::Unorm8;
    case GL_RGBA32UI:
      return ComponentType::Uint32;
    default:
      return ComponentType::Float;
  }
}

PixelRead::PixelRead(const gl::Texture& texture, GLenum format, int components, ReadPath path, ReadbackBuffers* buffers)
    : width_(texture.width()),
      height_(texture.height()),
      internalFormat_(texture.internalFormat()),
      type_(format == GL_DEPTH_COMPONENT ? ComponentType::Float : transferType(texture.internalFormat())) {
  const GLenum glType = type_ == ComponentType::Half     ? GL_HALF_FLOAT
                        : type_ == ComponentType::Unorm8 ? GL_UNSIGNED_BYTE
                        : type_ == ComponentType::Uint32 ? GL_UNSIGNED_INT
                                                         : GL_FLOAT;
  const std::size_t bytes =
      std::size_t(width_) * std::size_t(height_) * std::size_t(components) * componentBytes(type_);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  if (path == ReadPath::Direct) {
    bytes_.resize(bytes);
    glGetTextureImage(texture.id(), 0, format, glType, GLsizei(bytes), bytes_.data());
  } else {
    buffer_ = buffers ? buffers->acquire(bytes) : gl::Buffer::createReadback(bytes);
    glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer_.id());
    glGetTextureImage(texture.id(), 0, format, glType, GLsizei(bytes), nullptr);  // into the buffer, offset 0
    glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
  }
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
}

PixelRead::PixelRead(PixelRead&& other) noexcept
    : buffer_(std::move(other.buffer_)),
      mapped_(std::exchange(other.mapped_, nullptr)),
      bytes_(std::move(other.bytes_)),
      width_(other.width_),
      height_(other.height_),
      internalFormat_(other.internalFormat_),
      type_(other.type_) {}

PixelRead& PixelRead::operator=(PixelRead&& other) noexcept {
  if (this != &other) {
    release(nullptr);
    buffer_ = std::move(other.buffer_);
    mapped_ = std::exchange(other.mapped_, nullptr);
    bytes_ = std::move(other.bytes_);
    width_ = other.width_;
    height_ = other.height_;
    internalFormat_ = other.internalFormat_;
    type_ = other.type_;
  }
  return *this;
}

PixelRead::~PixelRead() {
  if (mapped_ && buffer_) buffer_.unmap();
}

const void* PixelRead::data() {
  if (!buffer_) return bytes_.data();
  if (!mapped_) {
    mapped_ = buffer_.mapRead();
    if (!mapped_)
      throw GlError("readback: a " + std::to_string(buffer_.size()) + "-byte pixel buffer could not be mapped");
  }
  return mapped_;
}

void PixelRead::release(ReadbackBuffers* buffers) {
  if (mapped_ && buffer_) buffer_.unmap();
  mapped_ = nullptr;
  if (buffers) buffers->release(std::move(buffer_));
  buffer_ = {};
  bytes_ = {};
}

PendingImage PendingImage::color(std::span<const gl::Texture* const> textures, std::vector<std::string> channels,
                                 ReadPath path, ReadbackBuffers* buffers) {
  if (textures.size() * 4 < channels.size() || textures.empty())
    throw GlError("readColor: " + std::to_string(channels.size()) + " channels need " +
                  std::to_string((channels.size() + 3) / 4) + " textures, got " + std::to_string(textures.size()));
  PendingImage image;
  image.buffers_ = buffers;
  for (std::size_t k = 0; k < textures.size(); ++k) {
    const gl::Texture& texture = *textures[k];
    if (texture.width() != textures.front()->width() || texture.height() != textures.front()->height())
      throw GlError("readColor: texture " + std::to_string(k) + " is " + std::to_string(texture.width()) + "x" +
                    std::to_string(texture.height()) + ", texture 0 is " + std::to_string(textures.front()->width()) +
                    "x" + std::to_string(textures.front()->height()));
    // An integer texture is read as integers (GL refuses GL_RGBA for it).
    const GLenum format = transferType(texture.internalFormat()) == ComponentType::Uint32 ? GL_RGBA_INTEGER : GL_RGBA;
    if (k * 4 < channels.size()) image.parts_.emplace_back(texture, format, 4, path, buffers);
  }
  image.channels_ = std::move(channels);
  return image;
}

PendingImage PendingImage::viewDepth(const gl::Texture& depth, const CameraView& view, std::string channel,
                                     ReadPath path, ReadbackBuffers* buffers) {
  PendingImage image;
  image.buffers_ = buffers;
  image.parts_.emplace_back(depth, GL_DEPTH_COMPONENT, 1, path, buffers);
  image.channels_ = {std::move(channel)};
  image.depthView_ = view;
  return image;
}

ImageF PendingImage::finish() {
  ImageF image;
  const int width = parts_.front().width(), height = parts_.front().height();
  image.width = width;
  image.height = height;
  image.channels = channels_;
  const std::size_t count = channels_.size();
  image.pixels.resize(std::size_t(width) * std::size_t(height) * count);
  if (depthView_) {
    const glm::dvec4 k = viewZCoefficients(*depthView_);
    interleaveRows(
        static_cast<const float*>(parts_.front().data()), 1, width, height, 1, 0, 1, image.pixels.data(),
        [&](float depth, std::size_t) { return float(-HL_VIEW_Z_FROM_NDC_DEPTH(2.0 * double(depth) - 1.0, k)); });
  } else {
    for (std::size_t part = 0; part < parts_.size(); ++part) {
      PixelRead& read = parts_[part];
      const std::size_t first = part * 4, last = std::min(count, first + 4);
      float* const to = image.pixels.data();
      switch (read.type()) {
        case ComponentType::Float:
          interleaveRows(static_cast<const float*>(read.data()), 4, width, height, count, first, last, to,
                         [](float value, std::size_t) { return value; });
          break;
        case ComponentType::Uint32:  // ids: exact below kLargestExactId, which the plan ensures
          interleaveRows(static_cast<const std::uint32_t*>(read.data()), 4, width, height, count, first, last, to,
                         [](std::uint32_t value, std::size_t) { return float(value); });
          break;
        case ComponentType::Half: {
          const std::array<float, 65536>& halves = halfDecodeTable();
          interleaveRows(static_cast<const std::uint16_t*>(read.data()), 4, width, height, count, first, last, to,
                         [&](std::uint16_t bits, std::size_t) { return halves[bits]; });
          break;
        }
        case ComponentType::Unorm8: {
          // An sRGB texture stores encoded values: decode here, alpha aside.
          const std::array<float, 256>& srgb = srgbDecodeTable();
          if (read.internalFormat() == GL_SRGB8_ALPHA8)
            interleaveRows(static_cast<const std::uint8_t*>(read.data()), 4, width, height, count, first, last, to,
                           [&](std::uint8_t code, std::size_t component) {
                             return component == 3 ? float(code) / 255.0f : srgb[code];
                           });
          else
            interleaveRows(static_cast<const std::uint8_t*>(read.data()), 4, width, height, count, first, last, to,
                           [](std::uint8_t code, std::size_t) { return float(code) / 255.0f; });
          break;
        }
      }
    }
  }
  for (PixelRead& part : parts_) part.release(buffers_);
  return image;
}

ImageF readColor(const gl::Texture& texture, std::vector<std::string> channels) {
  const gl::Texture* textures[] = {&texture};
  return PendingImage::color(textures, std::move(channels)).finish();
}

ImageF readColor(std::span<const gl::Texture* const> textures, const std::vector<std::string>& channels) {
  return PendingImage::color(textures, channels).finish();
}

glm::dvec4 viewZCoefficients(const CameraView& view) {
  const double n = view.nearPlane, f = view.farPlane;
  // In NDC depth ndc = 2d - 1: orthographic z = -(n + (ndc + 1) / 2 (f - n)),
  // perspective z = -2nf / (f + n - ndc (f - n)), each term as the shaders
  // computed it before the coefficients were shared (the same rounding).
  return view.orthographic ? glm::dvec4(-0.5 * (f + n), -0.5 * (f - n), 1.0, 0.0)
                           : glm::dvec4(-2.0 * n * f, 0.0, f + n, -(f - n));
}

ImageF readViewDepth(const gl::Texture& depth, const CameraView& view, std::string channel) {
  return PendingImage::viewDepth(depth, view, std::move(channel)).finish();
}

}  // namespace headlight

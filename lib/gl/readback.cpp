#include "gl/readback.hpp"

#include "color/srgb.hpp"
#include "shared_layout.h"

#include <algorithm>
#include <cmath>

#include "headlight/error.hpp"

namespace headlight {
namespace {

// glGetTextureImage returns rows bottom-up; images are top-down.
void flipRows(std::vector<float>& pixels, int width, int height, int channels) {
  const std::size_t row = std::size_t(width) * std::size_t(channels);
  for (int y = 0; y < height / 2; ++y)
    std::swap_ranges(pixels.begin() + std::ptrdiff_t(std::size_t(y) * row),
                     pixels.begin() + std::ptrdiff_t(std::size_t(y + 1) * row),
                     pixels.begin() + std::ptrdiff_t(std::size_t(height - 1 - y) * row));
}

}  // namespace

PixelRead::PixelRead(const gl::Texture& texture, GLenum format, int components, ReadPath path)
    : width_(texture.width()), height_(texture.height()), internalFormat_(texture.internalFormat()) {
  const std::size_t bytes = std::size_t(width_) * std::size_t(height_) * std::size_t(components) * sizeof(float);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  if (path == ReadPath::Direct) {
    pixels_.resize(bytes / sizeof(float));
    glGetTextureImage(texture.id(), 0, format, GL_FLOAT, GLsizei(bytes), pixels_.data());
    return;
  }
  buffer_ = gl::Buffer::createReadback(bytes);
  glBindBuffer(GL_PIXEL_PACK_BUFFER, buffer_.id());
  glGetTextureImage(texture.id(), 0, format, GL_FLOAT, GLsizei(bytes), nullptr);  // into the buffer, offset 0
  glBindBuffer(GL_PIXEL_PACK_BUFFER, 0);
}

std::vector<float> PixelRead::take() {
  if (!buffer_) return std::move(pixels_);
  std::vector<float> pixels(buffer_.size() / sizeof(float));
  buffer_.read(pixels.data(), buffer_.size());
  return pixels;
}

PendingImage PendingImage::color(std::span<const gl::Texture* const> textures, std::vector<std::string> channels,
                                 ReadPath path) {
  if (textures.size() * 4 < channels.size() || textures.empty())
    throw GlError("readColor: " + std::to_string(channels.size()) + " channels need " +
                  std::to_string((channels.size() + 3) / 4) + " textures, got " + std::to_string(textures.size()));
  PendingImage image;
  for (std::size_t k = 0; k < textures.size(); ++k) {
    const gl::Texture& texture = *textures[k];
    if (texture.width() != textures.front()->width() || texture.height() != textures.front()->height())
      throw GlError("readColor: texture " + std::to_string(k) + " is " + std::to_string(texture.width()) + "x" +
                    std::to_string(texture.height()) + ", texture 0 is " + std::to_string(textures.front()->width()) +
                    "x" + std::to_string(textures.front()->height()));
    if (k * 4 < channels.size()) image.parts_.emplace_back(texture, GL_RGBA, 4, path);
  }
  image.channels_ = std::move(channels);
  return image;
}

PendingImage PendingImage::viewDepth(const gl::Texture& depth, const CameraView& view, std::string channel,
                                     ReadPath path) {
  PendingImage image;
  image.parts_.emplace_back(depth, GL_DEPTH_COMPONENT, 1, path);
  image.channels_ = {std::move(channel)};
  image.depthView_ = view;
  return image;
}

ImageF PendingImage::finish() {
  ImageF image;
  image.width = parts_.front().width();
  image.height = parts_.front().height();
  image.channels = channels_;
  const std::size_t count = channels_.size(), pixels = std::size_t(image.width) * std::size_t(image.height);
  if (depthView_) {
    image.pixels = parts_.front().take();
    const glm::dvec4 k = viewZCoefficients(*depthView_);
    for (float& d : image.pixels) d = float(-HL_VIEW_Z_FROM_NDC_DEPTH(2.0 * double(d) - 1.0, k));
    flipRows(image.pixels, image.width, image.height, 1);
    return image;
  }
  image.pixels.resize(pixels * count);
  for (std::size_t k = 0; k < parts_.size(); ++k) {
    std::vector<float> rgba = parts_[k].take();
    // GL returns the stored (encoded) values of an sRGB texture: decode here.
    if (parts_[k].internalFormat() == GL_SRGB8_ALPHA8)
      for (std::size_t i = 0; i < rgba.size(); ++i)
        if (i % 4 != 3) rgba[i] = srgbToLinear(rgba[i]);
    const std::size_t first = k * 4, last = std::min(count, first + 4);
    for (std::size_t p = 0; p < pixels; ++p)
      for (std::size_t c = first; c < last; ++c) image.pixels[p * count + c] = rgba[p * 4 + c - first];
  }
  flipRows(image.pixels, image.width, image.height, int(count));
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

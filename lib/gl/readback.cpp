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

std::vector<float> readRgba(const gl::Texture& texture) {
  std::vector<float> rgba(std::size_t(texture.width()) * std::size_t(texture.height()) * 4);
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(texture.id(), 0, GL_RGBA, GL_FLOAT, GLsizei(rgba.size() * sizeof(float)), rgba.data());
  return rgba;
}

}  // namespace

ImageF readColor(const gl::Texture& texture, std::vector<std::string> channels) {
  ImageF image;
  image.width = texture.width();
  image.height = texture.height();
  const std::size_t count = channels.size();
  image.channels = std::move(channels);
  std::vector<float> rgba = readRgba(texture);
  // GL returns the stored (encoded) values of an sRGB texture: decode here.
  if (texture.internalFormat() == GL_SRGB8_ALPHA8)
    for (std::size_t i = 0; i < rgba.size(); ++i)
      if (i % 4 != 3) rgba[i] = srgbToLinear(rgba[i]);
  image.pixels.resize(std::size_t(image.width) * std::size_t(image.height) * count);
  for (std::size_t p = 0, n = std::size_t(image.width) * std::size_t(image.height); p < n; ++p)
    for (std::size_t c = 0; c < count; ++c) image.pixels[p * count + c] = rgba[p * 4 + c];
  flipRows(image.pixels, image.width, image.height, int(count));
  return image;
}

ImageF readColor(std::span<const gl::Texture* const> textures, const std::vector<std::string>& channels) {
  if (textures.size() * 4 < channels.size() || textures.empty())
    throw GlError("readColor: " + std::to_string(channels.size()) + " channels need " +
                  std::to_string((channels.size() + 3) / 4) + " textures, got " + std::to_string(textures.size()));
  ImageF image;
  image.width = textures.front()->width();
  image.height = textures.front()->height();
  image.channels = channels;
  const std::size_t count = channels.size(), pixels = std::size_t(image.width) * std::size_t(image.height);
  image.pixels.resize(pixels * count);
  for (std::size_t k = 0; k * 4 < count; ++k) {
    const std::size_t first = k * 4, last = std::min(count, first + 4);
    const ImageF part =
        readColor(*textures[k], {channels.begin() + std::ptrdiff_t(first), channels.begin() + std::ptrdiff_t(last)});
    if (part.width != image.width || part.height != image.height)
      throw GlError("readColor: texture " + std::to_string(k) + " is " + std::to_string(part.width) + "x" +
                    std::to_string(part.height) + ", texture 0 is " + std::to_string(image.width) + "x" +
                    std::to_string(image.height));
    for (std::size_t p = 0; p < pixels; ++p)
      for (std::size_t c = first; c < last; ++c)
        image.pixels[p * count + c] = part.pixels[p * (last - first) + c - first];
  }
  return image;
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
  ImageF image;
  image.width = depth.width();
  image.height = depth.height();
  image.channels = {std::move(channel)};
  image.pixels.resize(std::size_t(image.width) * std::size_t(image.height));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(image.pixels.size() * sizeof(float)),
                    image.pixels.data());
  const glm::dvec4 k = viewZCoefficients(view);
  for (float& d : image.pixels) d = float(-HL_VIEW_Z_FROM_NDC_DEPTH(2.0 * double(d) - 1.0, k));
  flipRows(image.pixels, image.width, image.height, 1);
  return image;
}

}  // namespace headlight

#include "gl/readback.hpp"

#include <cmath>

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

float srgbToLinear(float encoded) {
  return encoded <= 0.04045f ? encoded / 12.92f : std::pow((encoded + 0.055f) / 1.055f, 2.4f);
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

ImageF readViewDepth(const gl::Texture& depth, const CameraView& view, std::string channel) {
  ImageF image;
  image.width = depth.width();
  image.height = depth.height();
  image.channels = {std::move(channel)};
  image.pixels.resize(std::size_t(image.width) * std::size_t(image.height));
  glPixelStorei(GL_PACK_ALIGNMENT, 4);
  glGetTextureImage(depth.id(), 0, GL_DEPTH_COMPONENT, GL_FLOAT, GLsizei(image.pixels.size() * sizeof(float)),
                    image.pixels.data());
  const double n = view.nearPlane, f = view.farPlane;
  for (float& d : image.pixels) {
    const double ndc = 2.0 * double(d) - 1.0;
    // Inverse of glm::perspective / glm::ortho's depth mapping.
    d = float(view.orthographic ? n + double(d) * (f - n) : 2.0 * n * f / (f + n - ndc * (f - n)));
  }
  flipRows(image.pixels, image.width, image.height, 1);
  return image;
}

}  // namespace headlight

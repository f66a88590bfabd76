#include "support/images.hpp"

namespace headlight::test {

ImageF makeImage(int width, int height, std::vector<std::string> channels, float value) {
  ImageF image;
  image.width = width;
  image.height = height;
  image.channels = std::move(channels);
  image.pixels.assign(std::size_t(width) * std::size_t(height) * image.channels.size(), value);
  return image;
}

}  // namespace headlight::test

#include "reference/texture_sampler.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "color/srgb.hpp"
#include "reference/sampler_enums.hpp"

namespace headlight::reference {

namespace {

// The sRGB decode curve for each 8-bit code.
const float* srgbToLinearTable() {
  static const auto table = [] {
    std::array<float, 256> values{};
    for (int i = 0; i < 256; ++i) {
      const float c = float(i) / 255.0f;
      values[std::size_t(i)] = srgbToLinear(c);
    }
    return values;
  }();
  return table.data();
}

// Keeps a texture coordinate in a range where the integer texel arithmetic
// cannot overflow, without changing what it samples.
float tameCoordinate(float u, int mode) {
  if (!std::isfinite(u)) return 0.0f;
  if (mode == kGlClampToEdge) return std::clamp(u, -1.0f, 2.0f);
  if (mode == kGlMirroredRepeat) return u - 2.0f * std::floor(u * 0.5f);
  return u - std::floor(u);
}

}  // namespace

int wrapTexel(int i, int size, int mode) {
  if (mode == kGlClampToEdge) return std::clamp(i, 0, size - 1);
  if (mode == kGlMirroredRepeat) {
    const int m = ((i % (2 * size)) + 2 * size) % (2 * size);
    return m < size ? m : 2 * size - 1 - m;
  }
  return ((i % size) + size) % size;  // kGlRepeat
}

glm::vec4 sampleTexture(const Scene& scene, const TextureRef& ref, glm::vec2 uv, bool srgb) {
  const ImageData& image = scene.images[std::size_t(ref.image)];
  if (image.width <= 0 || image.height <= 0) return glm::vec4(1.0f);
  const float* decode = srgbToLinearTable();
  auto texel = [&](int x, int y) {
    const std::uint8_t* p = &image.rgba[(std::size_t(wrapTexel(y, image.height, ref.wrapT)) * std::size_t(image.width) +
                                         std::size_t(wrapTexel(x, image.width, ref.wrapS))) *
                                        4];
    if (srgb) return glm::vec4(decode[p[0]], decode[p[1]], decode[p[2]], float(p[3]) / 255.0f);
    return glm::vec4(p[0], p[1], p[2], p[3]) / 255.0f;
  };
  const float u = tameCoordinate(uv.x, ref.wrapS) * float(image.width);
  const float v = tameCoordinate(uv.y, ref.wrapT) * float(image.height);
  if (ref.magFilter == kGlNearest) return texel(int(std::floor(u)), int(std::floor(v)));
  const float x = u - 0.5f, y = v - 0.5f;
  const float x0 = std::floor(x), y0 = std::floor(y);
  const float fx = x - x0, fy = y - y0;
  const int ix = int(x0), iy = int(y0);
  return glm::mix(glm::mix(texel(ix, iy), texel(ix + 1, iy), fx),
                  glm::mix(texel(ix, iy + 1), texel(ix + 1, iy + 1), fx), fy);
}

glm::vec2 textureUv(const Primitive& primitive, const TextureRef& ref, const std::uint32_t* corner, float u, float v) {
  const std::vector<glm::vec2>& set = ref.texCoord == 1 ? primitive.texcoords1 : primitive.texcoords;
  if (set.empty()) return ref.transform.apply(glm::vec2(0.0f));
  const glm::vec2 uv = (1.0f - u - v) * set[corner[0]] + u * set[corner[1]] + v * set[corner[2]];
  return ref.transform.apply(uv);
}

}  // namespace headlight::reference

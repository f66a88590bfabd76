// Environment importance sampling (environment_sampler.hpp).
#include "environment/environment_sampler.hpp"

#include <algorithm>

namespace headlight::environment {
namespace {

// Index i with cdf[i] <= xi < cdf[i + 1], skipping empty cells.
int findCell(const double* cdf, int cells, double xi) {
  const int i = int(std::upper_bound(cdf, cdf + cells + 1, xi) - cdf) - 1;
  return std::clamp(i, 0, cells - 1);
}

}  // namespace

EnvironmentSampler::EnvironmentSampler(const EquirectImage& map)
    : rowCdf_(kGridHeight + 1, 0.0),
      columnCdfs_(std::size_t(kGridHeight) * (kGridWidth + 1), 0.0),
      texelProbability_(std::size_t(kGridHeight) * kGridWidth, 0.0f) {
  const EquirectImage grid = resampleEquirect(map, kGridWidth, kGridHeight);
  std::vector<double> luminance(texelProbability_.size());
  for (int y = 0; y < kGridHeight; ++y)
    for (int x = 0; x < kGridWidth; ++x) {
      const glm::vec3 c = grid.texel(x, y);
      luminance[std::size_t(y) * kGridWidth + std::size_t(x)] = 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b;
    }
  // Each cell weighs the brightest of its 3 x 3 neighbourhood: the map is
  // looked up bilinearly, which spreads a bright texel half a texel beyond
  // its edges, and those directions must be drawn as often as the texel.
  std::vector<double> weights(texelProbability_.size());
  double total = 0.0;
  for (int y = 0; y < kGridHeight; ++y)
    for (int x = 0; x < kGridWidth; ++x) {
      double brightest = 0.0;
      for (int dy = -1; dy <= 1; ++dy)
        for (int dx = -1; dx <= 1; ++dx) {
          const int ny = std::clamp(y + dy, 0, kGridHeight - 1), nx = (x + dx + kGridWidth) % kGridWidth;
          brightest = std::max(brightest, luminance[std::size_t(ny) * kGridWidth + std::size_t(nx)]);
        }
      const double w = brightest * texelSolidAngle(y, kGridWidth, kGridHeight);
      weights[std::size_t(y) * kGridWidth + std::size_t(x)] = w;
      total += w;
    }
  // A black map: all its weight is the uniform share's.
  for (int y = 0; y < kGridHeight; ++y) {
    double* columns = &columnCdfs_[std::size_t(y) * (kGridWidth + 1)];
    const double* rowWeights = &weights[std::size_t(y) * kGridWidth];
    for (int x = 0; x < kGridWidth; ++x) columns[x + 1] = columns[x] + rowWeights[x];
    const double rowSum = columns[kGridWidth];
    rowCdf_[std::size_t(y) + 1] = rowCdf_[std::size_t(y)] + rowSum;
    for (int x = 0; x <= kGridWidth; ++x) columns[x] = rowSum > 0.0 ? columns[x] / rowSum : double(x) / kGridWidth;
  }
  for (double& value : rowCdf_) value = total > 0.0 ? value / total : 0.0;
  for (std::size_t i = 0; i < weights.size(); ++i)
    texelProbability_[i] = total > 0.0 ? float(weights[i] / total) : 0.0f;
}

glm::vec3 EnvironmentSampler::sample(float xi0, float xi1, float& pdf) const {
  glm::vec3 direction;
  const bool gridEmpty = rowCdf_.back() <= 0.0;
  if (gridEmpty || xi0 < kUniformShare) {
    const float u = gridEmpty ? xi0 : xi0 / kUniformShare;  // reuse the number's remaining bits
    const float z = 1.0f - 2.0f * u, r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 2.0f * kPi * xi1;
    direction = glm::vec3(r * std::cos(phi), z, r * std::sin(phi));
  } else {
    const double xi = (double(xi0) - kUniformShare) / (1.0 - kUniformShare);
    const int y = findCell(rowCdf_.data(), kGridHeight, xi);
    const double rowLow = rowCdf_[std::size_t(y)], rowHigh = rowCdf_[std::size_t(y) + 1];
    const double rowShare = (xi - rowLow) / std::max(rowHigh - rowLow, 1e-300);
    const double* columns = &columnCdfs_[std::size_t(y) * (kGridWidth + 1)];
    const int x = findCell(columns, kGridWidth, double(xi1));
    const double columnShare = (double(xi1) - columns[x]) / std::max(columns[x + 1] - columns[x], 1e-300);
    // Uniform over the texel's solid angle: uniform in azimuth and in cos(theta).
    const double pi = 3.14159265358979323846;
    const double cosTop = std::cos(pi * y / kGridHeight), cosBottom = std::cos(pi * (y + 1) / kGridHeight);
    const double cosTheta = cosTop + (cosBottom - cosTop) * std::clamp(rowShare, 0.0, 1.0);
    const double u = (x + std::clamp(columnShare, 0.0, 1.0)) / kGridWidth;
    const double sinTheta = std::sqrt(std::max(0.0, 1.0 - cosTheta * cosTheta)), phi = (u - 0.5) * 2.0 * pi;
    direction = glm::vec3(float(sinTheta * std::sin(phi)), float(cosTheta), float(-sinTheta * std::cos(phi)));
  }
  pdf = this->pdf(direction);
  return direction;
}

float EnvironmentSampler::pdf(const glm::vec3& direction) const {
  const float uniform = 1.0f / (4.0f * kPi);
  if (rowCdf_.back() <= 0.0) return uniform;
  const glm::vec2 uv = directionToUv(direction);
  const int x = std::clamp(int(uv.x * kGridWidth), 0, kGridWidth - 1);
  const int y = std::clamp(int(uv.y * kGridHeight), 0, kGridHeight - 1);
  const float texel = texelProbability_[std::size_t(y) * kGridWidth + std::size_t(x)] /
                      float(texelSolidAngle(y, kGridWidth, kGridHeight));
  return kUniformShare * uniform + (1.0f - kUniformShare) * texel;
}

}  // namespace headlight::environment

// Equirectangular lookups and resampling (lib/environment/equirect.hpp).
#include "environment/equirect.hpp"

#include <algorithm>

namespace headlight::environment {
namespace {

// Overlap weights of `to` cells with `from` cells along one axis, cells
// bounded by `fromEdges` / `toEdges` (increasing): weight[t] lists (source
// index, overlap length).
struct Overlap {
  int source;
  double length;
};
std::vector<std::vector<Overlap>> overlaps(std::span<const double> fromEdges, std::span<const double> toEdges) {
  std::vector<std::vector<Overlap>> result(toEdges.size() - 1);
  std::size_t s = 0;
  for (std::size_t t = 0; t + 1 < toEdges.size(); ++t) {
    while (s + 2 < fromEdges.size() && fromEdges[s + 1] <= toEdges[t]) ++s;
    for (std::size_t k = s; k + 1 < fromEdges.size() && fromEdges[k] < toEdges[t + 1]; ++k) {
      const double length = std::min(fromEdges[k + 1], toEdges[t + 1]) - std::max(fromEdges[k], toEdges[t]);
      if (length > 0.0) result[t].push_back({int(k), length});
    }
  }
  return result;
}

// Cell edges: uniform in azimuth (fraction of a turn), uniform in polar
// angle but measured in 1 - cos(theta), which is proportional to area.
std::vector<double> azimuthEdges(int cells) {
  std::vector<double> edges(std::size_t(cells) + 1);
  for (int i = 0; i <= cells; ++i) edges[std::size_t(i)] = double(i) / cells;
  return edges;
}
std::vector<double> areaEdges(int cells) {
  const double pi = 3.14159265358979323846;
  std::vector<double> edges(std::size_t(cells) + 1);
  for (int i = 0; i <= cells; ++i) edges[std::size_t(i)] = 1.0 - std::cos(pi * i / cells);
  return edges;
}

}  // namespace

glm::vec3 EquirectImage::bilinear(const glm::vec2& uv) const {
  const float fx = uv.x * float(width) - 0.5f, fy = std::clamp(uv.y * float(height) - 0.5f, 0.0f, float(height - 1));
  const float x0f = std::floor(fx), y0f = std::floor(fy);
  const float tx = fx - x0f, ty = fy - y0f;
  const int x0 = ((int(x0f) % width) + width) % width, x1 = (x0 + 1) % width;
  const int y0 = int(y0f), y1 = std::min(y0 + 1, height - 1);
  return glm::mix(glm::mix(texel(x0, y0), texel(x1, y0), tx), glm::mix(texel(x0, y1), texel(x1, y1), tx), ty);
}

EquirectImage resampleEquirect(const EquirectImage& source, int width, int height) {
  const auto columns = overlaps(azimuthEdges(source.width), azimuthEdges(width));
  const auto rows = overlaps(areaEdges(source.height), areaEdges(height));
  EquirectImage target{width, height, std::vector<float>(std::size_t(width) * std::size_t(height) * 3)};
  std::vector<double> rowSum(std::size_t(source.width) * 3);
  for (int y = 0; y < height; ++y) {
    // The source rows' area-weighted mean over this target row, per source column.
    std::fill(rowSum.begin(), rowSum.end(), 0.0);
    double rowWeight = 0.0;
    for (const Overlap& row : rows[std::size_t(y)]) {
      rowWeight += row.length;
      const float* p = &source.rgb[std::size_t(row.source) * std::size_t(source.width) * 3];
      for (std::size_t i = 0; i < rowSum.size(); ++i) rowSum[i] += row.length * p[i];
    }
    for (int x = 0; x < width; ++x) {
      double sum[3] = {0.0, 0.0, 0.0}, weight = 0.0;
      for (const Overlap& column : columns[std::size_t(x)]) {
        weight += column.length;
        for (int c = 0; c < 3; ++c) sum[c] += column.length * rowSum[std::size_t(column.source) * 3 + std::size_t(c)];
      }
      float* out = &target.rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
      for (int c = 0; c < 3; ++c) out[c] = float(sum[c] / (weight * rowWeight));
    }
  }
  return target;
}

}  // namespace headlight::environment

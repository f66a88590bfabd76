#pragma once
// Importance sampling of an environment map for the Embree reference
// (lib/reference/tracer.cpp): directions drawn in proportion to the map's
// luminance (the brightest of each cell's 3 x 3 neighbourhood, for the
// bilinear lookup's spread) times solid angle over a 128 x 64 grid, mixed
// with 10% uniform sphere sampling so every direction has a positive
// density (the estimate stays unbiased where the grid's mean hides a
// bright speck). Map space; the caller turns directions by the rotation.
#include <vector>

#include "environment/equirect.hpp"

namespace headlight::environment {

class EnvironmentSampler {
 public:
  explicit EnvironmentSampler(const EquirectImage& map);
  // A direction from two uniform numbers in [0, 1), with its density per steradian.
  glm::vec3 sample(float xi0, float xi1, float& pdf) const;
  float pdf(const glm::vec3& direction) const;

  static constexpr int kGridWidth = 128;
  static constexpr int kGridHeight = 64;
  static constexpr float kUniformShare = 0.1f;

 private:
  std::vector<double> rowCdf_;      // kGridHeight + 1 entries, 0..1
  std::vector<double> columnCdfs_;  // per row: kGridWidth + 1 entries, 0..1
  std::vector<float> texelProbability_;
};

}  // namespace headlight::environment

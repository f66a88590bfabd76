#include "frame/antialias.hpp"

#include <cmath>

namespace headlight {

namespace {

// The R2 sequence's point `index` started at the pixel centre, in [-0.5, 0.5)^2.
glm::dvec2 r2Point(int index) {
  // 1 / g and 1 / g^2, g the plastic number's 2D analogue (g^3 = g + 1).
  constexpr double kStepX = 0.7548776662466927, kStepY = 0.5698402909980532;
  const double x = 0.5 + kStepX * index, y = 0.5 + kStepY * index;
  return {x - std::floor(x) - 0.5, y - std::floor(y) - 0.5};
}

}  // namespace

glm::vec2 antialiasOffset(int index, int count) {
  glm::dvec2 mean(0.0);
  for (int i = 0; i < count; ++i) mean += r2Point(i);
  return glm::vec2(r2Point(index) - mean / double(count));
}

CameraView jitteredView(const CameraView& view, glm::vec2 offsetPixels, int width, int height) {
  CameraView jittered = view;
  // A translation of clip x, y by the offset times w: the same shift in
  // normalised device coordinates for a perspective (w = -z) and an
  // orthographic (w = 1) projection alike.
  glm::mat4 shift(1.0f);
  shift[3][0] = 2.0f * offsetPixels.x / float(width);
  shift[3][1] = 2.0f * offsetPixels.y / float(height);
  jittered.projection = shift * view.projection;
  return jittered;
}

}  // namespace headlight

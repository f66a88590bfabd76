#pragma once
// The equirectangular layout every environment table shares (the map, its
// prefiltered levels, its irradiance; headlight::EnvironmentMap states it):
// texel (x, y) of W x H covers azimuth 2 pi ((x + 0.5) / W - 0.5) about +Y and
// polar angle pi (y + 0.5) / H from +Y, rows top first. glsl/environment.glsl
// is the GPU's copy of directionToUv and the rotation.
#include <cmath>
#include <span>
#include <vector>

#include <glm/glm.hpp>

namespace headlight::environment {

inline constexpr float kPi = 3.14159265358979f;

// The unit direction at texture coordinate (u, v) in 0..1 (v = 0: straight up).
inline glm::vec3 uvToDirection(float u, float v) {
  const float phi = (u - 0.5f) * 2.0f * kPi, theta = v * kPi;
  return {std::sin(theta) * std::sin(phi), std::cos(theta), -std::sin(theta) * std::cos(phi)};
}

// (u, v) of a unit direction; u in -0.5..0.5 + 0.5, v in 0..1.
inline glm::vec2 directionToUv(const glm::vec3& d) {
  return {std::atan2(d.x, -d.z) / (2.0f * kPi) + 0.5f, std::acos(std::fmin(1.0f, std::fmax(-1.0f, d.y))) / kPi};
}

// Solid angle of one texel of row y in an equirectangular grid of W x H.
inline double texelSolidAngle(int y, int width, int height) {
  const double pi = 3.14159265358979323846;
  return 2.0 * pi / width * (std::cos(pi * y / height) - std::cos(pi * (y + 1) / height));
}

// A world direction seen in the map: the map is turned by `degrees` about
// +Y (right-handed: at 90 degrees, what the map shows at -Z lies at -X), so
// the world's direction is turned back by it.
inline glm::vec3 worldToMap(const glm::vec3& d, float cosRotation, float sinRotation) {
  return {cosRotation * d.x - sinRotation * d.z, d.y, sinRotation * d.x + cosRotation * d.z};
}
inline glm::vec3 mapToWorld(const glm::vec3& d, float cosRotation, float sinRotation) {
  return {cosRotation * d.x + sinRotation * d.z, d.y, -sinRotation * d.x + cosRotation * d.z};
}

// An RGB float image in that layout, or (poleRows) with its first and last
// rows' centres at the poles (polar angle pi y / (H - 1)), so that a smooth
// function (the irradiance) interpolates right up to them.
struct EquirectImage {
  int width = 0, height = 0;
  std::vector<float> rgb;  // width x height x 3
  bool poleRows = false;

  glm::vec3 texel(int x, int y) const {
    const float* p = &rgb[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3];
    return {p[0], p[1], p[2]};
  }
  // Bilinear between texel centres, wrapping in azimuth and clamped at the
  // poles (as the GPU samples it: GL_REPEAT in s, GL_CLAMP_TO_EDGE in t).
  glm::vec3 bilinear(const glm::vec2& uv) const;
  glm::vec3 lookup(const glm::vec3& direction) const {
    glm::vec2 uv = directionToUv(direction);
    if (poleRows) uv.y = (uv.y * float(height - 1) + 0.5f) / float(height);
    return bilinear(uv);
  }
  // The direction texel (x, y)'s centre stands for.
  glm::vec3 texelDirection(int x, int y) const {
    const float v = poleRows ? float(y) / float(height - 1) : (float(y) + 0.5f) / float(height);
    return uvToDirection((float(x) + 0.5f) / float(width), v);
  }
};

// The image resampled to width x height as a piecewise-constant function of
// (azimuth, cos polar angle): each target texel is the solid-angle-weighted
// mean of the source over its area, so the integral of radiance over any
// target texel (and over the sphere) is the source's, whether it shrinks or
// grows.
EquirectImage resampleEquirect(const EquirectImage& source, int width, int height);

}  // namespace headlight::environment

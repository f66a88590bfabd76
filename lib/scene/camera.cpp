#include "headlight/camera.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

namespace headlight {

// About 40 degrees, a normal lens.
Camera fitCamera(const Bounds& bounds, float aspectRatio) { return fitCamera(bounds, aspectRatio, 0.7f, 0.0f); }

Camera fitCamera(const Bounds& bounds, float aspectRatio, float yfovRadians, float azimuthRadians,
                 float elevationRadians, float distanceScale) {
  Camera camera;
  camera.name = "fitted";
  camera.yfov = yfovRadians;
  const glm::vec3 center = bounds.empty() ? glm::vec3(0.0f) : bounds.center();
  // A scene of no extent (every vertex at one point) still gets an eye apart
  // from it: a radius under float's spacing at the centre put the eye on the
  // centre, and the view was NaN; under 1e-10 the projection's near x far
  // underflows float.
  const float spacingFloor = 1e-5f * std::max({std::abs(center.x), std::abs(center.y), std::abs(center.z)});
  const float radius = bounds.empty() ? 1.0f : std::max({bounds.radius(), 1e-10f, spacingFloor});
  // The sphere fits the narrower of the two fields of view.
  const float halfFov = 0.5f * camera.yfov * std::min(1.0f, aspectRatio);
  const float distance = distanceScale * radius / std::sin(halfFov);
  // By default a little from above: (sin a, 1/4, cos a) normalised, as before elevation was a parameter
  // (bit for bit: the goldens' fitted views); another elevation e rises tan(e) per unit across.
  const float rise = elevationRadians == kFitElevationRadians ? 0.25f : std::tan(elevationRadians);
  const glm::vec3 direction = glm::normalize(glm::vec3(std::sin(azimuthRadians), rise, std::cos(azimuthRadians)));
  camera.worldFromCamera = glm::inverse(glm::lookAt(center + direction * distance, center, glm::vec3(0, 1, 0)));
  return camera;
}

void fitDepthRange(const Camera& camera, const Bounds& bounds, float& nearPlane, float& farPlane) {
  const bool orthographic = camera.projection == Camera::Projection::Orthographic;
  if (bounds.empty()) {
    nearPlane = camera.znear > 0 ? camera.znear : 0.1f;
    farPlane = camera.zfar > nearPlane ? camera.zfar : nearPlane * 1000.0f;
    return;
  }
  const glm::mat4 view = glm::inverse(camera.worldFromCamera);
  float closest = INFINITY, farthest = -INFINITY;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
                      (corner & 4) ? bounds.max.z : bounds.min.z);
    const float depth = -(view * glm::vec4(p, 1.0f)).z;
    closest = std::min(closest, depth);
    farthest = std::max(farthest, depth);
  }
  const float margin = 0.01f * std::max(bounds.radius(), 1e-30f);
  if (orthographic) {
    // An orthographic camera may sit inside the scene; its near plane may be
    // behind it, which costs nothing in precision.
    nearPlane = closest - margin;
    farPlane = farthest + margin;
  } else {
    const float minimumNear = std::max(camera.znear, bounds.radius() * 1e-4f);
    nearPlane = std::max(closest - margin, minimumNear);
    farPlane = std::max(farthest + margin, nearPlane * 1.001f);
  }
  if (camera.zfar > 0) farPlane = std::min(farPlane, camera.zfar);
  if (farPlane <= nearPlane) farPlane = nearPlane + std::max(margin, std::abs(nearPlane) * 1e-3f);
}

CameraView makeCameraView(const Camera& camera, const Bounds& sceneBounds, int width, int height) {
  CameraView result;
  const float aspect = float(width) / float(height);
  result.view = glm::inverse(camera.worldFromCamera);
  result.position = glm::vec3(camera.worldFromCamera[3]);
  result.orthographic = camera.projection == Camera::Projection::Orthographic;
  fitDepthRange(camera, sceneBounds, result.nearPlane, result.farPlane);
  if (result.orthographic) {
    const float halfHeight = camera.ymag;
    const float halfWidth = halfHeight * aspect;
    result.projection = glm::ortho(-halfWidth, halfWidth, -halfHeight, halfHeight, result.nearPlane, result.farPlane);
  } else {
    result.projection = glm::perspective(camera.yfov, aspect, result.nearPlane, result.farPlane);
  }
  return result;
}

}  // namespace headlight

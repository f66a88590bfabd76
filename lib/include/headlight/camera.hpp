#pragma once
// From a scene camera (or none) to the matrices a frame is rendered with.
// Near and far planes hug the scene's bounds, so depth keeps its precision
// for an 8 mm asset and a 2 km one alike.
#include <glm/glm.hpp>

#include "headlight/export.hpp"
#include "headlight/scene.hpp"

namespace headlight HEADLIGHT_PUBLIC {

struct CameraView {
  glm::mat4 view{1.0f};        // world -> view; the camera looks down -Z, +Y up
  glm::mat4 projection{1.0f};  // view -> clip, OpenGL's -1..1 depth range
  glm::vec3 position{0.0f};    // world
  float nearPlane = 0.1f;      // view-space distance, > 0 for perspective
  float farPlane = 100.0f;     // view-space distance, > nearPlane
  bool orthographic = false;
};

// A perspective camera that frames `bounds` whole, looking at their centre
// from the front (+Z), a little above; used when a file has no camera.
Camera fitCamera(const Bounds& bounds, float aspectRatio);
// The same framing with a `yfovRadians` lens, turned by `azimuthRadians`
// about +Y (0: fitCamera's view, from +Z): a turntable's views; raised by
// `elevationRadians` above the bounds' centre (fitCamera's: atan(1/4), 14
// degrees) and `distanceScale` times the distance that frames them whole.
inline constexpr float kFitElevationRadians = 0.24497866f;  // atan(0.25)
Camera fitCamera(const Bounds& bounds, float aspectRatio, float yfovRadians, float azimuthRadians,
                 float elevationRadians = kFitElevationRadians, float distanceScale = 1.0f);

// Near/far planes for looking at `bounds` from `worldFromCamera`: the range
// of view depths of the box's corners, widened by 1% of its radius, clamped
// to the camera's own znear/zfar when it has them. A camera inside the box
// gets near = max(znear, radius * 1e-4).
void fitDepthRange(const Camera& camera, const Bounds& bounds, float& nearPlane, float& farPlane);

// The view of `camera` at an image of width x height pixels. The image's
// aspect ratio wins over the camera's (the glTF spec allows either; a user
// asking for a size expects no stretching).
CameraView makeCameraView(const Camera& camera, const Bounds& sceneBounds, int width, int height);

}  // namespace HEADLIGHT_PUBLIC

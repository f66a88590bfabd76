#pragma once
// Virtual point lights for the bitmask SSGI's far field: one bounce of the
// punctual lights off the surfaces they light, wherever those are (off
// screen, or behind what the screen shows), which the screen-space marches
// cannot see. Each light's view of the scene (a point light's six cube
// faces, a spot light's cone, a directional light's square over the scene)
// is drawn by the G-buffer pass at a few texels per side; every texel the
// light reaches becomes a virtual light that sends back, as a Lambertian
// surface, the share of the power reaching that texel its material
// reflects: the reflective shadow maps of Dachsbacher and Stamminger
// (I3D 2005). They depend on the scene and its lights, not on the camera,
// so a scene makes them once for all its views.
#include <cstddef>
#include <functional>
#include <vector>

#include "gl/objects.hpp"
#include "headlight/camera.hpp"
#include "headlight/scene.hpp"
#include "passes/gbuffer.hpp"
#include "shared_layout.h"

namespace headlight {

// One of a light's views and the measure of its texels.
struct LightView {
  CameraView camera;
  std::size_t light = 0;  // index into the scene's lights
  // A perspective view's tan(fov / 2): its texel at (u, v) in -1..1 spans
  // (2 t / size)^2 / (1 + t^2 (u^2 + v^2))^(3/2) steradians. 0: orthographic.
  float tanHalfFov = 0.0f;
  float halfWidth = 0.0f;  // orthographic (directional): half the square's side, world units
};

// A cube's faces, in GL's order: +X, -X, +Y, -Y, +Z, -Z.
inline const glm::vec3 kCubeFaceDirections[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};

// A square perspective view from `position` along `direction`, `fov`
// radians across, that reaches past the far side of `bounds`.
CameraView perspectiveCamera(const glm::vec3& position, const glm::vec3& direction, float fov, const Bounds& bounds);

// Every view of every light that casts shadows, in the lights' order: six
// for a point light, one for a spot or directional light.
std::vector<LightView> lightViews(const std::vector<Light>& lights, const Bounds& bounds);

// What texel (x, y) of a `size` x `size` rendering of `view` covers: its
// solid angle from the light (perspective views), or its area across the
// light's rays (orthographic), world units squared.
float texelMeasure(const LightView& view, int x, int y, int size);

// Texels per side of each of `viewCount` views, so that together they make
// at most `budget` virtual lights (at least 1).
int lightViewSize(int budget, std::size_t viewCount);

struct VirtualLights {
  gl::Buffer buffer;  // the entries, bound at kBindingVirtualLights
  int count = 0;
  std::vector<gpu::GpuVirtualLight> entries;  // what the buffer holds: the light field is filled from them
};

class VirtualLightPass {
 public:
  // Sets the frame block to a view of `size` x `size` pixels.
  using BindView = std::function<void(const CameraView& view, int size)>;
  // Draws every light's views with `gbuffer` (its position, normal, albedo
  // and material targets) and turns what they show into at most `budget`
  // virtual lights. Leaves the frame block at the last view.
  VirtualLights run(const GpuScene& scene, GBufferPass& gbuffer, const GBufferVariant& variant,
                    const std::vector<Light>& lights, int budget, const BindView& bindView);
};

}  // namespace headlight

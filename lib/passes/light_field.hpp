#pragma once
// A world-space light field for the bitmask SSGI's far field: irradiance
// probes on a grid over the scene, each with what it sees, after Majercik et
// al., "Dynamic Diffuse Global Illumination with Ray-Traced Irradiance
// Fields" (JCGT 8(2), 2019). Where DDGI traces rays from each probe, a probe
// here is drawn: the G-buffer pass renders its six cube faces at a few
// texels a side, which every build can do. From those views each probe keeps
//  * the irradiance the virtual lights (lib/passes/virtual_lights.hpp, one
//    bounce of the punctual lights) send it, for every normal, on an
//    octahedral map; a virtual light counts where the probe's view reaches
//    it;
//  * the mean and mean square of the distance to the nearest surface about
//    each direction (an octahedral map), by which a shaded point weighs the
//    probe with Chebyshev's inequality: a probe behind a wall does not see
//    the point, and lends it nothing (DDGI's probe-visibility moments).
// It depends on the scene and its lights, not on the camera: made once per
// scene and reused by every view. glsl/light_field.glsl reads it.
#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.hpp"
#include "headlight/camera.hpp"
#include "headlight/limits.hpp"
#include "headlight/scene.hpp"
#include "passes/gbuffer.hpp"
#include "shared_layout.h"

namespace headlight {

// Probes at the centres of a grid of cells over the scene's bounds.
struct LightFieldGrid {
  glm::vec3 origin{0.0f};   // probe (0, 0, 0)
  glm::vec3 spacing{1.0f};  // between neighbours, per axis (> 0)
  glm::ivec3 counts{0};     // probes per axis; all 0: no field

  int probeCount() const { return counts.x * counts.y * counts.z; }
  // Probe `index`, x fastest.
  glm::vec3 probePosition(int index) const;
};

// At most `budget` probes, as near to cubic cells as the bounds allow: an
// axis the scene is flat along (a wall, a floor) gets one layer. Empty
// bounds or a budget of 0: no probes.
LightFieldGrid lightFieldGrid(const Bounds& bounds, int budget);

// Each probe draws the scene kLightFieldViewsPerProbe times: six cube
// faces, front faces and then back faces.
inline constexpr int kLightFieldViewsPerProbe = 12;

// The probes a field may have: at most `requested`, and no more than keep
// its views within one frame's draw budgets (`--max-draws` over the
// scene's instances, `--max-drawn-triangles` over its triangles): made once
// per scene, it then costs no more than a frame may. A million-triangle
// scene gets 4 probes of the default 64 (50 million triangles).
int lightFieldProbeBudget(int requested, std::uint64_t instances, std::uint64_t triangles,
                          const ResourceLimits& limits);

// Octahedral mapping of unit directions onto [0, 1]^2 and back (Cigolle et
// al., "A Survey of Efficient Representations for Independent Unit
// Vectors", JCGT 2014); glsl/light_field.glsl has the same pair.
glm::vec2 octahedralFromDirection(const glm::vec3& direction);
glm::vec3 directionFromOctahedral(const glm::vec2& uv);

// What a probe's six cube views show: per texel, the distance to the
// surface seen along it (`infinity` where nothing is), in the views' order
// (+X, -X, +Y, -Y, +Z, -Z), each `size` x `size`, rows top first.
struct ProbeView {
  glm::vec3 position{0.0f};
  int size = 0;
  std::vector<glm::mat4> clipFromWorld;  // per face
  std::vector<float> distances;          // 6 x size x size
  // The share of texels that see the back of a single-sided surface first:
  // over kInsideShare, the probe is inside a closed mesh and is not used.
  float backFaceShare = 0.0f;
  static constexpr float kInsideShare = 0.25f;
  // The distance seen toward `point` (the largest of the 3 x 3 texels round
  // the one it projects to: a surface seen at a grazing angle spans a
  // texel's worth of depth).
  float reachToward(const glm::vec3& point) const;
};

// One probe's entry: its irradiance from the virtual lights that `view`
// reaches, and its distance moments from `view`, with misses counted at
// `farDistance`.
gpu::GpuLightProbe makeLightProbe(const ProbeView& view, std::span<const gpu::GpuVirtualLight> lights,
                                  float farDistance);

struct LightField {
  gl::Buffer buffer;  // gpu::GpuLightProbe entries, bound at kBindingLightField
  LightFieldGrid grid;
  int insideProbes = 0;  // probes inside a closed mesh (ProbeView::backFaceShare), not used
  int requested = 0;     // the probes asked for (ssgi-light-field); the grid may hold fewer
};

// What `--verbose` says of a field: "64 probes (4 x 4 x 4, 2 inside a
// closed mesh), 384 views of 16 x 16".
std::string describeLightField(const LightField& field);

class LightFieldPass {
 public:
  // Sets the frame block to a view of `size` x `size` pixels.
  using BindView = std::function<void(const CameraView& view, int size)>;
  // Draws each probe's six faces with `gbuffer` (its position target) and
  // fills the probes from `lights`. Leaves the frame block at the last view.
  LightField run(const GpuScene& scene, GBufferPass& gbuffer, const GBufferVariant& variant,
                 std::span<const gpu::GpuVirtualLight> lights, int budget, const BindView& bindView);
};

}  // namespace headlight

#pragma once
// Shadow maps, made only for lights that cast shadows (and not at all with
// shadows off): one layer of a 2D depth array per directional or spot light,
// one cube of a depth cube-map array per point light. Their extent comes from
// the scene bounds, so an 8 mm asset and a 2 km one are both covered; a
// directional light's is narrowed to what the camera sees of the scene
// where that is much less, so it may depend on the view (the renderer
// remakes the maps when it changes), while spot and point lights' do not.
//
// Transmissive casters (KHR_materials_transmission) are in no depth map.
// Where the plan asks (ShadowStep::transmittance), each depth map has a
// transmittance map beside it: RGBA32F, what the transmissive layers in
// front of the first opaque surface let through as a summed optical depth
// (rgb) and the nearest layer's depth (a). glsl/shadow_transmittance.glsl
// holds the model; shadows.glsl tints the receivers behind the layers.
#include <cstdint>
#include <span>
#include <string>
#include <vector>

#include "frame/frame_plan.hpp"
#include "gl/gpu_scene.hpp"
#include "gl/objects.hpp"
#include "headlight/camera.hpp"
#include "headlight/limits.hpp"
#include "passes/program_cache.hpp"
#include "shared_layout.h"

namespace headlight {

// How many maps of each kind the scene's casting lights need.
struct ShadowCasters {
  int planar = 0;  // directional and spot lights: layers of ShadowMaps::planar
  int cube = 0;    // point lights: cubes of ShadowMaps::cube
};
ShadowCasters countShadowCasters(const std::vector<Light>& lights);

// The bytes ShadowPass::run allocates for `casters` at `size` texels a side:
// 4 a depth texel, 16 more a transmittance texel (with `transmittance`).
std::uint64_t shadowMapBytes(const ShadowCasters& casters, int size, bool transmittance);

// Throws LimitError naming `source` (the scene), its casting lights and the
// map size when their maps and `otherBytes` (the frame, the scene) would not
// fit in max-memory: a file's thousands of point lights are refused before
// any map is made. Returns the maps' bytes (shadowMapBytes).
std::uint64_t checkShadowMapsFit(const std::string& source, const ShadowCasters& casters, int size, bool transmittance,
                                 std::uint64_t otherBytes, const ResourceLimits& limits);

// A point light's cube faces get half the texels per side of the planar
// maps: six of them cover its whole surroundings, where a directional map
// covers what the camera sees. builtin:cornell's lamp at 256x256: faces of
// 1024 instead of 512 cost 17 ms more (15-18 -> 33-36 ms) and moved HDR-FLIP
// from 0.2429 to 0.2432 (docs/BENCHMARKS.md, "Shadow maps").
int cubeFaceSize(int size);

struct ShadowMaps {
  gl::Texture planar;  // 2D array, GL_DEPTH_COMPONENT32F; empty without directional/spot casters
  gl::Texture cube;    // cube-map array, GL_DEPTH_COMPONENT32F, linear distance / far; empty without point casters
  // Beside planar and cube, layer for layer: GL_RGBA32F transmittance maps;
  // empty unless made with transmittance.
  gl::Texture planarTransmittance, cubeTransmittance;
  int size = 0;  // the planar maps' texels per side (the cubes': cubeFaceSize); 0 = no maps
  ShadowCasters casters() const { return {planar.layers(), cube.layers() / 6}; }
  bool transmittance() const { return bool(planarTransmittance) || bool(cubeTransmittance); }
  // What a lighting shader can read of these maps.
  ShadowLookups lookups() const { return {bool(planar), bool(cube), transmittance()}; }
};

// HAS_PLANAR_SHADOWS, HAS_CUBE_SHADOWS and HAS_SHADOW_TRANSMITTANCE, as
// `lookups` says: for every lighting pass's variant.
void appendShadowDefines(const ShadowLookups& lookups, std::vector<std::string>& defines);
// Binds the maps of `maps` that those defines read.
void bindShadowMaps(const ShadowMaps& maps, const ShadowLookups& lookups);

// Where one light's shadow is: what the lighting shader needs to look it up.
struct ShadowSlot {
  int layer = -1;                  // layer of ShadowMaps::planar, or cube of ShadowMaps::cube; -1 = none
  float far = 0.0f;                // point lights: the distance the cube's depth is divided by
  float texelSize = 0.0f;          // directional: a texel's world size; spot: per unit distance from the light
  glm::mat4 viewProjection{1.0f};  // directional and spot: world -> light clip
};

struct ShadowOutputs {
  ShadowMaps maps;
  std::vector<ShadowSlot> slots;  // one per scene light, in order; layer -1 for lights that cast none
};

// The rectangle of its light's view (min x, min y, max x, max y) that each
// directional caster's map covers for `camera`, in order: the part the
// camera sees where that is much less than the scene, else all of it. The
// maps ShadowPass::run makes for a camera serve another with the same.
std::vector<glm::vec4> directionalCoverage(const std::vector<Light>& lights, const Bounds& bounds,
                                           const CameraView* camera);

// The lights as the lighting shader reads them. `slots` (one per light, or
// empty for "no shadows") come from ShadowPass::run.
std::vector<gpu::GpuLight> packLights(const std::vector<Light>& lights, std::span<const ShadowSlot> slots = {});

class ShadowPass {
 public:
  ShadowPass();
  // Renders a map at `size` texels per side for each casting light of
  // `lights` (the scene's, in order) and says where each one went; with
  // `transmittance`, a transmittance map beside each.
  // Directional maps cover what `camera` sees (all of the scene without one).
  ShadowOutputs run(const GpuScene& scene, const std::vector<Light>& lights, int size,
                    const CameraView* camera = nullptr, bool transmittance = false);

 private:
  // One light's view: the block, its depth map layer and, when made, its transmittance map layer.
  void renderView(const GpuScene& scene, const ShadowMaps& maps, bool cube, int layer, const gpu::ShadowBlock& block);
  void drawGroups(const GpuScene& scene, const GpuPrimitiveRun& run, bool transmissive);
  gl::Program program_;  // every unmasked caster: depth only
  // Masked casters (alphaMode MASK), by the features they read
  // (kFeatureAlphaMask [| kFeatureTexcoords [| kFeatureBaseColorTexture]] [| kFeatureVertexColors]
  // [| kFeatureTexcoords1 | kFeatureBaseColorTexcoord1 | kFeatureTextureTransform]).
  ProgramCache<FeatureBits> maskedPrograms_;
  // Transmissive casters into the transmittance maps (shadow_transmittance.frag),
  // by the features they read: maskedPrograms_' and the transmission texture's.
  ProgramCache<FeatureBits> transmittancePrograms_;
  gl::Buffer block_;
  gl::Framebuffer framebuffer_;
};

}  // namespace headlight

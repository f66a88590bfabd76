#pragma once
// The G-buffer pass: the scene drawn once into four colour targets and depth
// (five with an emissive target, made only for scenes that glow). Formats
// come from the frame-target table (headlight/targets.hpp):
//   RT0 GL_RGBA32F      world position, A = 1 on geometry, 0 on background
//   RT1 GL_RGBA16F      world normal as a unit vector (not remapped to 0..1)
//   RT2 GL_SRGB8_ALPHA8 base colour (albedo)
//   RT3 GL_RGBA8        metallic, roughness, occlusion (glTF occlusion texture)
//   RT4 GL_RGBA16F      emissive radiance, only if the scene has any
//   depth GL_DEPTH_COMPONENT32F
#include <cstdint>

#include "gl/objects.hpp"
#include "passes/program_cache.hpp"
#include "scene/gpu_scene.hpp"

namespace headlight {

struct GBuffer {
  gl::Texture position;
  gl::Texture normal;
  gl::Texture albedo;
  gl::Texture material;
  gl::Texture emissive;  // empty unless the scene has emissive materials
  gl::Texture depth;
  gl::Framebuffer framebuffer;
  int width = 0;
  int height = 0;
};

GBuffer makeGBuffer(int width, int height, bool withEmissive);

class GBufferPass {
 public:
  // Builds one shader variant per feature combination the instances use.
  explicit GBufferPass(const GpuScene& scene);
  // Draws every instance; the frame block must be bound.
  void run(const GpuScene& scene, GBuffer& target);

 private:
  ProgramCache<std::uint32_t> programs_;  // keyed by GBufferFeature bits
};

}  // namespace headlight

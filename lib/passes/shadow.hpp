#pragma once
// Shadow maps, made only for lights that cast shadows (and not at all with
// shadows off): one layer of a 2D depth array per directional or spot light,
// one cube of a depth cube-map array per point light. Their extent comes from
// the scene bounds, so an 8 mm asset and a 2 km one are both covered.
// Shadows do not depend on the camera: the renderer keeps them across views.
#include <vector>

#include "gl/objects.hpp"
#include "scene/gpu_scene.hpp"
#include "shared_layout.h"

namespace headlight {

struct ShadowMaps {
  gl::Texture planar;  // GL_TEXTURE_2D_ARRAY, GL_DEPTH_COMPONENT32F; empty without directional/spot casters
  gl::Texture cube;    // GL_TEXTURE_CUBE_MAP_ARRAY, GL_DEPTH_COMPONENT32F, linear distance / far
  int size = 0;        // texels per side
};

// The lights as the lighting shader reads them, without shadows assigned.
std::vector<gpu::GpuLight> packLights(const std::vector<Light>& lights);

class ShadowPass {
 public:
  ShadowPass();
  // Assigns a shadow layer, matrix and far distance to each casting light in
  // `lights` and renders its map at `size` texels per side.
  ShadowMaps run(const GpuScene& scene, const std::vector<Light>& sceneLights, std::vector<gpu::GpuLight>& lights,
                 int size);

 private:
  void renderView(const GpuScene& scene, const gl::Texture& target, int layer, const glm::mat4& viewProjection,
                  const glm::vec4& positionFar);
  gl::Program program_;
  gl::Buffer block_;
  gl::Framebuffer framebuffer_;
};

}  // namespace headlight

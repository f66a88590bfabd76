#pragma once
// The composite pass: direct light + image-based ambient from the procedural
// sky (split-sum, tables from EnvironmentPass), occluded by the material's
// occlusion and the SSGI's AO, + the SSGI's indirect term, as in the seed:
//   ambient = (diffuse_ibl + specular_ibl) * material_ao * ssgi_ao + ssgi_indirect
// Output GL_RGBA16F linear radiance; background pixels get the sky, alpha 0.
#include <map>

#include "gl/objects.hpp"
#include "passes/environment.hpp"
#include "passes/gbuffer.hpp"

namespace headlight {

class CompositePass {
 public:
  CompositePass();
  void prepare(bool withSsgi) { programFor(withSsgi); }
  // The lighting block must be bound. `ssgi` is null with SSGI off: ambient
  // is then unoccluded but for the material's occlusion.
  void run(const GBuffer& gbuffer, const gl::Texture& direct, const gl::Texture* ssgi,
           const EnvironmentTables& environment, const gl::Texture& output);

 private:
  const gl::Program& programFor(bool withSsgi);
  std::map<bool, gl::Program> programs_;
  gl::Framebuffer framebuffer_;
  gl::VertexArray emptyVertexArray_;
};

}  // namespace headlight

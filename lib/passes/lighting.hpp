#pragma once
// The lighting pass: a fullscreen pass from the G-buffer to linear HDR
// radiance (GL_RGBA16F). Cook-Torrance GGX for each punctual light (glTF
// units and range falloff, PCF-filtered shadows where a map exists), then
//   ambient = (diffuse_ibl + specular_ibl) * material_ao * ssgi_ao + ssgi_indirect
// as in the seed, plus emission. Background pixels get the sky, alpha 0.
#include <map>
#include <string>
#include <vector>

#include "gl/objects.hpp"
#include "headlight/settings.hpp"
#include "passes/environment.hpp"
#include "passes/gbuffer.hpp"
#include "passes/shadow.hpp"

namespace headlight {

struct LightingInputs {
  const GBuffer& gbuffer;
  const gl::Texture* ssgi;  // null with SSGI off: ambient is then unoccluded
  const ShadowMaps& shadows;
  const EnvironmentTables& environment;
  const gl::Buffer& lights;  // GpuLight[lightCount], std430
  int lightCount;
  float skyIntensity;
};

class LightingPass {
 public:
  // Which optional inputs a frame has; each combination is one shader variant.
  struct Inputs {
    bool ssgi, emissive, planarShadows, cubeShadows;
  };
  LightingPass();
  // Builds the variant for `inputs` ahead of the first frame, so frames time
  // shading, not compiling. Variants a frame needs later are built then.
  void prepare(const Inputs& inputs) { programFor(inputs); }
  void run(const LightingInputs& inputs, const LightingSettings& settings, const gl::Texture& output);

 private:
  const gl::Program& programFor(const Inputs& inputs);
  std::map<std::vector<std::string>, gl::Program> programs_;
  gl::Buffer block_;
  gl::Framebuffer framebuffer_;
  gl::VertexArray emptyVertexArray_;
};

}  // namespace headlight

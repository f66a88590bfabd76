#include "passes/lighting.hpp"

#include "gl/shader_library.hpp"
#include "shared_layout.h"

namespace headlight {

LightingPass::LightingPass() : block_(sizeof(gpu::LightingBlock), nullptr) {
  const GLenum drawBuffers[] = {GL_COLOR_ATTACHMENT0};
  framebuffer_.setDrawBuffers(drawBuffers);
}

const gl::Program& LightingPass::programFor(const Inputs& inputs) {
  // Only the inputs this frame has are declared in the shader.
  std::vector<std::string> defines;
  if (inputs.ssgi) defines.emplace_back("HAS_SSGI");
  if (inputs.emissive) defines.emplace_back("HAS_EMISSIVE");
  if (inputs.planarShadows) defines.emplace_back("HAS_PLANAR_SHADOWS");
  if (inputs.cubeShadows) defines.emplace_back("HAS_CUBE_SHADOWS");
  auto found = programs_.find(defines);
  if (found != programs_.end()) return found->second;
  const std::string_view files[] = {"fullscreen.vert", "lighting.frag"};
  return programs_.emplace(defines, detail::buildProgram(files, defines)).first->second;
}

void LightingPass::run(const LightingInputs& in, const LightingSettings& settings, const gl::Texture& output) {
  gpu::LightingBlock block{};
  block.ambient = glm::vec4(in.skyIntensity, in.ssgi ? 1.0f : 0.0f, float(in.lightCount), settings.pcfRadius);
  block.shadow = glm::vec4(1.5f, 0.0f, float(in.shadows.size), 0.0f);
  block_.update(block);
  block_.bindUniform(gpu::LightingBlock::kBinding);
  in.lights.bindStorage(gpu::LightBuffer::kBinding);

  in.gbuffer.position.bind(gpu::kUnitGbufferPosition);
  in.gbuffer.normal.bind(gpu::kUnitGbufferNormal);
  in.gbuffer.albedo.bind(gpu::kUnitGbufferAlbedo);
  in.gbuffer.material.bind(gpu::kUnitGbufferMaterial);
  if (in.gbuffer.emissive) in.gbuffer.emissive.bind(gpu::kUnitGbufferEmissive);
  if (in.ssgi) in.ssgi->bind(gpu::kUnitSsgi);
  if (in.shadows.planar) in.shadows.planar.bind(gpu::kUnitShadowMaps2D);
  if (in.shadows.cube) in.shadows.cube.bind(gpu::kUnitShadowMapsCube);
  in.environment.brdfLut.bind(gpu::kUnitBrdfLut);
  in.environment.skyPrefiltered.bind(gpu::kUnitSkyPrefiltered);
  in.environment.skyIrradiance.bind(gpu::kUnitSkyIrradiance);

  framebuffer_.attach(GL_COLOR_ATTACHMENT0, output);
  framebuffer_.checkComplete("lighting");
  framebuffer_.bind();
  glViewport(0, 0, output.width(), output.height());
  glDisable(GL_DEPTH_TEST);
  programFor({in.ssgi != nullptr, bool(in.gbuffer.emissive), bool(in.shadows.planar), bool(in.shadows.cube)}).use();
  emptyVertexArray_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
}

}  // namespace headlight

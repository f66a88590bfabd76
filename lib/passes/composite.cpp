#include "passes/composite.hpp"

#include "gl/shader_library.hpp"
#include "shared_layout.h"

namespace headlight {

CompositePass::CompositePass() {
  const GLenum drawBuffers[] = {GL_COLOR_ATTACHMENT0};
  framebuffer_.setDrawBuffers(drawBuffers);
}

const gl::Program& CompositePass::programFor(bool withSsgi) {
  auto found = programs_.find(withSsgi);
  if (found != programs_.end()) return found->second;
  std::vector<std::string> defines;
  if (withSsgi) defines.emplace_back("HAS_SSGI");
  const std::string_view files[] = {"fullscreen.vert", "composite.frag"};
  return programs_.emplace(withSsgi, detail::buildProgram(files, defines)).first->second;
}

void CompositePass::run(const GBuffer& gbuffer, const gl::Texture& direct, const gl::Texture* ssgi,
                        const EnvironmentTables& environment, const gl::Texture& output) {
  gbuffer.position.bind(gpu::kUnitGbufferPosition);
  gbuffer.normal.bind(gpu::kUnitGbufferNormal);
  gbuffer.albedo.bind(gpu::kUnitGbufferAlbedo);
  gbuffer.material.bind(gpu::kUnitGbufferMaterial);
  direct.bind(gpu::kUnitDirect);
  if (ssgi) ssgi->bind(gpu::kUnitSsgi);
  environment.brdfLut.bind(gpu::kUnitBrdfLut);
  environment.skyPrefiltered.bind(gpu::kUnitSkyPrefiltered);
  environment.skyIrradiance.bind(gpu::kUnitSkyIrradiance);

  framebuffer_.attach(GL_COLOR_ATTACHMENT0, output);
  framebuffer_.checkComplete("composite");
  framebuffer_.bind();
  glViewport(0, 0, output.width(), output.height());
  glDisable(GL_DEPTH_TEST);
  programFor(ssgi != nullptr).use();
  emptyVertexArray_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  framebuffer_.detach(GL_COLOR_ATTACHMENT0);
}

}  // namespace headlight

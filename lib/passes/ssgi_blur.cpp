#include "passes/ssgi_blur.hpp"

#include "gl/shader_library.hpp"
#include "shared_layout.h"

namespace headlight {

SsgiBlurPass::SsgiBlurPass() : block_(sizeof(gpu::SsgiBlurBlock), nullptr) {
  const std::string_view files[] = {"fullscreen.vert", "ssgi_blur.frag"};
  program_ = detail::buildProgram(files);
  const GLenum drawBuffers[] = {GL_COLOR_ATTACHMENT0};
  framebuffer_.setDrawBuffers(drawBuffers);
}

void SsgiBlurPass::run(const GBuffer& gbuffer, const gl::Texture& input, const gl::Texture& output, float radius,
                       int divisor) {
  const gpu::SsgiBlurBlock block{glm::vec4(radius, float(divisor), 0.0f, 0.0f)};
  block_.update(block);
  block_.bindUniform(gpu::SsgiBlurBlock::kBinding);
  framebuffer_.attach(GL_COLOR_ATTACHMENT0, output);
  framebuffer_.checkComplete("SSGI blur");
  framebuffer_.bind();
  glViewport(0, 0, output.width(), output.height());
  const float clear[] = {1.0f, 0.0f, 0.0f, 0.0f};  // background, as the SSGI pass leaves it
  glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 0, clear);
  glDisable(GL_DEPTH_TEST);
  gbuffer.position.bind(gpu::kUnitGbufferPosition);
  gbuffer.normal.bind(gpu::kUnitGbufferNormal);
  input.bind(gpu::kUnitSsgi);
  program_.use();
  emptyVertexArray_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  framebuffer_.detach(GL_COLOR_ATTACHMENT0);
}

}  // namespace headlight

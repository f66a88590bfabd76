#include "passes/fullscreen.hpp"

#include <string>

#include "headlight/error.hpp"

namespace headlight {

gl::Program buildFullscreenProgram(std::string_view fragmentFile) {
  const std::string_view files[] = {"fullscreen.vert", fragmentFile};
  return detail::buildProgram(files);
}

FullscreenDraw::FullscreenDraw()
    : framebuffer_(gl::Framebuffer::create()), emptyVertexArray_(gl::VertexArray::create()) {}

void FullscreenDraw::draw(std::string_view what, const gl::Program& program,
                          std::span<const gl::Texture* const> outputs, std::optional<glm::vec4> clear) {
  static constexpr GLenum kAttachments[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                            GL_COLOR_ATTACHMENT3};
  if (outputs.empty() || outputs.size() > std::size(kAttachments))
    throw GlError("FullscreenDraw: " + std::string(what) + " has " + std::to_string(outputs.size()) +
                  " outputs, expected 1 to " + std::to_string(std::size(kAttachments)));
  for (std::size_t i = 0; i < outputs.size(); ++i) framebuffer_.attach(kAttachments[i], *outputs[i]);
  framebuffer_.setDrawBuffers(std::span(kAttachments, outputs.size()));
  framebuffer_.checkComplete(what);
  framebuffer_.bind();
  glViewport(0, 0, outputs[0]->width(), outputs[0]->height());
  if (clear)
    for (std::size_t i = 0; i < outputs.size(); ++i)
      glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, GLint(i), &clear->x);
  glDisable(GL_DEPTH_TEST);
  program.use();
  emptyVertexArray_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  for (std::size_t i = 0; i < outputs.size(); ++i) framebuffer_.detach(kAttachments[i]);
}

}  // namespace headlight

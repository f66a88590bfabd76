#pragma once
// What the forward passes over lit (blend, transmission) draw into: lit at
// output 0 and the pass's own target at output 1 (cleared to 0), depth-tested
// against the G-buffer's depth; bound, with the viewport set.
#include <string_view>

#include "gl/objects.hpp"

namespace headlight {

inline void bindForwardTargets(gl::Framebuffer& framebuffer, const gl::Texture& lit, const gl::Texture& own,
                               const gl::Texture& depth, int width, int height, std::string_view pass) {
  framebuffer.attach(GL_COLOR_ATTACHMENT0, lit);
  framebuffer.attach(GL_COLOR_ATTACHMENT1, own);
  framebuffer.attach(GL_DEPTH_ATTACHMENT, depth);
  const GLenum drawBuffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  framebuffer.setDrawBuffers(drawBuffers);
  framebuffer.checkComplete(pass);
  framebuffer.bind();
  glViewport(0, 0, width, height);
  const float zero[] = {0.0f, 0.0f, 0.0f, 0.0f};
  glClearNamedFramebufferfv(framebuffer.id(), GL_COLOR, 1, zero);
}

}  // namespace headlight

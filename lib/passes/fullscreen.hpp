#pragma once
// What the fullscreen passes share: their program caches, and the draw of
// one triangle that covers a pass's targets. A fullscreen pass binds its
// inputs (textures to their gpu::kUnit*, its block), then calls
// FullscreenDraw::draw with its program and outputs; everything between
// "attach the targets" and "detach them" happens there, once.
#include <optional>
#include <span>
#include <string_view>

#include <glm/glm.hpp>

#include "gl/objects.hpp"
#include "passes/program_cache.hpp"

namespace headlight {

// A cache of `fullscreen.vert` + `fragmentFile` programs.
template <class Variant>
ProgramCache<Variant> fullscreenPrograms(std::string_view fragmentFile,
                                         typename ProgramCache<Variant>::Defines defines) {
  return ProgramCache<Variant>("fullscreen.vert", fragmentFile, std::move(defines));
}

// The one program of a fullscreen pass without variants.
gl::Program buildFullscreenProgram(std::string_view fragmentFile);

// Draws a fullscreen triangle into `outputs` (colour attachments 0..n-1, all
// of one size). Owns the framebuffer and the empty vertex array a pass would
// otherwise repeat; targets are detached after the draw, so a dropped target
// is not kept alive by the framebuffer.
class FullscreenDraw {
 public:
  FullscreenDraw();
  // `what` names the pass in an incomplete-framebuffer error. With `clear`,
  // every output is first cleared to it (pixels the shader discards keep
  // it). Depth testing is turned off.
  void draw(std::string_view what, const gl::Program& program, std::span<const gl::Texture* const> outputs,
            std::optional<glm::vec4> clear = std::nullopt);
  void draw(std::string_view what, const gl::Program& program, const gl::Texture& output,
            std::optional<glm::vec4> clear = std::nullopt) {
    const gl::Texture* outputs[] = {&output};
    draw(what, program, outputs, clear);
  }

 private:
  gl::Framebuffer framebuffer_;
  gl::VertexArray emptyVertexArray_;  // a fullscreen triangle needs no vertices, but core GL needs a VAO bound
};

// The base of a fullscreen pass with #define-selected variants: its program
// cache and its draw. The derived pass's run() binds its inputs, then calls
// draw() with the variant the inputs select.
template <class Variant>
class FullscreenPass {
 public:
  // Builds `variant`'s program ahead of its first frame.
  void prepare(const Variant& variant) { programs_.get(variant); }

 protected:
  FullscreenPass(std::string_view fragmentFile, typename ProgramCache<Variant>::Defines defines)
      : programs_(fullscreenPrograms<Variant>(fragmentFile, std::move(defines))) {}
  void draw(std::string_view what, const Variant& variant, std::span<const gl::Texture* const> outputs,
            std::optional<glm::vec4> clear = std::nullopt) {
    draw_.draw(what, programs_.get(variant), outputs, clear);
  }
  void draw(std::string_view what, const Variant& variant, const gl::Texture& output,
            std::optional<glm::vec4> clear = std::nullopt) {
    draw_.draw(what, programs_.get(variant), output, clear);
  }

 private:
  ProgramCache<Variant> programs_;
  FullscreenDraw draw_;
};

}  // namespace headlight

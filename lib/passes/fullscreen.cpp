#include "passes/fullscreen.hpp"

#include "headlight/error.hpp"
#include "shared_layout.h"

namespace headlight {
namespace {

// The image format qualifier (GLSL) of an output texture's internal format.
std::string_view imageFormatQualifier(GLenum internalFormat) {
  switch (internalFormat) {
    case GL_RGBA32F:
      return "rgba32f";
    case GL_RGBA16F:
      return "rgba16f";
    case GL_RG16F:
      return "rg16f";
    case GL_RGBA8:
      return "rgba8";
    default:
      return {};
  }
}

}  // namespace

PassEntry passEntry(PassForm form, std::span<const PassOutput> outputs, bool accumulates) {
  PassEntry entry{form, accumulates, {}};
  for (const PassOutput& output : outputs) entry.outputs.emplace_back(output.member, output.texture->internalFormat());
  return entry;
}

gl::Program buildPassProgram(std::string_view body, const PassEntry& entry, std::span<const std::string> defines) {
  if (entry.outputs.empty() || entry.outputs.size() > kMaxPassOutputs)
    throw GlError(std::string(body) + ": " + std::to_string(entry.outputs.size()) + " outputs, expected 1 to " +
                  std::to_string(kMaxPassOutputs));
  std::vector<std::string> all(defines.begin(), defines.end());
  all.push_back("PASS_OUTPUT_COUNT " + std::to_string(entry.outputs.size()));
  for (std::size_t i = 0; i < entry.outputs.size(); ++i) {
    const auto& [member, format] = entry.outputs[i];
    all.push_back("PASS_OUTPUT" + std::to_string(i) + " " + member);
    if (entry.form == PassForm::Compute) {
      const std::string_view qualifier = imageFormatQualifier(format);
      if (qualifier.empty())
        throw GlError(std::string(body) + ": output " + member + " has internal format 0x" + std::to_string(format) +
                      ", which no image format qualifier names");
      all.push_back("PASS_OUTPUT" + std::to_string(i) + "_FORMAT " + std::string(qualifier));
    }
  }
  if (entry.accumulates) all.emplace_back("ACCUMULATE_OUTPUTS");
  if (entry.form == PassForm::Compute) {
    const std::string_view compute[] = {body, "fullscreen_entry.comp"};
    const detail::StageFiles stages[] = {{compute}};
    return detail::buildProgram(stages, all);
  }
  const std::string_view vertex[] = {"fullscreen.vert"};
  const std::string_view fragment[] = {body, "fullscreen_entry.frag"};
  const detail::StageFiles stages[] = {{vertex}, {fragment}};
  return detail::buildProgram(stages, all);
}

FullscreenRunner::FullscreenRunner()
    : framebuffer_(gl::Framebuffer::create()), emptyVertexArray_(gl::VertexArray::create()) {}

void FullscreenRunner::run(std::string_view what, const gl::Program& program, PassForm form,
                           std::span<const PassOutput> outputs, std::optional<float> accumulateWeight) {
  if (outputs.empty() || outputs.size() > kMaxPassOutputs)
    throw GlError("FullscreenRunner: " + std::string(what) + " has " + std::to_string(outputs.size()) +
                  " outputs, expected 1 to " + std::to_string(kMaxPassOutputs));
  const int width = outputs[0].texture->width(), height = outputs[0].texture->height();
  for (const PassOutput& output : outputs)
    if (output.texture->width() != width || output.texture->height() != height)
      throw GlError("FullscreenRunner: " + std::string(what) + "'s outputs differ in size (" +
                    std::string(output.member) + " is " + std::to_string(output.texture->width()) + "x" +
                    std::to_string(output.texture->height()) + ", " + std::string(outputs[0].member) + " " +
                    std::to_string(width) + "x" + std::to_string(height) + ")");
  if (accumulateWeight) glProgramUniform1f(program.id(), gpu::kLocationAccumulateWeight, *accumulateWeight);
  program.use();
  if (form == PassForm::Compute) {
    for (std::size_t i = 0; i < outputs.size(); ++i) {
      const gl::Texture& texture = *outputs[i].texture;
      glBindImageTexture(GLuint(gpu::kImagePassOutput0 + int(i)), texture.id(), 0, GL_FALSE, 0,
                         accumulateWeight ? GL_READ_WRITE : GL_WRITE_ONLY, texture.internalFormat());
    }
    glDispatchCompute(GLuint((width + gpu::kPassGroupSize - 1) / gpu::kPassGroupSize),
                      GLuint((height + gpu::kPassGroupSize - 1) / gpu::kPassGroupSize), 1);
    // Whatever reads the outputs next (a pass's texelFetch, an image load, a
    // framebuffer, a copy or the readback) sees the stores.
    glMemoryBarrier(GL_ALL_BARRIER_BITS);
    for (std::size_t i = 0; i < outputs.size(); ++i)
      glBindImageTexture(GLuint(gpu::kImagePassOutput0 + int(i)), 0, 0, GL_FALSE, 0, GL_WRITE_ONLY, GL_RGBA16F);
    return;
  }
  static constexpr GLenum kAttachments[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                            GL_COLOR_ATTACHMENT3};
  static_assert(std::size(kAttachments) == kMaxPassOutputs);
  for (std::size_t i = 0; i < outputs.size(); ++i) framebuffer_.attach(kAttachments[i], *outputs[i].texture);
  framebuffer_.setDrawBuffers(std::span(kAttachments, outputs.size()));
  framebuffer_.checkComplete(what);
  framebuffer_.bind();
  glViewport(0, 0, width, height);
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_BLEND);
  if (accumulateWeight) {
    // Each fragment reads its own texel of the output it writes: defined
    // once the previous draw's writes are made visible to texture fetches.
    for (std::size_t i = 0; i < outputs.size(); ++i) outputs[i].texture->bind(gpu::kUnitPassAccumulated0 + int(i));
    glTextureBarrier();
  }
  emptyVertexArray_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  for (std::size_t i = 0; i < outputs.size(); ++i) framebuffer_.detach(kAttachments[i]);
}

}  // namespace headlight

#include "passes/environment.hpp"

#include "gl/shader_library.hpp"
#include "shared_layout.h"

namespace headlight {
namespace {

gl::Program buildTableProgram(const char* fragment) {
  const std::string_view files[] = {"fullscreen.vert", fragment};
  return detail::buildProgram(files);
}

}  // namespace

EnvironmentPass::EnvironmentPass()
    : brdfProgram_(buildTableProgram("brdf_lut.frag")),
      prefilterProgram_(buildTableProgram("sky_prefilter.frag")),
      irradianceProgram_(buildTableProgram("sky_irradiance.frag")),
      skyBlock_(sizeof(gpu::SkyBlock), nullptr) {
  tables_.brdfLut = gl::Texture(GL_TEXTURE_2D, GL_RG16F, gpu::kBrdfLutSize, gpu::kBrdfLutSize);
  tables_.skyPrefiltered = gl::Texture(GL_TEXTURE_2D, GL_RGBA16F, gpu::kSkyTableWidth, gpu::kSkyRoughnessLevels);
  tables_.skyIrradiance = gl::Texture(GL_TEXTURE_2D, GL_RGBA16F, gpu::kSkyTableWidth, 1);
  for (const gl::Texture* table : {&tables_.brdfLut, &tables_.skyPrefiltered, &tables_.skyIrradiance}) {
    glTextureParameteri(table->id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(table->id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(table->id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(table->id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  renderTable(brdfProgram_, tables_.brdfLut);
}

void EnvironmentPass::updateSky(const Sky& sky) {
  // Intensity is applied in the composite pass, so a changed intensity
  // needs no new table.
  if (tabulatedSky_ && tabulatedSky_->zenith == sky.zenith && tabulatedSky_->horizon == sky.horizon &&
      tabulatedSky_->ground == sky.ground)
    return;
  tabulatedSky_ = sky;
  gpu::SkyBlock block{glm::vec4(sky.zenith, 0.0f), glm::vec4(sky.horizon, 0.0f), glm::vec4(sky.ground, 0.0f)};
  skyBlock_.update(block);
  skyBlock_.bindUniform(gpu::SkyBlock::kBinding);
  renderTable(prefilterProgram_, tables_.skyPrefiltered);
  renderTable(irradianceProgram_, tables_.skyIrradiance);
}

void EnvironmentPass::renderTable(const gl::Program& program, const gl::Texture& target) {
  gl::Framebuffer framebuffer;
  framebuffer.attach(GL_COLOR_ATTACHMENT0, target);
  const GLenum drawBuffers[] = {GL_COLOR_ATTACHMENT0};
  framebuffer.setDrawBuffers(drawBuffers);
  framebuffer.checkComplete("environment table");
  framebuffer.bind();
  glViewport(0, 0, target.width(), target.height());
  glDisable(GL_DEPTH_TEST);
  program.use();
  emptyVertexArray_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

}  // namespace headlight

#include "passes/direct_light.hpp"

#include "gl/shader_library.hpp"
#include "shared_layout.h"

namespace headlight {

const gl::Program& DirectLightPass::programFor(const Variant& variant) {
  auto found = programs_.find(variant);
  if (found != programs_.end()) return found->second;
  std::vector<std::string> defines;
  if (variant.emissive) defines.emplace_back("HAS_EMISSIVE");
  if (variant.planarShadows) defines.emplace_back("HAS_PLANAR_SHADOWS");
  if (variant.cubeShadows) defines.emplace_back("HAS_CUBE_SHADOWS");
  if (variant.diffuseTarget) defines.emplace_back("WRITE_DIFFUSE_RADIANCE");
  const std::string_view files[] = {"fullscreen.vert", "direct_light.frag"};
  return programs_.emplace(variant, detail::buildProgram(files, defines)).first->second;
}

void DirectLightPass::run(const GBuffer& gbuffer, const ShadowMaps& shadows, DirectLightTargets& targets) {
  const bool diffuse = bool(targets.diffuse);
  framebuffer_.attach(GL_COLOR_ATTACHMENT0, targets.towardEye);
  if (diffuse) framebuffer_.attach(GL_COLOR_ATTACHMENT1, targets.diffuse);
  const GLenum drawBuffers[] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
  framebuffer_.setDrawBuffers(std::span(drawBuffers, diffuse ? 2 : 1));
  framebuffer_.checkComplete("direct light");
  framebuffer_.bind();
  glViewport(0, 0, targets.towardEye.width(), targets.towardEye.height());
  const float zero[] = {0.0f, 0.0f, 0.0f, 0.0f};
  glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 0, zero);
  if (diffuse) glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 1, zero);
  glDisable(GL_DEPTH_TEST);

  gbuffer.position.bind(gpu::kUnitGbufferPosition);
  gbuffer.normal.bind(gpu::kUnitGbufferNormal);
  gbuffer.albedo.bind(gpu::kUnitGbufferAlbedo);
  gbuffer.material.bind(gpu::kUnitGbufferMaterial);
  if (gbuffer.emissive) gbuffer.emissive.bind(gpu::kUnitGbufferEmissive);
  if (shadows.planar) shadows.planar.bind(gpu::kUnitShadowMaps2D);
  if (shadows.cube) shadows.cube.bind(gpu::kUnitShadowMapsCube);
  programFor({bool(gbuffer.emissive), bool(shadows.planar), bool(shadows.cube), diffuse}).use();
  emptyVertexArray_.bind();
  glDrawArrays(GL_TRIANGLES, 0, 3);
  framebuffer_.detach(GL_COLOR_ATTACHMENT0);
  framebuffer_.detach(GL_COLOR_ATTACHMENT1);
}

}  // namespace headlight

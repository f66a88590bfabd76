#include "passes/gbuffer.hpp"

#include <string>
#include <vector>

#include "gl/shader_library.hpp"
#include "shared_layout.h"

namespace headlight {

namespace {

std::vector<std::string> definesFor(FeatureBits features, const std::vector<std::string>& targetDefines) {
  std::vector<std::string> defines = featureDefines(features);
  defines.insert(defines.end(), targetDefines.begin(), targetDefines.end());
  return defines;
}

}  // namespace

GBufferPass::GBufferPass(const GpuScene& scene, const GBufferVariant& variant)
    : programs_("gbuffer.vert", "gbuffer.frag",
                [](const ProgramKey& key) { return definesFor(key.features, key.targetDefines); }) {
  for (const GpuDrawGroup& group : scene.drawGroups)
    programs_.get({drawFeatures(scene.primitives[std::size_t(group.primitive)],
                                  scene.materials[std::size_t(group.material)]),
                   variant.defines});
}

void GBufferPass::run(const GpuScene& scene, const GBufferTargets& targets, const GBufferVariant& variant,
                      Faces faces) {
  attach(targets);
  // Zero everywhere: position.a = 0 marks background for every later pass.
  // An integer target (ids) is cleared as integers: a float clear of it is undefined.
  const float zero[] = {0.0f, 0.0f, 0.0f, 0.0f};
  const GLuint zeroIds[] = {0, 0, 0, 0};
  for (std::size_t location = 0; location < targets.colors.size(); ++location) {
    const gl::Texture* color = targets.colors[location];
    if (!color) continue;
    if (color->internalFormat() == GL_RGBA32UI)
      glClearNamedFramebufferuiv(framebuffer_.id(), GL_COLOR, GLint(location), zeroIds);
    else
      glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, GLint(location), zero);
  }
  const float farDepth = 1.0f;
  glClearNamedFramebufferfv(framebuffer_.id(), GL_DEPTH, 0, &farDepth);
  draw(scene, variant,
       faces == Faces::Back        ? Draws::BackFaces
       : variant.deferTransmissive ? Draws::Opaque
                                   : Draws::All);
  detach(targets);
}

void GBufferPass::drawTransmissive(const GpuScene& scene, const GBufferTargets& targets,
                                   const GBufferVariant& variant) {
  attach(targets);
  draw(scene, variant, Draws::Transmissive);
  detach(targets);
}

void GBufferPass::attach(const GBufferTargets& targets) {
  // Attached every frame: the plan may change the set, and a size change
  // replaces the textures.
  std::vector<GLenum> drawBuffers;
  for (std::size_t location = 0; location < targets.colors.size(); ++location) {
    const GLenum attachment = GLenum(GL_COLOR_ATTACHMENT0 + location);
    if (targets.colors[location]) framebuffer_.attach(attachment, *targets.colors[location]);
    drawBuffers.push_back(targets.colors[location] ? attachment : GL_NONE);
  }
  framebuffer_.attach(GL_DEPTH_ATTACHMENT, *targets.depth);
  framebuffer_.setDrawBuffers(drawBuffers);
  framebuffer_.checkComplete("G-buffer");
  framebuffer_.bind();
  glViewport(0, 0, targets.width, targets.height);
}

void GBufferPass::draw(const GpuScene& scene, const GBufferVariant& variant, Draws draws) {
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  // Writes to the sRGB albedo target are encoded only with this on.
  glEnable(GL_FRAMEBUFFER_SRGB);

  scene.objects.bindStorage(gpu::ObjectBuffer::kBinding);
  for (const GpuDrawGroup& group : scene.drawGroups) {
    const GpuPrimitive& primitive = scene.primitives[std::size_t(group.primitive)];
    const GpuMaterial& material = scene.materials[std::size_t(group.material)];
    if ((draws == Draws::Opaque && material.transmissive) || (draws == Draws::Transmissive && !material.transmissive) ||
        (draws == Draws::BackFaces && material.doubleSided))
      continue;
    const FeatureBits features = drawFeatures(primitive, material);
    programs_.get({features, variant.defines}).use();
    if (material.doubleSided)
      glDisable(GL_CULL_FACE);
    else
      glEnable(GL_CULL_FACE);
    glCullFace(draws == Draws::BackFaces ? GL_FRONT : GL_BACK);
    // Also decides gl_FrontFacing, so a mirrored double-sided mesh keeps
    // its normals pointing the right way.
    glFrontFace(group.mirrored ? GL_CW : GL_CCW);
    material.block.bindUniform(gpu::MaterialBlock::kBinding);
    bindMaterialTextures(scene, material, features);
    primitive.vertexArray.bind();
    glDrawElementsInstancedBaseInstance(primitive.mode, primitive.indexCount, GL_UNSIGNED_INT, nullptr,
                                        group.instanceCount, group.firstInstance);
  }
  glDisable(GL_FRAMEBUFFER_SRGB);
  glDisable(GL_CULL_FACE);
  glCullFace(GL_BACK);
  glFrontFace(GL_CCW);
}

void GBufferPass::detach(const GBufferTargets& targets) {
  // Detached, so that a dropped attachment is not kept alive (gl/objects.hpp).
  for (std::size_t location = 0; location < targets.colors.size(); ++location)
    framebuffer_.detach(GLenum(GL_COLOR_ATTACHMENT0 + location));
  framebuffer_.detach(GL_DEPTH_ATTACHMENT);
}

}  // namespace headlight

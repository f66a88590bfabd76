#include "passes/gbuffer.hpp"

#include <string>
#include <vector>

#include "gl/shader_library.hpp"
#include "gl/target_formats.hpp"
#include "shared_layout.h"

namespace headlight {

GBuffer makeGBuffer(int width, int height, bool withEmissive) {
  GBuffer gbuffer;
  gbuffer.width = width;
  gbuffer.height = height;
  gbuffer.position = gl::Texture::create2D(gl::targetFormat(&Frame::position), width, height);
  gbuffer.normal = gl::Texture::create2D(gl::targetFormat(&Frame::normal), width, height);
  gbuffer.albedo = gl::Texture::create2D(gl::targetFormat(&Frame::albedo), width, height);
  gbuffer.material = gl::Texture::create2D(gl::targetFormat(&Frame::material), width, height);
  gbuffer.depth = gl::Texture::create2D(gl::targetFormat(&Frame::depth), width, height);
  gbuffer.framebuffer = gl::Framebuffer::create();
  auto& fb = gbuffer.framebuffer;
  fb.attach(GL_COLOR_ATTACHMENT0, gbuffer.position);
  fb.attach(GL_COLOR_ATTACHMENT1, gbuffer.normal);
  fb.attach(GL_COLOR_ATTACHMENT2, gbuffer.albedo);
  fb.attach(GL_COLOR_ATTACHMENT3, gbuffer.material);
  fb.attach(GL_DEPTH_ATTACHMENT, gbuffer.depth);
  std::vector<GLenum> drawBuffers{GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1, GL_COLOR_ATTACHMENT2,
                                  GL_COLOR_ATTACHMENT3};
  if (withEmissive) {
    gbuffer.emissive = gl::Texture::create2D(gl::targetFormat(&Frame::emissive), width, height);
    fb.attach(GL_COLOR_ATTACHMENT4, gbuffer.emissive);
    drawBuffers.push_back(GL_COLOR_ATTACHMENT4);
  }
  fb.setDrawBuffers(drawBuffers);
  fb.checkComplete("G-buffer");
  return gbuffer;
}

namespace {

std::vector<std::string> definesFor(std::uint32_t features, bool emissiveTarget) {
  static const std::pair<std::uint32_t, const char*> names[] = {
      {kFeatureTexcoords, "HAS_TEXCOORDS"},
      {kFeatureTangents, "HAS_TANGENTS"},
      {kFeatureBaseColorTexture, "HAS_BASE_COLOR_TEXTURE"},
      {kFeatureMetallicRoughnessTexture, "HAS_METALLIC_ROUGHNESS_TEXTURE"},
      {kFeatureNormalTexture, "HAS_NORMAL_TEXTURE"},
      {kFeatureOcclusionTexture, "HAS_OCCLUSION_TEXTURE"},
      {kFeatureEmissiveTexture, "HAS_EMISSIVE_TEXTURE"},
  };
  std::vector<std::string> defines;
  for (const auto& [bit, name] : names)
    if (features & bit) defines.emplace_back(name);
  if (emissiveTarget) defines.emplace_back("HAS_EMISSIVE_TARGET");
  return defines;
}

// A texture without texcoords to read it by is ignored, as glTF viewers do.
std::uint32_t usableFeatures(const GpuPrimitive& primitive, const GpuMaterial& material) {
  std::uint32_t features = primitive.vertexFeatures;
  if (features & kFeatureTexcoords) features |= material.textureFeatures;
  return features;
}

void bindMaterialTextures(const GpuScene& scene, const GpuMaterial& material, std::uint32_t features) {
  const std::pair<int, int> unitTexture[] = {
      {gpu::kUnitBaseColorTexture, material.baseColor},
      {gpu::kUnitMetallicRoughnessTexture, material.metallicRoughness},
      {gpu::kUnitNormalTexture, material.normal},
      {gpu::kUnitOcclusionTexture, material.occlusion},
      {gpu::kUnitEmissiveTexture, material.emissive},
  };
  if (!(features & kFeatureTexcoords)) return;
  for (const auto& [unit, texture] : unitTexture) {
    if (texture < 0) continue;
    scene.textures[std::size_t(texture)].texture.bind(unit);
    scene.textures[std::size_t(texture)].sampler.bind(unit);
  }
}

}  // namespace

GBufferPass::GBufferPass(const GpuScene& scene)
    : programs_("gbuffer.vert", "gbuffer.frag", [emissiveTarget = scene.hasEmissive](std::uint32_t features) {
        return definesFor(features, emissiveTarget);
      }) {
  for (const GpuInstance& instance : scene.instances)
    programs_.get(usableFeatures(scene.primitives[std::size_t(instance.primitive)],
                                 scene.materials[std::size_t(instance.material)]));
}

void GBufferPass::run(const GpuScene& scene, GBuffer& target) {
  target.framebuffer.bind();
  glViewport(0, 0, target.width, target.height);
  // Zero everywhere: position.a = 0 marks background for every later pass.
  const float zero[] = {0.0f, 0.0f, 0.0f, 0.0f};
  for (int attachment = 0; attachment < (target.emissive ? 5 : 4); ++attachment)
    glClearNamedFramebufferfv(target.framebuffer.id(), GL_COLOR, attachment, zero);
  const float farDepth = 1.0f;
  glClearNamedFramebufferfv(target.framebuffer.id(), GL_DEPTH, 0, &farDepth);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  // Writes to the sRGB albedo target are encoded only with this on.
  glEnable(GL_FRAMEBUFFER_SRGB);

  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    const GpuPrimitive& primitive = scene.primitives[std::size_t(scene.instances[i].primitive)];
    const GpuMaterial& material = scene.materials[std::size_t(scene.instances[i].material)];
    const std::uint32_t features = usableFeatures(primitive, material);
    programs_.get(features).use();
    if (material.doubleSided)
      glDisable(GL_CULL_FACE);
    else
      glEnable(GL_CULL_FACE);
    // Also decides gl_FrontFacing, so a mirrored double-sided mesh keeps
    // its normals pointing the right way.
    glFrontFace(scene.instances[i].mirrored ? GL_CW : GL_CCW);
    material.block.bindUniform(gpu::MaterialBlock::kBinding);
    bindMaterialTextures(scene, material, features);
    glBindBufferRange(GL_UNIFORM_BUFFER, gpu::ObjectBlock::kBinding, scene.instanceBlocks.id(),
                      GLintptr(i * scene.instanceStride), sizeof(gpu::ObjectBlock));
    primitive.vertexArray.bind();
    glDrawElements(GL_TRIANGLES, primitive.indexCount, GL_UNSIGNED_INT, nullptr);
  }
  glDisable(GL_FRAMEBUFFER_SRGB);
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
}

}  // namespace headlight

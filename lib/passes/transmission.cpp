#include "passes/transmission.hpp"

#include <algorithm>

#include "passes/forward_targets.hpp"
#include "shared_layout.h"

namespace headlight {

namespace {

std::vector<std::string> transmissionDefines(FeatureBits features, const TransmissionVariant& variant) {
  std::vector<std::string> defines = featureDefines(features);
  defines.emplace_back("TRANSMISSION_FORWARD");
  appendForwardLightingDefines(variant, defines);
  return defines;
}

void bindLightingInputs(const TransmissionInputs& inputs, const TransmissionVariant& variant) {
  bindForwardLighting(inputs.shadows, inputs.environment, variant);
  // The throughput's specular albedo reads the BRDF table with or without the sky term.
  inputs.environment.brdfLut.bind(gpu::kUnitBrdfLut);
}

}  // namespace

TransmissionPass::TransmissionPass()
    : programs_("gbuffer.vert", "gbuffer.frag",
                [](const ProgramKey& key) { return transmissionDefines(key.features, key.variant); }) {
  // Trilinear: the roughness picks a fractional level. Clamped: a refracted
  // path that leaves the image reads its edge.
  backgroundSampler_.set(GL_TEXTURE_MIN_FILTER, GL_LINEAR_MIPMAP_LINEAR);
  backgroundSampler_.set(GL_TEXTURE_MAG_FILTER, GL_LINEAR);
  backgroundSampler_.set(GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
  backgroundSampler_.set(GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
}

void TransmissionPass::prepare(const GpuScene& scene, const TransmissionVariant& variant) {
  for (const GpuDrawGroup& group : scene.drawGroups) {
    const GpuMaterial& material = scene.materials[std::size_t(group.material)];
    if (material.transmissive)
      programs_.get({drawFeatures(scene.primitives[std::size_t(group.primitive)], material), variant});
  }
}

void TransmissionPass::copyBackground(const gl::Texture& lit, const gl::Texture& position) {
  if (backgroundPosition_.width() != position.width() || backgroundPosition_.height() != position.height() ||
      backgroundPosition_.internalFormat() != position.internalFormat())
    backgroundPosition_ = gl::Texture::create2D(position.internalFormat(), position.width(), position.height());
  glCopyImageSubData(position.id(), GL_TEXTURE_2D, 0, 0, 0, 0, backgroundPosition_.id(), GL_TEXTURE_2D, 0, 0, 0, 0,
                     position.width(), position.height(), 1);
  if (background_.width() != lit.width() || background_.height() != lit.height() ||
      background_.internalFormat() != lit.internalFormat())
    background_ = gl::Texture::create2D(lit.internalFormat(), lit.width(), lit.height(),
                                        gl::fullMipChainLevels(lit.width(), lit.height()));
  glCopyImageSubData(lit.id(), GL_TEXTURE_2D, 0, 0, 0, 0, background_.id(), GL_TEXTURE_2D, 0, 0, 0, 0, lit.width(),
                     lit.height(), 1);
  glGenerateTextureMipmap(background_.id());
}

void TransmissionPass::run(const TransmissionInputs& inputs, const TransmissionTargets& targets,
                           const TransmissionVariant& variant) {
  // G-buffer location 0 is the position (the attachment table's first row).
  copyBackground(targets.lit, *inputs.gbufferTargets.colors.at(0));
  inputs.gbuffer.drawTransmissive(inputs.scene, inputs.gbufferTargets, inputs.gbufferVariant);
  shade(inputs, targets, variant);
}

void TransmissionPass::shade(const TransmissionInputs& inputs, const TransmissionTargets& targets,
                             const TransmissionVariant& variant) {
  const GpuScene& scene = inputs.scene;
  bindForwardTargets(framebuffer_, targets.lit, targets.transmission, *inputs.gbufferTargets.depth, targets.width,
                     targets.height, "transmission");
  // Equal to what step 2 wrote: only the nearest transmissive surface of a
  // pixel is shaded (gbuffer.vert's gl_Position is invariant, so both
  // programs rasterise the same depths).
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_EQUAL);
  glDepthMask(GL_FALSE);
  bindLightingInputs(inputs, variant);
  background_.bind(gpu::kUnitTransmissionBackground);
  backgroundSampler_.bind(gpu::kUnitTransmissionBackground);
  backgroundPosition_.bind(gpu::kUnitTransmissionBackgroundPosition);
  scene.objects.bindStorage(gpu::ObjectBuffer::kBinding);

  for (const GpuDrawGroup& group : scene.drawGroups) {
    const GpuMaterial& material = scene.materials[std::size_t(group.material)];
    if (!material.transmissive) continue;
    const GpuPrimitive& primitive = scene.primitives[std::size_t(group.primitive)];
    const FeatureBits features = drawFeatures(primitive, material);
    programs_.get({features, variant}).use();
    if (material.doubleSided)
      glDisable(GL_CULL_FACE);
    else
      glEnable(GL_CULL_FACE);
    glFrontFace(group.mirrored ? GL_CW : GL_CCW);
    material.block.bindUniform(gpu::MaterialBlock::kBinding);
    bindMaterialTextures(scene, material, features);
    primitive.vertexArray.bind();
    glDrawElementsInstancedBaseInstance(primitive.mode, primitive.indexCount, GL_UNSIGNED_INT, nullptr,
                                        group.instanceCount, group.firstInstance);
  }
  glBindSampler(GLuint(gpu::kUnitTransmissionBackground), 0);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  framebuffer_.detach(GL_COLOR_ATTACHMENT0);
  framebuffer_.detach(GL_COLOR_ATTACHMENT1);
  framebuffer_.detach(GL_DEPTH_ATTACHMENT);
}

}  // namespace headlight

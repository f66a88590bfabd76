#include "passes/blend.hpp"

#include <algorithm>
#include <numeric>

#include "passes/forward_targets.hpp"
#include "shared_layout.h"

namespace headlight {

namespace {

std::vector<std::string> blendDefines(FeatureBits features, const BlendVariant& variant) {
  std::vector<std::string> defines = featureDefines(features);
  defines.emplace_back("BLEND_FORWARD");
  appendForwardLightingDefines(variant, defines);
  return defines;
}

// Premultiplied "over" on both targets: colour by alpha, alpha as coverage.
void setBlendState() {
  glEnable(GL_BLEND);
  glBlendEquation(GL_FUNC_ADD);
  glBlendFuncSeparatei(0, GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
  glBlendFunci(1, GL_ONE, GL_ONE_MINUS_SRC_ALPHA);
}

}  // namespace

std::vector<std::size_t> blendOrder(const std::vector<GpuBlendDraw>& draws, const CameraView& view) {
  std::vector<float> viewZ(draws.size());
  for (std::size_t i = 0; i < draws.size(); ++i) viewZ[i] = (view.view * glm::vec4(draws[i].worldCenter, 1.0f)).z;
  std::vector<std::size_t> order(draws.size());
  std::iota(order.begin(), order.end(), std::size_t(0));
  // The camera looks down -Z: the most negative z is the farthest.
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) { return viewZ[a] < viewZ[b]; });
  return order;
}

BlendPass::BlendPass()
    : programs_("gbuffer.vert", "gbuffer.frag",
                [](const ProgramKey& key) { return blendDefines(key.features, key.variant); }) {}

void BlendPass::prepare(const GpuScene& scene, const BlendVariant& variant) {
  for (const GpuBlendDraw& draw : scene.blendDraws)
    programs_.get({drawFeatures(scene.primitives[std::size_t(draw.primitive)],
                                scene.materials[std::size_t(draw.material)]),
                   variant});
}

void BlendPass::run(const BlendInputs& inputs, const BlendTargets& targets, const BlendVariant& variant) {
  const GpuScene& scene = inputs.scene;
  bindForwardTargets(framebuffer_, targets.lit, targets.coverage, inputs.depth, targets.width, targets.height, "blend");
  // Tested against the opaque surfaces, not written: blended layers do not
  // hide each other, the sort orders them.
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  glDepthMask(GL_FALSE);
  setBlendState();
  bindForwardLighting(inputs.shadows, inputs.environment, variant);
  scene.objects.bindStorage(gpu::ObjectBuffer::kBinding);

  for (std::size_t index : blendOrder(scene.blendDraws, inputs.view)) {
    const GpuBlendDraw& draw = scene.blendDraws[index];
    const GpuPrimitive& primitive = scene.primitives[std::size_t(draw.primitive)];
    const GpuMaterial& material = scene.materials[std::size_t(draw.material)];
    const FeatureBits features = drawFeatures(primitive, material);
    programs_.get({features, variant}).use();
    if (material.doubleSided)
      glDisable(GL_CULL_FACE);
    else
      glEnable(GL_CULL_FACE);
    glFrontFace(draw.mirrored ? GL_CW : GL_CCW);
    material.block.bindUniform(gpu::MaterialBlock::kBinding);
    bindMaterialTextures(scene, material, features);
    primitive.vertexArray.bind();
    glDrawElementsInstancedBaseInstance(primitive.mode, primitive.indexCount, GL_UNSIGNED_INT, nullptr, 1,
                                        draw.drawPosition);
  }
  glDisable(GL_BLEND);
  glDepthMask(GL_TRUE);
  glDisable(GL_CULL_FACE);
  glFrontFace(GL_CCW);
  framebuffer_.detach(GL_COLOR_ATTACHMENT0);
  framebuffer_.detach(GL_COLOR_ATTACHMENT1);
  framebuffer_.detach(GL_DEPTH_ATTACHMENT);
}

}  // namespace headlight

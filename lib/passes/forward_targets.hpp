#pragma once
// What the forward passes over lit (blend, transmission) share: the lighting
// #defines and inputs of their variants (BlendVariant and TransmissionVariant
// carry the same shadow, sky and environment flags), and their framebuffer.
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "frame/frame_plan.hpp"
#include "gl/objects.hpp"
#include "passes/environment.hpp"
#include "passes/shadow.hpp"
#include "shared_layout.h"

namespace headlight {

// The shadow lookups' defines (appendShadowDefines), HAS_SKY, HAS_ENVIRONMENT
// and the lobes' (lobeDefines: the material's own values, surface.glsl
// forwardLobes), as the variant says.
template <class Variant>
void appendForwardLightingDefines(const Variant& variant, std::vector<std::string>& defines) {
  appendShadowDefines(variant.shadows, defines);
  if (variant.sky) defines.emplace_back("HAS_SKY");
  if (variant.environment) defines.emplace_back("HAS_ENVIRONMENT");
  for (std::string& define : lobeDefines(variant.lobes)) defines.push_back(std::move(define));
}

// The shadow maps and ambient tables those defines read.
template <class Variant>
void bindForwardLighting(const ShadowMaps& shadows, const EnvironmentTables& environment, const Variant& variant) {
  bindShadowMaps(shadows, variant.shadows);
  bindAmbientTables(environment, variant.sky, variant.environment);
}

// Lit at output 0 and the pass's own target at output 1 (cleared to 0),
// depth-tested against the G-buffer's depth; bound, with the viewport set.
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

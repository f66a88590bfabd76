#pragma once
// The direct-light pass: every punctual light (glTF units and range falloff,
// PCF-filtered shadows where a map exists) plus emission, from the G-buffer.
//   target 0 GL_RGBA16F  radiance toward the eye (Cook-Torrance GGX)
//   target 1 GL_RGBA16F  Lambertian radiance leaving the surface, for the SSGI
//                        `radiance` method to gather; made only when asked
// Background pixels stay 0.
#include <map>

#include "gl/objects.hpp"
#include "passes/gbuffer.hpp"
#include "passes/shadow.hpp"

namespace headlight {

struct DirectLightTargets {
  gl::Texture towardEye;  // always
  gl::Texture diffuse;    // only for the SSGI radiance method
};

class DirectLightPass {
 public:
  struct Variant {
    bool emissive, planarShadows, cubeShadows, diffuseTarget;
    auto operator<=>(const Variant&) const = default;
  };
  DirectLightPass() = default;
  void prepare(const Variant& variant) { programFor(variant); }
  // The lighting block (light count, PCF radius) and the light buffer must be
  // bound; reads gbuffer and `shadows`.
  void run(const GBuffer& gbuffer, const ShadowMaps& shadows, DirectLightTargets& targets);

 private:
  const gl::Program& programFor(const Variant& variant);
  std::map<Variant, gl::Program> programs_;
  gl::Framebuffer framebuffer_;
  gl::VertexArray emptyVertexArray_;
};

}  // namespace headlight

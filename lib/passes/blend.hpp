#pragma once
// The blend pass: alphaMode BLEND surfaces, drawn after the composite over
// the lit target, back to front, lit by the same lights, shadow maps and
// sky as the G-buffer's surfaces (gbuffer.frag built with BLEND_FORWARD:
// the material as the G-buffer evaluates it, lit by glsl/blend.glsl).
//
// Inputs: the scene's blend draws (GpuScene::blendDraws), the G-buffer's
// depth (tested, not written: a blended surface behind an opaque one is
// hidden, and blended surfaces do not hide each other), the shadow maps and
// environment tables the variant reads, the frame, lighting and light
// blocks (bound by the renderer). Outputs, both blended:
//   lit       RGB = a * radiance + (1 - a) * RGB, A = a + (1 - a) * A
//   coverage  1 - prod(1 - a) over the layers drawn at the pixel
// The G-buffer keeps the opaque surface (or background) under a blended
// one: its targets describe what the direct, SSGI and composite passes lit.
//
// Sort key: the view-space depth of the centre of each instance's world
// bounds, farthest first (ties keep the file's order); one draw per
// instance. Known failures: two blended surfaces that intersect, or that
// interleave in depth (a long pane whose centre is nearer than a small one
// in front of its far end), are drawn in the wrong order for some pixels;
// the triangles of one instance are drawn in index order, so a closed
// double-sided blended mesh may draw its far side over its near side.
#include <cstdint>
#include <vector>

#include "frame/frame_plan.hpp"
#include "gl/gpu_scene.hpp"
#include "gl/objects.hpp"
#include "headlight/camera.hpp"
#include "passes/environment.hpp"
#include "passes/program_cache.hpp"
#include "passes/shadow.hpp"

namespace headlight {

struct BlendInputs {
  const GpuScene& scene;
  const CameraView& view;                // the sort's view depth
  const gl::Texture& depth;              // the G-buffer's depth attachment
  const ShadowMaps& shadows;             // read by the variant's shadow flags
  const EnvironmentTables& environment;  // read by the variant with the sky term
};

struct BlendTargets {
  const gl::Texture& lit;       // the composite's output, blended over
  const gl::Texture& coverage;  // cleared to 0 here, then blended
  int width = 0;
  int height = 0;
};

// The order the pass draws `draws` in: indices into it, farthest centre
// first along the view's -Z (the sort key above), stable.
std::vector<std::size_t> blendOrder(const std::vector<GpuBlendDraw>& draws, const CameraView& view);

class BlendPass {
 public:
  BlendPass();
  // Builds the programs `scene`'s blend draws need for `variant` (setScene:
  // the default frame's), so the first frame times drawing, not compiling.
  void prepare(const GpuScene& scene, const BlendVariant& variant);
  // Draws every blended instance of `inputs.scene`, back to front.
  void run(const BlendInputs& inputs, const BlendTargets& targets, const BlendVariant& variant);

 private:
  struct ProgramKey {
    FeatureBits features;  // GBufferFeature bits of the draw
    BlendVariant variant;
    auto operator<=>(const ProgramKey&) const = default;
  };
  ProgramCache<ProgramKey> programs_;
  gl::Framebuffer framebuffer_ = gl::Framebuffer::create();
};

}  // namespace headlight

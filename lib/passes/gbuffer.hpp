#pragma once
// The G-buffer pass: the scene drawn once into four colour targets and depth
// (five with an emissive target, made only for scenes that glow). Formats
// come from the frame-target table (headlight/targets.hpp):
//   RT0 GL_RGBA32F      world position, A = 1 on geometry, 0 on background
//   RT1 GL_RGBA16F      world normal as a unit vector (not remapped to 0..1)
//   RT2 GL_SRGB8_ALPHA8 base colour (albedo)
//   RT3 GL_RGBA8        metallic, roughness, occlusion (glTF occlusion texture)
//   RT4 GL_RGBA16F      emissive radiance, only if the scene has any
//   depth GL_DEPTH_COMPONENT32F
// The frame plan lists them (frame/frame_plan.cpp, kAttachmentRows); an
// optional one is drawn only when its #define is set.
#include <cstdint>
#include <string>
#include <vector>

#include "frame/frame_plan.hpp"
#include "gl/gpu_scene.hpp"
#include "gl/objects.hpp"
#include "passes/program_cache.hpp"

namespace headlight {

// The G-buffer as the passes after it read it: the frame's attachments
// (empty textures for those the plan did not allocate).
struct GBuffer {
  const gl::Texture& position;
  const gl::Texture& normal;
  const gl::Texture& albedo;
  const gl::Texture& material;
  const gl::Texture& emissive;  // empty unless the scene has emissive materials
  const gl::Texture& depth;
  int width = 0;
  int height = 0;
};

// What the G-buffer pass draws into: colour targets by fragment-output
// location (null: not drawn this frame), and depth.
struct GBufferTargets {
  std::vector<const gl::Texture*> colors;
  const gl::Texture* depth = nullptr;
  int width = 0;
  int height = 0;
};

class GBufferPass {
 public:
  // Builds the programs the instances need for `variant` (the default frame's).
  GBufferPass(const GpuScene& scene, const GBufferVariant& variant);
  // Which faces a draw keeps: the front faces (a double-sided material's
  // both), or only the back faces of single-sided materials (what a light
  // field probe inside a closed mesh sees first: lib/passes/light_field.hpp).
  enum class Faces { Front, Back };
  // Draws every instance into `targets`, the attachments `variant` lists;
  // the frame block must be bound.
  void run(const GpuScene& scene, const GBufferTargets& targets, const GBufferVariant& variant,
           Faces faces = Faces::Front);
  // Draws the transmissive instances (GpuMaterial::transmissive) over what
  // run() left, depth-tested: the transmission pass's step 2, after the
  // composite has lit the opaque image (GBufferVariant::deferTransmissive).
  void drawTransmissive(const GpuScene& scene, const GBufferTargets& targets, const GBufferVariant& variant);

 private:
  enum class Draws { All, Opaque, Transmissive, BackFaces };
  void attach(const GBufferTargets& targets);
  void draw(const GpuScene& scene, const GBufferVariant& variant, Draws draws);
  void detach(const GBufferTargets& targets);

  // A program: the vertex and material features (GBufferFeature bits) and
  // the optional targets' #defines.
  struct ProgramKey {
    FeatureBits features;
    std::vector<std::string> targetDefines;
    auto operator<=>(const ProgramKey&) const = default;
  };
  ProgramCache<ProgramKey> programs_;
  gl::Framebuffer framebuffer_ = gl::Framebuffer::create();
};

}  // namespace headlight

#pragma once
// The scene on the GPU: one vertex array per primitive, one uniform block per
// material and per instance, one texture per image and colour space that a
// material actually uses. Only what the scene has is allocated.
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "gl/objects.hpp"
#include "headlight/scene.hpp"
#include "scene/material_textures.hpp"

namespace headlight {

// The #defines that build `features` into a shader (HAS_TEXCOORDS, ...,
// ALPHA_MASK): one table for the G-buffer and shadow passes.
std::vector<std::string> featureDefines(FeatureBits features);

struct GpuPrimitive {
  gl::VertexArray vertexArray;
  std::vector<gl::Buffer> buffers;  // positions, normals, [texcoords], [tangents], [colors], [texcoords1], indices
  GLsizei indexCount = 0;
  GLenum mode = GL_TRIANGLES;  // GL_LINES, GL_POINTS: drawn 1 pixel wide, in no shadow map
  // kFeatureTexcoords | kFeatureTangents | kFeatureVertexColors | kFeatureTexcoords1
  FeatureBits vertexFeatures = 0;
};

constexpr std::array<int, kMaterialTextureCount> filledWith(int value) {
  std::array<int, kMaterialTextureCount> array{};
  array.fill(value);
  return array;
}

struct GpuMaterial {
  gl::Buffer block;  // MaterialBlock
  // Texture indices into GpuScene::textures by MaterialTexture, -1 = none.
  std::array<int, kMaterialTextureCount> textures = filledWith(-1);
  // The textures (kFeature*Texture), the set each reads (kFeature*Texcoord1)
  // and kFeatureTextureTransform: read only where the primitive has texcoords.
  FeatureBits textureFeatures = 0;
  FeatureBits alphaFeatures = 0;    // kFeatureAlphaMask for alphaMode MASK (needs no texcoords)
  FeatureBits shadingFeatures = 0;  // kFeatureUnlit
  bool doubleSided = false;
  bool blended = false;  // alphaMode BLEND: drawn by the blend pass only (not the G-buffer, no shadow)
  // Material::transmissive: the G-buffer pass may leave it to the
  // transmission pass (GBufferVariant::deferTransmissive); casts shadows.
  bool transmissive = false;
};

struct GpuTexture {
  gl::Texture texture;
  gl::Sampler sampler;
};

// One instanced draw: every instance of a primitive with one material and
// one winding. Instances are drawn in draw order (sorted by primitive, then
// material, then winding), so a primitive's groups are contiguous and the
// shadow pass draws all its instances at once.
struct GpuDrawGroup {
  int primitive = 0;         // index into GpuScene::primitives
  int material = 0;          // index into GpuScene::materials
  bool mirrored = false;     // negative determinant: clockwise triangles face front (glTF)
  GLuint firstInstance = 0;  // into the draw order (the base instance of the draw)
  GLsizei instanceCount = 0;
};

// A primitive's instances in draw order, for passes that ignore materials
// unless one of them is masked (the shadow pass then draws the run's groups).
// Triangle primitives only: points and lines cast no shadow.
struct GpuPrimitiveRun {
  int primitive = 0;
  GLuint firstInstance = 0;
  GLsizei instanceCount = 0;
  std::size_t firstGroup = 0;  // the run's draw groups: drawGroups[firstGroup, firstGroup + groupCount)
  std::size_t groupCount = 0;
  bool masked = false;        // some group's material is alphaMode MASK
  bool transmissive = false;  // some group's material transmits (GpuMaterial::transmissive): not in the depth maps
};

// One instance of an alphaMode BLEND material: the blend pass sorts these
// by view depth every frame and draws them one by one, back to front.
struct GpuBlendDraw {
  int primitive = 0;
  int material = 0;
  bool mirrored = false;
  GLuint drawPosition = 0;      // its position in the draw order (the draw's base instance)
  glm::vec3 worldCenter{0.0f};  // the centre of its world bounds: the sort key's point
};

struct GpuScene {
  std::vector<GpuPrimitive> primitives;
  std::vector<GpuMaterial> materials;  // the scene's, then glTF's default material last
  std::vector<GpuTexture> textures;
  // Opaque and masked instances only: blended ones are in blendDraws.
  std::vector<GpuDrawGroup> drawGroups;        // in draw order
  std::vector<GpuPrimitiveRun> primitiveRuns;  // in draw order
  std::vector<GpuBlendDraw> blendDraws;        // after the others in the draw order, in Scene::instances order
  gl::Buffer objects;                          // GpuObject per instance, in Scene::instances order (ObjectBuffer)
  gl::Buffer drawOrder;  // per draw-order position, its instance's index into objects (kAttributeObjectIndex)
  Bounds bounds;
  bool hasEmissive = false;
};

GpuScene uploadScene(const Scene& scene);

// Binds the material's textures to their units (materialTextureRows()),
// when the draw's `features` read textures (it has texcoords).
void bindMaterialTextures(const GpuScene& scene, const GpuMaterial& material, FeatureBits features);

// The features a draw of `primitive` with `material` reads: a texture
// without texcoords to read it by is ignored, as glTF viewers do.
FeatureBits drawFeatures(const GpuPrimitive& primitive, const GpuMaterial& material);

}  // namespace headlight

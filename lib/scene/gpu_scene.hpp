#pragma once
// The scene on the GPU: one vertex array per primitive, one uniform block per
// material and per instance, one texture per image and colour space that a
// material actually uses. Only what the scene has is allocated.
#include <cstdint>
#include <vector>

#include "gl/objects.hpp"
#include "headlight/scene.hpp"

namespace headlight {

// Which optional inputs a G-buffer shader variant reads; a bit set, built
// into the shader as #defines.
enum GBufferFeature : std::uint32_t {
  kFeatureTexcoords = 1u << 0,
  kFeatureTangents = 1u << 1,
  kFeatureBaseColorTexture = 1u << 2,
  kFeatureMetallicRoughnessTexture = 1u << 3,
  kFeatureNormalTexture = 1u << 4,
  kFeatureOcclusionTexture = 1u << 5,
  kFeatureEmissiveTexture = 1u << 6,
};

struct GpuPrimitive {
  gl::VertexArray vertexArray;
  std::vector<gl::Buffer> buffers;  // positions, normals, [texcoords], [tangents], indices
  GLsizei indexCount = 0;
  std::uint32_t vertexFeatures = 0;  // kFeatureTexcoords | kFeatureTangents
};

struct GpuMaterial {
  gl::Buffer block;  // MaterialBlock
  // Texture indices into GpuScene::textures, -1 = none; in the order of the
  // kUnit*Texture units.
  int baseColor = -1, metallicRoughness = -1, normal = -1, occlusion = -1, emissive = -1;
  std::uint32_t textureFeatures = 0;
  bool doubleSided = false;
};

struct GpuTexture {
  gl::Texture texture;
  gl::Sampler sampler;
};

struct GpuInstance {
  int primitive = 0;      // index into GpuScene::primitives
  int material = 0;       // index into GpuScene::materials
  bool mirrored = false;  // negative determinant: clockwise triangles face front (glTF)
};

struct GpuScene {
  std::vector<GpuPrimitive> primitives;
  std::vector<GpuInstance> instances;  // same order as Scene::instances and instanceBlocks
  std::vector<GpuMaterial> materials;  // the scene's, then glTF's default material last
  std::vector<GpuTexture> textures;
  gl::Buffer instanceBlocks;       // one ObjectBlock per instance, at instanceStride apart
  std::size_t instanceStride = 0;  // bytes, a multiple of GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT
  Bounds bounds;
  bool hasEmissive = false;
};

GpuScene uploadScene(const Scene& scene);

}  // namespace headlight

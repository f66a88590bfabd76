#include "scene/gpu_scene.hpp"

#include <algorithm>
#include <cstring>
#include <map>
#include <span>
#include <tuple>

#include "shared_layout.h"

namespace headlight {
namespace {

template <class T>
gl::Buffer makeBuffer(const std::vector<T>& items) {
  return gl::Buffer::create(std::span<const T>(items));
}

// Attribute locations are shared_layout.h's kAttribute*.
void addAttribute(GpuPrimitive& gpu, GLuint location, GLint components, std::size_t stride, gl::Buffer buffer) {
  const GLuint vao = gpu.vertexArray.id();
  glVertexArrayVertexBuffer(vao, location, buffer.id(), 0, GLsizei(stride));
  glVertexArrayAttribFormat(vao, location, components, GL_FLOAT, GL_FALSE, 0);
  glVertexArrayAttribBinding(vao, location, location);
  glEnableVertexArrayAttrib(vao, location);
  gpu.buffers.push_back(std::move(buffer));
}

GpuPrimitive uploadPrimitive(const Primitive& primitive) {
  GpuPrimitive gpu;
  gpu.vertexArray = gl::VertexArray::create();
  addAttribute(gpu, gpu::kAttributePosition, 3, sizeof(glm::vec3), makeBuffer(primitive.positions));
  addAttribute(gpu, gpu::kAttributeNormal, 3, sizeof(glm::vec3), makeBuffer(primitive.normals));
  if (!primitive.texcoords.empty()) {
    addAttribute(gpu, gpu::kAttributeTexcoord, 2, sizeof(glm::vec2), makeBuffer(primitive.texcoords));
    gpu.vertexFeatures |= kFeatureTexcoords;
  }
  if (!primitive.tangents.empty()) {
    addAttribute(gpu, gpu::kAttributeTangent, 4, sizeof(glm::vec4), makeBuffer(primitive.tangents));
    gpu.vertexFeatures |= kFeatureTangents;
  }
  if (!primitive.colors.empty()) {
    addAttribute(gpu, gpu::kAttributeColor, 4, sizeof(glm::vec4), makeBuffer(primitive.colors));
    gpu.vertexFeatures |= kFeatureVertexColors;
  }
  if (!primitive.texcoords1.empty()) {
    addAttribute(gpu, gpu::kAttributeTexcoord1, 2, sizeof(glm::vec2), makeBuffer(primitive.texcoords1));
    gpu.vertexFeatures |= kFeatureTexcoords1;
  }
  gl::Buffer indices = makeBuffer(primitive.indices);
  glVertexArrayElementBuffer(gpu.vertexArray.id(), indices.id());
  gpu.buffers.push_back(std::move(indices));
  gpu.indexCount = GLsizei(primitive.indices.size());
  gpu.mode = primitive.mode == PrimitiveMode::Lines    ? GL_LINES
             : primitive.mode == PrimitiveMode::Points ? GL_POINTS
                                                       : GL_TRIANGLES;
  return gpu;
}

bool isMipmapFilter(int filter) {
  return filter == GL_NEAREST_MIPMAP_NEAREST || filter == GL_LINEAR_MIPMAP_NEAREST ||
         filter == GL_NEAREST_MIPMAP_LINEAR || filter == GL_LINEAR_MIPMAP_LINEAR;
}

int mipLevels(int width, int height) {
  int levels = 1;
  for (int size = std::max(width, height); size > 1; size /= 2) ++levels;
  return levels;
}

// Textures are made per (image, colour space, sampler) on first use: a
// glTF image may be both an sRGB base colour and a linear occlusion map.
class TextureCache {
 public:
  TextureCache(const Scene& scene, GpuScene& gpu) : scene_(scene), gpu_(gpu) {}

  int get(const TextureRef& ref, bool srgb) {
    if (!ref.present()) return -1;
    const auto key = std::make_tuple(ref.image, srgb, ref.wrapS, ref.wrapT, ref.minFilter, ref.magFilter);
    if (auto found = cache_.find(key); found != cache_.end()) return found->second;
    gpu_.textures.push_back(upload(ref, srgb));
    return cache_[key] = int(gpu_.textures.size()) - 1;
  }

 private:
  GpuTexture upload(const TextureRef& ref, bool srgb) {
    const ImageData& image = scene_.images[std::size_t(ref.image)];
    const int levels = isMipmapFilter(ref.minFilter) ? mipLevels(image.width, image.height) : 1;
    GpuTexture gpu{gl::Texture::create2D(srgb ? GL_SRGB8_ALPHA8 : GL_RGBA8, image.width, image.height, levels),
                   gl::Sampler::create()};
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    // Rows go up top first, so glTF's top-left UV origin needs no flip.
    glTextureSubImage2D(gpu.texture.id(), 0, 0, 0, image.width, image.height, GL_RGBA, GL_UNSIGNED_BYTE,
                        image.rgba.data());
    if (levels > 1) glGenerateTextureMipmap(gpu.texture.id());
    gpu.sampler.set(GL_TEXTURE_WRAP_S, ref.wrapS);
    gpu.sampler.set(GL_TEXTURE_WRAP_T, ref.wrapT);
    gpu.sampler.set(GL_TEXTURE_MIN_FILTER, ref.minFilter);
    gpu.sampler.set(GL_TEXTURE_MAG_FILTER, ref.magFilter);
    return gpu;
  }

  const Scene& scene_;
  GpuScene& gpu_;
  std::map<std::tuple<int, bool, int, int, int, int>, int> cache_;
};

GpuMaterial uploadMaterial(const Material& material, TextureCache& textures) {
  GpuMaterial gpu;
  gpu::MaterialBlock block{};
  block.baseColorFactor = material.baseColorFactor;
  block.emissiveFactor = glm::vec4(material.emissiveFactor, 0.0f);
  block.factors =
      glm::vec4(material.metallicFactor, material.roughnessFactor, material.normalScale, material.occlusionStrength);
  block.alphaCutoff = material.alphaCutoff;
  gpu.doubleSided = material.doubleSided;
  gpu.blended = material.blended();
  if (material.masked()) gpu.alphaFeatures |= kFeatureAlphaMask;
  if (material.unlit) gpu.shadingFeatures |= kFeatureUnlit;
  struct Slot {
    const TextureRef& ref;
    bool srgb;
    int& index;
    GBufferFeature feature;
    GBufferFeature texcoord1;
    glm::vec4& transformU;
    glm::vec4& transformV;
  };
  const Slot slots[] = {
      {material.baseColorTexture, true, gpu.baseColor, kFeatureBaseColorTexture, kFeatureBaseColorTexcoord1,
       block.baseColorTransformU, block.baseColorTransformV},
      {material.metallicRoughnessTexture, false, gpu.metallicRoughness, kFeatureMetallicRoughnessTexture,
       kFeatureMetallicRoughnessTexcoord1, block.metallicRoughnessTransformU, block.metallicRoughnessTransformV},
      {material.normalTexture, false, gpu.normal, kFeatureNormalTexture, kFeatureNormalTexcoord1,
       block.normalTransformU, block.normalTransformV},
      {material.occlusionTexture, false, gpu.occlusion, kFeatureOcclusionTexture, kFeatureOcclusionTexcoord1,
       block.occlusionTransformU, block.occlusionTransformV},
      {material.emissiveTexture, true, gpu.emissive, kFeatureEmissiveTexture, kFeatureEmissiveTexcoord1,
       block.emissiveTransformU, block.emissiveTransformV},
  };
  for (const Slot& slot : slots) {
    slot.transformU = glm::vec4(slot.ref.transform.rowU(), 0.0f);
    slot.transformV = glm::vec4(slot.ref.transform.rowV(), 0.0f);
    slot.index = textures.get(slot.ref, slot.srgb);
    if (slot.index < 0) continue;
    gpu.textureFeatures |= slot.feature;
    if (slot.ref.texCoord == 1) gpu.textureFeatures |= slot.texcoord1;
    // Only a material that transforms some texture pays for the matrix.
    if (!slot.ref.transform.identity()) gpu.textureFeatures |= kFeatureTextureTransform;
  }
  gpu.block = gl::Buffer::create(sizeof(block), &block);
  return gpu;
}

// Every instance's transforms, in Scene::instances order. At least one
// entry: a zero-sized buffer cannot be bound.
gl::Buffer uploadObjects(const Scene& scene) {
  std::vector<gpu::GpuObject> objects(std::max<std::size_t>(1, scene.instances.size()));
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    objects[i].worldFromLocal = scene.instances[i].worldFromLocal;
    objects[i].normalFromLocal = glm::mat4(normalMatrix(objects[i].worldFromLocal));
  }
  return makeBuffer(objects);
}

// Sorts the instances into draw order and groups them: one instanced draw
// per (primitive, material, winding), one run per primitive, for the
// instances that are not blended; the blended ones follow, one draw each
// (GpuScene::blendDraws). Returns the draw order (instance indices).
std::vector<std::uint32_t> groupInstances(const Scene& scene, int defaultMaterial, GpuScene& gpu) {
  struct Key {
    int primitive, material;
    bool mirrored;
    auto operator<=>(const Key&) const = default;
  };
  std::vector<Key> keys;
  keys.reserve(scene.instances.size());
  for (const Instance& instance : scene.instances)
    keys.push_back({instance.primitive, instance.material >= 0 ? instance.material : defaultMaterial,
                    mirrors(instance.worldFromLocal)});
  auto blended = [&](std::uint32_t instance) { return gpu.materials[std::size_t(keys[instance].material)].blended; };
  std::vector<std::uint32_t> order;
  order.reserve(scene.instances.size());
  for (std::size_t i = 0; i < scene.instances.size(); ++i)
    if (!blended(std::uint32_t(i))) order.push_back(std::uint32_t(i));
  // Stable: instances of one group keep the file's order (depth ties resolve as before).
  std::stable_sort(order.begin(), order.end(), [&](std::uint32_t a, std::uint32_t b) { return keys[a] < keys[b]; });
  for (std::size_t position = 0; position < order.size(); ++position) {
    const Key& key = keys[order[position]];
    // Points and lines are in no run: the shadow pass draws runs only.
    const bool casts = gpu.primitives[std::size_t(key.primitive)].mode == GL_TRIANGLES;
    if (casts && (gpu.primitiveRuns.empty() || gpu.primitiveRuns.back().primitive != key.primitive))
      gpu.primitiveRuns.push_back({key.primitive, GLuint(position), 0, gpu.drawGroups.size(), 0, false});
    if (casts) ++gpu.primitiveRuns.back().instanceCount;
    if (gpu.drawGroups.empty() || Key{gpu.drawGroups.back().primitive, gpu.drawGroups.back().material,
                                      gpu.drawGroups.back().mirrored} != key) {
      gpu.drawGroups.push_back({key.primitive, key.material, key.mirrored, GLuint(position), 0});
      if (casts) {
        GpuPrimitiveRun& run = gpu.primitiveRuns.back();
        ++run.groupCount;
        run.masked = run.masked || gpu.materials[std::size_t(key.material)].alphaFeatures != 0;
      }
    }
    ++gpu.drawGroups.back().instanceCount;
  }
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    if (!blended(std::uint32_t(i))) continue;
    const Instance& instance = scene.instances[i];
    const Bounds world =
        scene.primitives[std::size_t(instance.primitive)].bounds.transformed(instance.worldFromLocal);
    gpu.blendDraws.push_back({keys[i].primitive, keys[i].material, keys[i].mirrored, GLuint(order.size()),
                              world.empty() ? glm::vec3(instance.worldFromLocal[3]) : world.center()});
    order.push_back(std::uint32_t(i));
  }
  return order;
}

// Each primitive's vertex array reads its instance's index into the
// objects buffer from the draw order, once per instance.
void attachDrawOrder(GpuScene& gpu) {
  const GLuint location = GLuint(gpu::kAttributeObjectIndex);
  for (GpuPrimitive& primitive : gpu.primitives) {
    const GLuint vao = primitive.vertexArray.id();
    glVertexArrayVertexBuffer(vao, location, gpu.drawOrder.id(), 0, sizeof(std::uint32_t));
    glVertexArrayAttribIFormat(vao, location, 1, GL_UNSIGNED_INT, 0);
    glVertexArrayAttribBinding(vao, location, location);
    glVertexArrayBindingDivisor(vao, location, 1);
    glEnableVertexArrayAttrib(vao, location);
  }
}

}  // namespace

std::vector<std::string> featureDefines(std::uint32_t features) {
  static const std::pair<std::uint32_t, const char*> names[] = {
      {kFeatureTexcoords, "HAS_TEXCOORDS"},
      {kFeatureTangents, "HAS_TANGENTS"},
      {kFeatureBaseColorTexture, "HAS_BASE_COLOR_TEXTURE"},
      {kFeatureMetallicRoughnessTexture, "HAS_METALLIC_ROUGHNESS_TEXTURE"},
      {kFeatureNormalTexture, "HAS_NORMAL_TEXTURE"},
      {kFeatureOcclusionTexture, "HAS_OCCLUSION_TEXTURE"},
      {kFeatureEmissiveTexture, "HAS_EMISSIVE_TEXTURE"},
      {kFeatureAlphaMask, "ALPHA_MASK"},
      {kFeatureVertexColors, "HAS_VERTEX_COLORS"},
      {kFeatureTexcoords1, "HAS_TEXCOORDS_1"},
      {kFeatureTextureTransform, "HAS_TEXTURE_TRANSFORM"},
      {kFeatureUnlit, "UNLIT"},
      {kFeatureBaseColorTexcoord1, "BASE_COLOR_TEXCOORD_1"},
      {kFeatureMetallicRoughnessTexcoord1, "METALLIC_ROUGHNESS_TEXCOORD_1"},
      {kFeatureNormalTexcoord1, "NORMAL_TEXCOORD_1"},
      {kFeatureOcclusionTexcoord1, "OCCLUSION_TEXCOORD_1"},
      {kFeatureEmissiveTexcoord1, "EMISSIVE_TEXCOORD_1"},
  };
  std::vector<std::string> defines;
  for (const auto& [bit, name] : names)
    if (features & bit) defines.emplace_back(name);
  return defines;
}

std::uint32_t drawFeatures(const GpuPrimitive& primitive, const GpuMaterial& material) {
  std::uint32_t features = primitive.vertexFeatures | material.alphaFeatures | material.shadingFeatures;
  if (features & kFeatureTexcoords) features |= material.textureFeatures;
  return features;
}

GpuScene uploadScene(const Scene& scene) {
  GpuScene gpu;
  for (const Primitive& primitive : scene.primitives) gpu.primitives.push_back(uploadPrimitive(primitive));
  TextureCache textures(scene, gpu);
  for (const Material& material : scene.materials) gpu.materials.push_back(uploadMaterial(material, textures));
  gpu.materials.push_back(uploadMaterial(Material{}, textures));  // glTF's default material
  const int defaultMaterial = int(gpu.materials.size()) - 1;
  std::vector<std::uint32_t> drawOrder = groupInstances(scene, defaultMaterial, gpu);
  if (drawOrder.empty()) drawOrder.push_back(0);  // a buffer to bind; nothing is drawn
  gpu.drawOrder = makeBuffer(drawOrder);
  gpu.objects = uploadObjects(scene);
  attachDrawOrder(gpu);
  gpu.bounds = scene.worldBounds();
  gpu.hasEmissive = scene.hasEmissive();
  return gpu;
}

}  // namespace headlight

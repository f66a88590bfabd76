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

// Attribute locations match gbuffer.vert's.
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
  addAttribute(gpu, 0, 3, sizeof(glm::vec3), makeBuffer(primitive.positions));
  addAttribute(gpu, 1, 3, sizeof(glm::vec3), makeBuffer(primitive.normals));
  if (!primitive.texcoords.empty()) {
    addAttribute(gpu, 2, 2, sizeof(glm::vec2), makeBuffer(primitive.texcoords));
    gpu.vertexFeatures |= kFeatureTexcoords;
  }
  if (!primitive.tangents.empty()) {
    addAttribute(gpu, 3, 4, sizeof(glm::vec4), makeBuffer(primitive.tangents));
    gpu.vertexFeatures |= kFeatureTangents;
  }
  gl::Buffer indices = makeBuffer(primitive.indices);
  glVertexArrayElementBuffer(gpu.vertexArray.id(), indices.id());
  gpu.buffers.push_back(std::move(indices));
  gpu.indexCount = GLsizei(primitive.indices.size());
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
  gpu.block = gl::Buffer::create(sizeof(block), &block);
  gpu.doubleSided = material.doubleSided;
  struct Slot {
    const TextureRef& ref;
    bool srgb;
    int& index;
    GBufferFeature feature;
  };
  const Slot slots[] = {
      {material.baseColorTexture, true, gpu.baseColor, kFeatureBaseColorTexture},
      {material.metallicRoughnessTexture, false, gpu.metallicRoughness, kFeatureMetallicRoughnessTexture},
      {material.normalTexture, false, gpu.normal, kFeatureNormalTexture},
      {material.occlusionTexture, false, gpu.occlusion, kFeatureOcclusionTexture},
      {material.emissiveTexture, true, gpu.emissive, kFeatureEmissiveTexture},
  };
  for (const Slot& slot : slots) {
    slot.index = textures.get(slot.ref, slot.srgb);
    if (slot.index >= 0) gpu.textureFeatures |= slot.feature;
  }
  return gpu;
}

gl::Buffer uploadInstances(const Scene& scene, std::size_t& stride) {
  GLint alignment = 256;
  glGetIntegerv(GL_UNIFORM_BUFFER_OFFSET_ALIGNMENT, &alignment);
  stride = (sizeof(gpu::ObjectBlock) + std::size_t(alignment) - 1) / std::size_t(alignment) * std::size_t(alignment);
  std::vector<std::uint8_t> bytes(std::max<std::size_t>(1, scene.instances.size()) * stride);
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    gpu::ObjectBlock block{};
    block.worldFromLocal = scene.instances[i].worldFromLocal;
    block.normalFromLocal = glm::mat4(normalMatrix(block.worldFromLocal));
    std::memcpy(bytes.data() + i * stride, &block, sizeof(block));
  }
  return gl::Buffer::create(bytes.size(), bytes.data());
}

}  // namespace

GpuScene uploadScene(const Scene& scene) {
  GpuScene gpu;
  for (const Primitive& primitive : scene.primitives) gpu.primitives.push_back(uploadPrimitive(primitive));
  TextureCache textures(scene, gpu);
  for (const Material& material : scene.materials) gpu.materials.push_back(uploadMaterial(material, textures));
  gpu.materials.push_back(uploadMaterial(Material{}, textures));  // glTF's default material
  const int defaultMaterial = int(gpu.materials.size()) - 1;
  for (const Instance& instance : scene.instances) {
    gpu.instances.push_back({instance.primitive, instance.material >= 0 ? instance.material : defaultMaterial,
                             mirrors(instance.worldFromLocal)});
  }
  gpu.instanceBlocks = uploadInstances(scene, gpu.instanceStride);
  gpu.bounds = scene.worldBounds();
  gpu.hasEmissive = scene.hasEmissive();
  return gpu;
}

}  // namespace headlight

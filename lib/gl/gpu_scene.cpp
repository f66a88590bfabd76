#include "gl/gpu_scene.hpp"

#include <algorithm>
#include <cstring>
#include <map>
#include <span>
#include <tuple>

#include "scene/ids.hpp"
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
    const int levels = isMipmapFilter(ref.minFilter) ? gl::fullMipChainLevels(image.width, image.height) : 1;
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

// The KHR_materials_* factors, or each extension's "no effect" defaults.
void fillExtensionFactors(const Material& material, gpu::MaterialBlock& block) {
  const MaterialSpecular specular = material.specular.value_or(MaterialSpecular{});
  block.specularFactors = glm::vec4(specular.specularColorFactor, specular.specularFactor);
  const MaterialClearcoat clearcoat = material.clearcoat.value_or(MaterialClearcoat{});
  block.clearcoatFactors =
      glm::vec4(clearcoat.clearcoatFactor, clearcoat.clearcoatRoughnessFactor, clearcoat.clearcoatNormalScale, 0.0f);
  const MaterialSheen sheen = material.sheen.value_or(MaterialSheen{});
  block.sheenFactors = glm::vec4(sheen.sheenColorFactor, sheen.sheenRoughnessFactor);
  const MaterialIridescence iridescence = material.iridescence.value_or(MaterialIridescence{});
  block.iridescenceFactors =
      glm::vec4(iridescence.iridescenceFactor, iridescence.iridescenceIor, iridescence.iridescenceThicknessMinimum,
                iridescence.iridescenceThicknessMaximum);
  const MaterialAnisotropy anisotropy = material.anisotropy.value_or(MaterialAnisotropy{});
  block.anisotropyFactors = glm::vec4(anisotropy.anisotropyStrength, std::cos(anisotropy.anisotropyRotation),
                                      std::sin(anisotropy.anisotropyRotation), 0.0f);
  const MaterialTransmission transmission = material.transmission.value_or(MaterialTransmission{});
  const MaterialVolume volume = material.volume.value_or(MaterialVolume{});
  // 0 stands for an infinite attenuation distance (no attenuation): GLSL
  // has no infinity literal.
  const float distance = std::isinf(volume.attenuationDistance) ? 0.0f : volume.attenuationDistance;
  block.transmissionFactors =
      glm::vec4(transmission.transmissionFactor, volume.thicknessFactor, material.ior, distance);
  block.attenuationColor = glm::vec4(volume.attenuationColor, 0.0f);
}

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
  gpu.transmissive = material.transmissive();
  if (material.masked()) gpu.alphaFeatures |= kFeatureAlphaMask;
  if (material.unlit) gpu.shadingFeatures |= kFeatureUnlit;
  if (material.roughnessFromGlossiness && material.metallicRoughnessTexture.present())
    gpu.shadingFeatures |= kFeatureRoughnessFromGlossiness;
  for (const MaterialTextureRow& row : materialTextureRows()) {
    const TextureRef* ref = row.ref(material);
    const TextureRef none;
    const TextureRef& used = ref ? *ref : none;
    block.*row.transformU = glm::vec4(used.transform.rowU(), 0.0f);
    block.*row.transformV = glm::vec4(used.transform.rowV(), 0.0f);
    int& index = gpu.textures[std::size_t(row.id)];
    index = textures.get(used, row.srgb);
    if (index < 0) continue;
    gpu.textureFeatures |= row.feature;
    if (used.texCoord == 1) gpu.textureFeatures |= row.texcoord1;
    // Only a material that transforms some texture pays for the matrix.
    if (!used.transform.identity()) gpu.textureFeatures |= kFeatureTextureTransform;
  }
  fillExtensionFactors(material, block);
  gpu.block = gl::Buffer::create(sizeof(block), &block);
  return gpu;
}

// Every instance's transforms and ids, in Scene::instances order. At least
// one entry: a zero-sized buffer cannot be bound.
gl::Buffer uploadObjects(const Scene& scene) {
  std::vector<gpu::GpuObject> objects(std::max<std::size_t>(1, scene.instances.size()));
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    objects[i].worldFromLocal = scene.instances[i].worldFromLocal;
    objects[i].normalFromLocal = glm::mat4(normalMatrix(objects[i].worldFromLocal));
    objects[i].ids = instanceIds(scene, scene.instances[i]);
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
      gpu.primitiveRuns.push_back({key.primitive, GLuint(position), 0, gpu.drawGroups.size(), 0, false, false});
    if (casts) ++gpu.primitiveRuns.back().instanceCount;
    if (gpu.drawGroups.empty() ||
        Key{gpu.drawGroups.back().primitive, gpu.drawGroups.back().material, gpu.drawGroups.back().mirrored} != key) {
      gpu.drawGroups.push_back({key.primitive, key.material, key.mirrored, GLuint(position), 0});
      if (casts) {
        GpuPrimitiveRun& run = gpu.primitiveRuns.back();
        ++run.groupCount;
        run.masked = run.masked || gpu.materials[std::size_t(key.material)].alphaFeatures != 0;
        run.transmissive = run.transmissive || gpu.materials[std::size_t(key.material)].transmissive;
      }
    }
    ++gpu.drawGroups.back().instanceCount;
  }
  for (std::size_t i = 0; i < scene.instances.size(); ++i) {
    if (!blended(std::uint32_t(i))) continue;
    const Instance& instance = scene.instances[i];
    const Bounds world = scene.primitives[std::size_t(instance.primitive)].bounds.transformed(instance.worldFromLocal);
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

std::vector<std::string> featureDefines(FeatureBits features) {
  static const std::pair<FeatureBits, const char*> names[] = {
      {kFeatureTexcoords, "HAS_TEXCOORDS"},
      {kFeatureTangents, "HAS_TANGENTS"},
      {kFeatureAlphaMask, "ALPHA_MASK"},
      {kFeatureVertexColors, "HAS_VERTEX_COLORS"},
      {kFeatureTexcoords1, "HAS_TEXCOORDS_1"},
      {kFeatureTextureTransform, "HAS_TEXTURE_TRANSFORM"},
      {kFeatureUnlit, "UNLIT"},
      {kFeatureRoughnessFromGlossiness, "ROUGHNESS_FROM_GLOSSINESS"},
  };
  std::vector<std::string> defines;
  for (const auto& [bit, name] : names)
    if (features & bit) defines.emplace_back(name);
  for (const MaterialTextureRow& row : materialTextureRows()) {
    if (features & row.feature) defines.push_back("HAS_" + std::string(row.define) + "_TEXTURE");
    if (features & row.texcoord1) defines.push_back(std::string(row.define) + "_TEXCOORD_1");
  }
  return defines;
}

void bindMaterialTextures(const GpuScene& scene, const GpuMaterial& material, FeatureBits features) {
  if (!(features & kFeatureTexcoords)) return;
  for (const MaterialTextureRow& row : materialTextureRows()) {
    const int texture = material.textures[std::size_t(row.id)];
    if (texture < 0) continue;
    scene.textures[std::size_t(texture)].texture.bind(row.unit);
    scene.textures[std::size_t(texture)].sampler.bind(row.unit);
  }
}

FeatureBits drawFeatures(const GpuPrimitive& primitive, const GpuMaterial& material) {
  FeatureBits features = primitive.vertexFeatures | material.alphaFeatures | material.shadingFeatures;
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

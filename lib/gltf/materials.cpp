#include "gltf/materials.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include "gltf/material_extensions.hpp"
#include "image_io/texture_decode.hpp"

namespace headlight::gltf {

namespace {

// Largest texture side accepted: GL 4.5 guarantees only 16384, and a larger
// claim in a file header is far more likely corruption than a real texture.
constexpr int kMaxImageSide = 16384;

bool validWrap(int wrap) { return wrap == 33071 || wrap == 33648 || wrap == 10497; }

bool validFilter(int filter) { return filter == 9728 || filter == 9729 || (filter >= 9984 && filter <= 9987); }

void readSampler(const Source& source, int samplerIndex, TextureRef& ref) {
  const tinygltf::Sampler& sampler = source.model.samplers[static_cast<std::size_t>(samplerIndex)];
  const std::string samplerName = "sampler " + std::to_string(samplerIndex);
  if (!validWrap(sampler.wrapS) || !validWrap(sampler.wrapT)) {
    source.fail(samplerName + " has wrap modes " + std::to_string(sampler.wrapS) + "/" + std::to_string(sampler.wrapT) +
                ", expected 33071, 33648 or 10497");
  }
  ref.wrapS = sampler.wrapS;
  ref.wrapT = sampler.wrapT;
  // -1 = not given: keep TextureRef's defaults (trilinear, as viewers do).
  if (sampler.minFilter != -1) {
    if (!validFilter(sampler.minFilter)) {
      source.fail(samplerName + " has minFilter " + std::to_string(sampler.minFilter) +
                  ", expected 9728, 9729 or 9984..9987");
    }
    ref.minFilter = sampler.minFilter;
  }
  if (sampler.magFilter != -1) {
    if (sampler.magFilter != 9728 && sampler.magFilter != 9729) {
      source.fail(samplerName + " has magFilter " + std::to_string(sampler.magFilter) + ", expected 9728 or 9729");
    }
    ref.magFilter = sampler.magFilter;
  }
}

// A number of KHR_texture_transform that must be finite as a float: 1e39
// is a valid JSON number but overflows the GPU's float.
float transformNumber(const Source& source, const tinygltf::Value& value, const std::string& what) {
  if (!value.IsNumber() && !value.IsInt()) {
    source.fail(what + " is not a number");
  }
  const double number = value.GetNumberAsDouble();
  if (!std::isfinite(static_cast<float>(number))) {
    std::ostringstream text;
    text << what << " is " << number << ", expected a finite number";
    source.fail(text.str());
  }
  return static_cast<float>(number);
}

glm::vec2 transformPair(const Source& source, const tinygltf::Value& holder, const char* key, glm::vec2 fallback,
                        const std::string& user) {
  if (!holder.Has(key)) return fallback;
  const tinygltf::Value& pair = holder.Get(key);
  const std::string what = user + " KHR_texture_transform " + key;
  if (!pair.IsArray() || pair.ArrayLen() != 2) {
    source.fail(what + " is not an array of 2 numbers");
  }
  return {transformNumber(source, pair.Get(0), what + "[0]"), transformNumber(source, pair.Get(1), what + "[1]")};
}

// KHR_texture_transform (`extension` may be null): offset, rotation, scale,
// and the texCoord it overrides.
void readTransform(const Source& source, const tinygltf::Value* extension, const std::string& user, TextureRef& ref) {
  if (extension == nullptr) return;
  if (!extension->IsObject()) {
    source.fail(user + " KHR_texture_transform is not an object");
  }
  ref.transform.offset = transformPair(source, *extension, "offset", glm::vec2(0.0f), user);
  ref.transform.scale = transformPair(source, *extension, "scale", glm::vec2(1.0f), user);
  if (extension->Has("rotation")) {
    ref.transform.rotation =
        transformNumber(source, extension->Get("rotation"), user + " KHR_texture_transform rotation");
  }
  if (extension->Has("texCoord")) {
    const tinygltf::Value& texCoord = extension->Get("texCoord");
    if (!texCoord.IsInt() || texCoord.GetNumberAsInt() < 0) {
      source.fail(user + " KHR_texture_transform texCoord is not an integer >= 0");
    }
    ref.texCoord = texCoord.GetNumberAsInt();
  }
}

const tinygltf::Value* transformExtension(const tinygltf::ExtensionMap& extensions) {
  const auto found = extensions.find("KHR_texture_transform");
  return found == extensions.end() ? nullptr : &found->second;
}

}  // namespace

TextureRef readTextureRef(const Source& source, int textureIndex, int texCoord, const tinygltf::Value* transform,
                          const std::string& user) {
  TextureRef ref;
  if (textureIndex < 0) {
    return ref;
  }
  const tinygltf::Model& model = source.model;
  source.checkIndex(textureIndex, model.textures, user, "texture");
  // A texCoord of kTexcoordSets or more is sampled from TEXCOORD_0
  // (gltf_features names it).
  if (texCoord < 0) {
    source.fail(user + " has texCoord " + std::to_string(texCoord) + ", expected >= 0");
  }
  ref.texCoord = texCoord;
  readTransform(source, transform, user + " (texture " + std::to_string(textureIndex) + ")", ref);
  const tinygltf::Texture& texture = model.textures[static_cast<std::size_t>(textureIndex)];
  const std::string textureName = "texture " + std::to_string(textureIndex);
  if (texture.source < 0) {
    source.fail(textureName +
                " has no source image (extension-only images such as KHR_texture_basisu are not supported)");
  }
  source.checkIndex(texture.source, model.images, textureName, "image");
  ref.image = texture.source;
  if (texture.sampler >= 0) {
    source.checkIndex(texture.sampler, model.samplers, textureName, "sampler");
    readSampler(source, texture.sampler, ref);
  }
  return ref;
}

namespace {

float emissiveStrength(const Source& source, const tinygltf::Material& material, const std::string& materialName) {
  const auto extension = material.extensions.find("KHR_materials_emissive_strength");
  if (extension == material.extensions.end() || !extension->second.Has("emissiveStrength")) {
    return 1.0f;
  }
  const double strength = extension->second.Get("emissiveStrength").GetNumberAsDouble();
  if (!(strength >= 0.0) || !std::isfinite(strength)) {
    source.fail(materialName + " has emissiveStrength " + std::to_string(strength) + ", expected >= 0");
  }
  return static_cast<float>(strength);
}

void readFactors(const Source& source, const tinygltf::Material& material, const std::string& name, Material& out) {
  const auto& pbr = material.pbrMetallicRoughness;
  if (pbr.baseColorFactor.size() != 4) {
    source.fail(name + " has " + std::to_string(pbr.baseColorFactor.size()) + " baseColorFactor values, expected 4");
  }
  out.baseColorFactor =
      glm::vec4(pbr.baseColorFactor[0], pbr.baseColorFactor[1], pbr.baseColorFactor[2], pbr.baseColorFactor[3]);
  out.metallicFactor = static_cast<float>(pbr.metallicFactor);
  out.roughnessFactor = static_cast<float>(pbr.roughnessFactor);
  if (!material.emissiveFactor.empty() && material.emissiveFactor.size() != 3) {
    source.fail(name + " has " + std::to_string(material.emissiveFactor.size()) + " emissiveFactor values, expected 3");
  }
  if (material.emissiveFactor.size() == 3) {
    out.emissiveFactor = glm::vec3(material.emissiveFactor[0], material.emissiveFactor[1], material.emissiveFactor[2]) *
                         emissiveStrength(source, material, name);
  }
  out.normalScale = static_cast<float>(material.normalTexture.scale);
  out.occlusionStrength = static_cast<float>(material.occlusionTexture.strength);
  out.doubleSided = material.doubleSided;
  const std::array<float, 9> factors{out.baseColorFactor.r,
                                     out.baseColorFactor.g,
                                     out.baseColorFactor.b,
                                     out.baseColorFactor.a,
                                     out.metallicFactor,
                                     out.roughnessFactor,
                                     out.emissiveFactor.r + out.emissiveFactor.g + out.emissiveFactor.b,
                                     out.normalScale,
                                     out.occlusionStrength};
  if (!std::all_of(factors.begin(), factors.end(), [](float f) { return std::isfinite(f); })) {
    source.fail(name + " has a non-finite factor");
  }
}

// glTF 2.0 3.9.4: alphaMode is one of three names; alphaCutoff (MASK) is >= 0.
// Above 1 nothing could pass, so it is refused as the corrupt value it is.
void readAlpha(const Source& source, const tinygltf::Material& material, const std::string& name, Material& out) {
  static const std::pair<const char*, AlphaMode> modes[] = {
      {"OPAQUE", AlphaMode::Opaque}, {"MASK", AlphaMode::Mask}, {"BLEND", AlphaMode::Blend}};
  const auto mode = std::find_if(std::begin(modes), std::end(modes),
                                 [&](const auto& row) { return material.alphaMode == row.first; });
  if (mode == std::end(modes)) {
    source.fail(name + " has alphaMode '" + material.alphaMode + "', expected OPAQUE, MASK or BLEND");
  }
  out.alphaMode = mode->second;
  const double cutoff = material.alphaCutoff;
  if (!std::isfinite(cutoff) || cutoff < 0.0 || cutoff > 1.0) {
    source.fail(name + " has alphaCutoff " + std::to_string(cutoff) + ", expected a number in 0..1");
  }
  out.alphaCutoff = static_cast<float>(cutoff);
}

}  // namespace

Material readMaterial(const Source& source, int materialIndex) {
  const tinygltf::Material& material = source.model.materials[static_cast<std::size_t>(materialIndex)];
  const std::string name = "material " + std::to_string(materialIndex);
  Material out;
  out.name = material.name.empty() ? name : material.name;
  readFactors(source, material, name, out);
  readAlpha(source, material, name, out);
  const auto& pbr = material.pbrMetallicRoughness;
  const auto reference = [&](const auto& info, const char* slot) {
    return readTextureRef(source, info.index, info.texCoord, transformExtension(info.extensions), name + " " + slot);
  };
  out.baseColorTexture = reference(pbr.baseColorTexture, "baseColorTexture");
  out.metallicRoughnessTexture = reference(pbr.metallicRoughnessTexture, "metallicRoughnessTexture");
  out.normalTexture = reference(material.normalTexture, "normalTexture");
  out.occlusionTexture = reference(material.occlusionTexture, "occlusionTexture");
  out.emissiveTexture = reference(material.emissiveTexture, "emissiveTexture");
  // KHR_materials_unlit: its object has no properties; being there is the flag.
  out.unlit = material.extensions.count("KHR_materials_unlit") != 0;
  readMaterialExtensions(source, material, name, out);
  return out;
}

std::vector<ImageData> readImages(tinygltf::Model& model, const std::string& file, const std::string& warnings,
                                  const ResourceLimits& limits) {
  const Source source{file, model};
  std::vector<ImageData> images;
  // The images together within max-memory (estimateSceneBytes then adds the geometry).
  detail::TextureDecodeLimits decodeLimits{kMaxImageSide, limits.maxTexels, maxMemoryBytes(limits)};
  for (std::size_t index = 0; index < model.images.size(); ++index) {
    tinygltf::Image& encodedImage = model.images[index];
    // An external image tinygltf could not find is only a warning to it.
    if (encodedImage.image.empty() || encodedImage.width != -1) {
      source.fail("image " + std::to_string(index) +
                  (encodedImage.uri.empty() ? "" : " (uri '" + encodedImage.uri + "')") + " could not be loaded" +
                  (warnings.empty() ? "" : ": " + warnings));
    }
    const std::vector<unsigned char> encoded = std::move(encodedImage.image);
    bool overBudget = false;
    detail::DecodedTexture decoded;
    const std::string problem =
        detail::decodeTexture(encoded.data(), encoded.size(), decodeLimits, decoded, overBudget);
    if (!problem.empty()) {
      const std::string message = "image " + std::to_string(index) +
                                  (encodedImage.name.empty() ? "" : " '" + encodedImage.name + "'") + ": " + problem;
      overBudget ? source.failLimit(message, decodeLimits.refusedBy) : source.fail(message);
    }
    ImageData image;
    image.name = !encodedImage.name.empty() ? encodedImage.name : encodedImage.uri;
    image.width = decoded.width;
    image.height = decoded.height;
    image.rgba = std::move(decoded.rgba);
    images.push_back(std::move(image));
  }
  return images;
}

}  // namespace headlight::gltf

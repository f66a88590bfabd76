#include "gltf/texture_sources.hpp"

#include <set>

namespace headlight::gltf {

namespace {

// A 1x1 PNG: what a KTX2 image no texture draws is read as, so that the
// image indices stay and nothing tries to decode KTX2.
constexpr unsigned char kOnePixelPng[] = {
    0x89, 0x50, 0x4e, 0x47, 0x0d, 0x0a, 0x1a, 0x0a, 0x00, 0x00, 0x00, 0x0d, 0x49, 0x48, 0x44, 0x52, 0x00, 0x00,
    0x00, 0x01, 0x00, 0x00, 0x00, 0x01, 0x08, 0x06, 0x00, 0x00, 0x00, 0x1f, 0x15, 0xc4, 0x89, 0x00, 0x00, 0x00,
    0x0d, 0x49, 0x44, 0x41, 0x54, 0x78, 0xda, 0x63, 0x64, 0x60, 0xf8, 0x5f, 0x0f, 0x00, 0x02, 0x87, 0x01, 0x80,
    0xeb, 0x47, 0xba, 0x92, 0x00, 0x00, 0x00, 0x00, 0x49, 0x45, 0x4e, 0x44, 0xae, 0x42, 0x60, 0x82};

// The extension's `source` image, checked; -1 when the texture lacks the extension.
int extensionSource(const Source& source, const tinygltf::Texture& texture, const char* extension,
                    const std::string& textureName) {
  const auto found = texture.extensions.find(extension);
  if (found == texture.extensions.end()) return -1;
  const tinygltf::Value& object = found->second;
  const std::string user = textureName + " " + extension;
  if (!object.IsObject() || !object.Has("source") || !object.Get("source").IsNumber() ||
      object.Get("source").GetNumberAsDouble() != double(object.Get("source").GetNumberAsInt())) {
    source.fail(user + " has no integer source image");
  }
  const int image = object.Get("source").GetNumberAsInt();
  source.checkIndex(image, source.model.images, user, "image");
  return image;
}

}  // namespace

void resolveTextureSources(tinygltf::Model& model, const Source& source) {
  std::set<int> basisuImages;
  for (std::size_t index = 0; index < model.textures.size(); ++index) {
    tinygltf::Texture& texture = model.textures[index];
    const std::string name =
        "texture " + std::to_string(index) + (texture.name.empty() ? "" : " '" + texture.name + "'");
    if (const int webp = extensionSource(source, texture, kTextureWebp, name); webp >= 0) {
      texture.source = webp;
    }
    const int basisu = extensionSource(source, texture, kTextureBasisu, name);
    if (basisu >= 0 && texture.source < 0) {
      source.fail(name + " has only a " + kTextureBasisu + " image (image " + std::to_string(basisu) +
                  ", KTX2 Basis Universal), which is not decoded: no Debian package decodes Basis Universal; "
                  "give the texture a PNG or JPEG source as a fallback");
    }
    if (basisu >= 0) basisuImages.insert(basisu);
  }
  for (const tinygltf::Texture& texture : model.textures) basisuImages.erase(texture.source);
  for (const int image : basisuImages) {
    model.images[std::size_t(image)].image.assign(std::begin(kOnePixelPng), std::end(kOnePixelPng));
    model.images[std::size_t(image)].width = -1;  // "not decoded yet", as the file sandbox leaves images
  }
}

}  // namespace headlight::gltf

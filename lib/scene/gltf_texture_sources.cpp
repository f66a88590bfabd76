#include "scene/gltf_texture_sources.hpp"

namespace headlight::gltf {

namespace {

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
  for (std::size_t index = 0; index < model.textures.size(); ++index) {
    tinygltf::Texture& texture = model.textures[index];
    const std::string name = "texture " + std::to_string(index) + (texture.name.empty() ? "" : " '" + texture.name + "'");
    if (const int webp = extensionSource(source, texture, kTextureWebp, name); webp >= 0) {
      texture.source = webp;
    }
    if (extensionSource(source, texture, kTextureBasisu, name) >= 0 && texture.source < 0) {
      source.fail(name + " has only a " + kTextureBasisu +
                  " (KTX2 Basis Universal) image, which is not decoded: no Debian package decodes Basis Universal; "
                  "give the texture a PNG or JPEG source as a fallback");
    }
  }
}

}  // namespace headlight::gltf

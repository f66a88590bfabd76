#pragma once
// Materials and their images: glTF's metallic-roughness material with its
// texture references, samplers and KHR_materials_emissive_strength, and the
// images the textures name, decoded last.
#include <string>
#include <vector>

#include "gltf/common.hpp"
#include "headlight/limits.hpp"
#include "headlight/scene.hpp"

namespace headlight::gltf {

// A texture reference: its texture and image checked, its sampler and
// KHR_texture_transform (`transform`, may be null) read. `user` names the
// reference ("material 2 baseColorTexture"); messages about it add the
// texture: "material 2 baseColorTexture (texture 0)". An index < 0 is no texture.
TextureRef readTextureRef(const Source& source, int textureIndex, int texCoord, const tinygltf::Value* transform,
                          const std::string& user);

// Material `materialIndex` (which must exist) with its factors and texture
// references checked. Throws SceneError.
Material readMaterial(const Source& source, int materialIndex);

// Decodes every image of `model` (kept encoded by the file sandbox), within
// `limits`; `warnings` (tinygltf's) are quoted when an image is missing.
// Moves the encoded bytes out of the model. Throws SceneError or LimitError.
std::vector<ImageData> readImages(tinygltf::Model& model, const std::string& file, const std::string& warnings,
                                  const ResourceLimits& limits);

}  // namespace headlight::gltf

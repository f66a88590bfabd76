#pragma once
// Materials and their images: glTF's metallic-roughness material with its
// texture references, samplers and KHR_materials_emissive_strength, and the
// images the textures name, decoded last.
#include <string>
#include <vector>

#include "headlight/limits.hpp"
#include "headlight/scene.hpp"
#include "scene/gltf_common.hpp"

namespace headlight::gltf {

// Material `materialIndex` (which must exist) with its factors and texture
// references checked. Throws SceneError.
Material readMaterial(const Source& source, int materialIndex);

// Decodes every image of `model` (kept encoded by the file sandbox), within
// `limits`; `warnings` (tinygltf's) are quoted when an image is missing.
// Moves the encoded bytes out of the model. Throws SceneError or LimitError.
std::vector<ImageData> readImages(tinygltf::Model& model, const std::string& file, const std::string& warnings,
                                  const ResourceLimits& limits);

}  // namespace headlight::gltf

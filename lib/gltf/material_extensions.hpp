#pragma once
// The ratified KHR_materials_* extensions a material may carry (ior,
// specular, clearcoat, sheen, iridescence, anisotropy, transmission,
// volume): read into Material with the specification's defaults, every
// factor range-checked and every texture reference checked like the core
// ones. Which of them are rendered is gltf/features.cpp's list.
#include <string>

#include "gltf/common.hpp"
#include "headlight/scene.hpp"

namespace headlight::gltf {

// Reads `material`'s extensions into `out`; `name` names the material in
// messages ("material 2"). Throws SceneError naming the extension, the
// property and the value that is out of range.
void readMaterialExtensions(const Source& source, const tinygltf::Material& material, const std::string& name,
                            Material& out);

}  // namespace headlight::gltf

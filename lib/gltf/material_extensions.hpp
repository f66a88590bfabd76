#pragma once
// The KHR_materials_* extensions a material may carry (the rows of
// material_extensions.cpp): read into Material with the specification's
// defaults, every factor range-checked and every texture reference checked
// like the core ones. Each is rendered (gltf/features.cpp).
#include <span>
#include <string>
#include <string_view>

#include "gltf/common.hpp"
#include "headlight/scene.hpp"

namespace headlight::gltf {

// Reads `material`'s extensions into `out`; `name` names the material in
// messages ("material 2"). Throws SceneError naming the extension, the
// property and the value that is out of range.
void readMaterialExtensions(const Source& source, const tinygltf::Material& material, const std::string& name,
                            Material& out);

// The names of the extensions readMaterialExtensions reads, in its order.
std::span<const std::string_view> materialExtensionNames();

}  // namespace headlight::gltf

#pragma once
// KHR_materials_variants: named sets of material choices. Without a choice
// the primitives keep their own `material` (the file's default); with one
// (SceneLoadOptions::materialVariant, --material-variant), each primitive
// whose mappings list that variant takes the mapping's material.
#include <string>
#include <vector>

#include "gltf/common.hpp"

namespace headlight::gltf {

// Checks the file's variants and every primitive's mappings (material and
// variant indices in range), applies the variant named `chosen` (empty: none)
// to the primitives' materials, and returns the variants' names in file
// order. An unknown name is a SceneError listing the variants.
std::vector<std::string> applyMaterialVariant(tinygltf::Model& model, const Source& source, const std::string& chosen);

}  // namespace headlight::gltf

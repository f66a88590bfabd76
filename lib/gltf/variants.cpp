#include "gltf/variants.hpp"

#include <algorithm>

namespace headlight::gltf {

namespace {

constexpr const char* kVariants = "KHR_materials_variants";

bool isIndex(const tinygltf::Value& value) {
  return value.IsNumber() && value.GetNumberAsDouble() >= 0 && value.GetNumberAsDouble() <= 2147483647.0 &&
         value.GetNumberAsDouble() == double(value.GetNumberAsInt());
}

std::vector<std::string> variantNames(const tinygltf::Model& model, const Source& source) {
  const auto found = model.extensions.find(kVariants);
  if (found == model.extensions.end()) return {};
  const tinygltf::Value& object = found->second;
  if (!object.IsObject() || !object.Has("variants") || !object.Get("variants").IsArray()) {
    source.fail(std::string(kVariants) + " has no variants array");
  }
  std::vector<std::string> names;
  const tinygltf::Value& variants = object.Get("variants");
  for (std::size_t index = 0; index < variants.ArrayLen(); ++index) {
    const tinygltf::Value& variant = variants.Get(int(index));
    if (!variant.IsObject() || !variant.Has("name") || !variant.Get("name").IsString()) {
      source.fail(std::string(kVariants) + " variant " + std::to_string(index) + " has no name");
    }
    names.push_back(variant.Get("name").Get<std::string>());
  }
  return names;
}

// The material primitive `primitive` takes for variant `chosen` (-1: none),
// checking all of its mappings; -2 when no mapping lists the variant.
int mappedMaterial(const tinygltf::Primitive& primitive, const Source& source, const std::string& name,
                   std::size_t variantCount, int chosen) {
  const auto found = primitive.extensions.find(kVariants);
  if (found == primitive.extensions.end()) return -2;
  const std::string user = name + " " + kVariants;
  const tinygltf::Value& object = found->second;
  if (!object.IsObject() || !object.Has("mappings") || !object.Get("mappings").IsArray()) {
    source.fail(user + " has no mappings array");
  }
  int material = -2;
  const tinygltf::Value& mappings = object.Get("mappings");
  for (std::size_t index = 0; index < mappings.ArrayLen(); ++index) {
    const tinygltf::Value& mapping = mappings.Get(int(index));
    const std::string mappingName = user + " mapping " + std::to_string(index);
    if (!mapping.IsObject() || !mapping.Has("material") || !isIndex(mapping.Get("material")) ||
        !mapping.Has("variants") || !mapping.Get("variants").IsArray()) {
      source.fail(mappingName + " expected a material index and a variants array");
    }
    const int mapped = mapping.Get("material").GetNumberAsInt();
    source.checkIndex(mapped, source.model.materials, mappingName, "material");
    const tinygltf::Value& variants = mapping.Get("variants");
    for (std::size_t k = 0; k < variants.ArrayLen(); ++k) {
      const tinygltf::Value& variant = variants.Get(int(k));
      if (!isIndex(variant) || std::size_t(variant.GetNumberAsInt()) >= variantCount) {
        source.fail(mappingName + " lists variant " +
                    (isIndex(variant) ? std::to_string(variant.GetNumberAsInt()) : std::string("(not an index)")) +
                    ", but the file has " + countOf(variantCount, "variant"));
      }
      if (variant.GetNumberAsInt() == chosen) material = mapped;
    }
  }
  return material;
}

}  // namespace

std::vector<std::string> applyMaterialVariant(tinygltf::Model& model, const Source& source, const std::string& chosen) {
  const std::vector<std::string> names = variantNames(model, source);
  int chosenIndex = -1;
  if (!chosen.empty()) {
    const auto found = std::find(names.begin(), names.end(), chosen);
    if (found == names.end()) {
      source.fail("material variant " + quotedName(chosen) + " is not in the file: " +
                      (names.empty() ? std::string("it has no KHR_materials_variants")
                                     : "its variants are " + quotedList(names)),
                  {"material-variant"});
    }
    chosenIndex = int(found - names.begin());
  }
  for (std::size_t mesh = 0; mesh < model.meshes.size(); ++mesh) {
    for (std::size_t primitive = 0; primitive < model.meshes[mesh].primitives.size(); ++primitive) {
      tinygltf::Primitive& target = model.meshes[mesh].primitives[primitive];
      const int material =
          mappedMaterial(target, source, "mesh " + std::to_string(mesh) + " primitive " + std::to_string(primitive),
                         names.size(), chosenIndex);
      if (material >= 0) target.material = material;
    }
  }
  return names;
}

}  // namespace headlight::gltf

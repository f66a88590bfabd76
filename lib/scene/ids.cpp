#include "scene/ids.hpp"

#include <algorithm>

namespace headlight {

glm::uvec4 instanceIds(const Scene& scene, const Instance& instance) {
  // The default material (-1) is the entry after the scene's own.
  const std::size_t material = instance.material >= 0 ? std::size_t(instance.material) : scene.materials.size();
  return {unsigned(instance.meshInstance + 1), unsigned(instance.mesh + 1), unsigned(material + 1),
          unsigned(instance.meshPrimitive + 1)};
}

std::size_t largestId(const Scene& scene) {
  return std::max({scene.meshInstanceNames.size(), scene.meshNames.size(), scene.materials.size() + 1,
                   scene.meshPrimitiveNames.size()});
}

IdNames makeIdNames(const Scene& scene) {
  IdNames names{scene.meshInstanceNames, scene.meshNames, {}, scene.meshPrimitiveNames};
  for (std::size_t index = 0; index < scene.materials.size(); ++index)
    names.materials.push_back({scene.materials[index].name, int(index), -1});
  names.materials.push_back({"glTF default material", -1, -1});
  return names;
}

}  // namespace headlight

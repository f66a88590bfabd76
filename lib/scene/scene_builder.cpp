#include "headlight/scene_builder.hpp"

#include <glm/gtc/matrix_transform.hpp>
#include <utility>

namespace headlight {

Material makeMaterial(const glm::vec3& baseColor, float roughness, float metallic, std::string name) {
  Material material;
  material.name = std::move(name);
  material.baseColorFactor = glm::vec4(baseColor, 1.0f);
  material.roughnessFactor = roughness;
  material.metallicFactor = metallic;
  return material;
}

Camera makeLookAtCamera(const glm::vec3& eye, const glm::vec3& target, float yfov, std::string name) {
  Camera camera;
  camera.name = std::move(name);
  camera.yfov = yfov;
  camera.worldFromCamera = glm::inverse(glm::lookAt(eye, target, glm::vec3(0.0f, 1.0f, 0.0f)));
  return camera;
}

Camera makeOrthographicCamera(const glm::vec3& eye, const glm::vec3& target, float halfHeight, std::string name) {
  Camera camera = makeLookAtCamera(eye, target, Camera{}.yfov, std::move(name));
  camera.projection = Camera::Projection::Orthographic;
  camera.ymag = halfHeight;
  camera.xmag = halfHeight;
  return camera;
}

glm::mat4 moved(const glm::vec3& offset) { return glm::translate(glm::mat4(1.0f), offset); }

glm::mat4 rotatedAboutYThenMoved(float degrees, const glm::vec3& center) {
  return glm::rotate(glm::translate(glm::mat4(1.0f), center), glm::radians(degrees), glm::vec3(0.0f, 1.0f, 0.0f));
}

int addMaterial(Scene& scene, Material material) {
  scene.materials.push_back(std::move(material));
  return static_cast<int>(scene.materials.size()) - 1;
}

int addGeometry(Scene& scene, Primitive primitive) {
  scene.primitives.push_back(std::move(primitive));
  return static_cast<int>(scene.primitives.size()) - 1;
}

void addInstance(Scene& scene, int geometry, int material, const glm::mat4& worldFromLocal, std::string name) {
  // Each placement is a mesh instance of its own; a geometry is a mesh of one primitive.
  const int meshInstance = int(scene.meshInstanceNames.size());
  scene.meshInstanceNames.push_back({std::move(name), -1, -1});
  for (std::size_t mesh = scene.meshNames.size(); mesh < scene.primitives.size(); ++mesh) {
    scene.meshNames.push_back({"geometry " + std::to_string(mesh), -1, -1});
    scene.meshPrimitiveNames.push_back({"geometry " + std::to_string(mesh), -1, -1});
  }
  scene.instances.push_back({geometry, worldFromLocal, material, meshInstance, geometry, geometry});
}

void addInstance(Scene& scene, Primitive primitive, int material, const glm::mat4& worldFromLocal, std::string name) {
  addInstance(scene, addGeometry(scene, std::move(primitive)), material, worldFromLocal, std::move(name));
}

}  // namespace headlight

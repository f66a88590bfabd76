#include "gltf/nodes.hpp"

#include <cmath>
#include <cstdio>
#include <glm/gtc/quaternion.hpp>
#include <glm/gtc/type_ptr.hpp>

#include "headlight/limits.hpp"

namespace headlight::gltf {

NodeWalk::NodeWalk(const Source& source) : source_(source) {
  const auto& nodes = source_.model.nodes;
  parentOf_.assign(nodes.size(), -1);
  for (std::size_t parent = 0; parent < nodes.size(); ++parent) {
    const std::string parentName = "node " + std::to_string(parent);
    for (int child : nodes[parent].children) {
      source_.checkIndex(child, nodes, parentName, "node");
      int& recordedParent = parentOf_[static_cast<std::size_t>(child)];
      if (recordedParent != -1) {
        source_.fail("node " + std::to_string(child) + " is a child of both node " + std::to_string(recordedParent) +
                     " and node " + std::to_string(parent) + ", but glTF nodes must form trees");
      }
      recordedParent = static_cast<int>(parent);
    }
  }
  // With one parent each, a cycle is a parent chain that comes back to
  // itself; found here, before a scene can list a node of it as a root.
  std::vector<char> state(nodes.size(), 0);  // 0 unseen, 1 on this walk, 2 done
  std::vector<int> walk;
  for (std::size_t start = 0; start < nodes.size(); ++start) {
    walk.clear();
    int node = static_cast<int>(start);
    while (node != -1 && state[static_cast<std::size_t>(node)] == 0) {
      state[static_cast<std::size_t>(node)] = 1;
      walk.push_back(node);
      node = parentOf_[static_cast<std::size_t>(node)];
    }
    if (node != -1 && state[static_cast<std::size_t>(node)] == 1) {
      source_.fail("node " + std::to_string(parentOf_[static_cast<std::size_t>(node)]) + " has child node " +
                   std::to_string(node) + ", which is also its ancestor: the node graph has a cycle");
    }
    for (int visited : walk) {
      state[static_cast<std::size_t>(visited)] = 2;
    }
  }
}

std::vector<int> NodeWalk::rootNodes(int sceneIndex) const {
  const tinygltf::Model& model = source_.model;
  if (model.scenes.empty()) {
    std::vector<int> roots;  // no scene: every node without a parent
    for (std::size_t node = 0; node < model.nodes.size(); ++node) {
      if (parentOf_[node] == -1) {
        roots.push_back(static_cast<int>(node));
      }
    }
    return roots;
  }
  const bool chosen = sceneIndex >= 0;
  if (!chosen) {
    sceneIndex = model.defaultScene == -1 ? 0 : model.defaultScene;
  }
  source_.checkIndex(sceneIndex, model.scenes, chosen ? "scene" : "the default scene", "scene");
  const std::string sceneName = "scene " + std::to_string(sceneIndex);
  std::vector<char> listed(model.nodes.size(), 0);
  for (int node : model.scenes[static_cast<std::size_t>(sceneIndex)].nodes) {
    source_.checkIndex(node, model.nodes, sceneName, "node");
    // glTF: a scene lists root nodes, each once; repeats would multiply
    // the node's whole subtree.
    if (listed[static_cast<std::size_t>(node)]++) {
      source_.fail(sceneName + " lists node " + std::to_string(node) +
                   " more than once, but scene nodes must be unique");
    }
    if (parentOf_[static_cast<std::size_t>(node)] != -1) {
      source_.fail(sceneName + " lists node " + std::to_string(node) + " as a root, but it is a child of node " +
                   std::to_string(parentOf_[static_cast<std::size_t>(node)]) + "; scene nodes must be roots");
    }
  }
  return model.scenes[static_cast<std::size_t>(sceneIndex)].nodes;
}

glm::dmat4 NodeWalk::localTransform(int nodeIndex) const {
  const tinygltf::Node& node = source_.model.nodes[static_cast<std::size_t>(nodeIndex)];
  const std::string name = "node " + std::to_string(nodeIndex);
  glm::dmat4 local(1.0);
  if (!node.matrix.empty()) {
    if (node.matrix.size() != 16) {
      source_.fail(name + " has " + std::to_string(node.matrix.size()) + " matrix values, expected 16");
    }
    local = glm::make_mat4(node.matrix.data());  // glTF matrices are column-major, as GLM's
  } else {
    if ((!node.translation.empty() && node.translation.size() != 3) ||
        (!node.rotation.empty() && node.rotation.size() != 4) || (!node.scale.empty() && node.scale.size() != 3)) {
      source_.fail(name + " has translation/rotation/scale of " + std::to_string(node.translation.size()) + "/" +
                   std::to_string(node.rotation.size()) + "/" + std::to_string(node.scale.size()) +
                   " values, expected 3/4/3");
    }
    const glm::dvec3 translation = node.translation.empty() ? glm::dvec3(0.0) : glm::make_vec3(node.translation.data());
    const glm::dvec3 scale = node.scale.empty() ? glm::dvec3(1.0) : glm::make_vec3(node.scale.data());
    // glTF stores quaternions as x, y, z, w; GLM's constructor takes w first.
    glm::dquat rotation(1.0, 0.0, 0.0, 0.0);
    if (!node.rotation.empty()) {
      rotation = glm::dquat(node.rotation[3], node.rotation[0], node.rotation[1], node.rotation[2]);
      const double length = glm::length(rotation);
      if (!(length > 0.0)) {
        source_.fail(name + " has a zero rotation quaternion");
      }
      rotation /= length;
    }
    local =
        glm::translate(glm::dmat4(1.0), translation) * glm::mat4_cast(rotation) * glm::scale(glm::dmat4(1.0), scale);
  }
  for (int column = 0; column < 4; ++column) {
    for (int row = 0; row < 4; ++row) {
      if (!std::isfinite(local[column][row])) {
        source_.fail(name + " has a non-finite transform");
      }
    }
  }
  return local;
}

glm::mat4 NodeWalk::worldTransform(int nodeIndex) const {
  // Each node's world transform is composed once and kept: a skin's joints
  // are often one long chain, and composing each joint's chain anew cost
  // joints^2 / 2 products (a 20,000-joint chain took 12.5 s; issue 32).
  if (worldKnown_.empty()) {
    worldKnown_.assign(parentOf_.size(), false);
    world_.resize(parentOf_.size());
  }
  std::vector<int> chain;  // nodeIndex and its ancestors whose world is not yet known, nearest first
  for (int node = nodeIndex; node != -1 && !worldKnown_[std::size_t(node)]; node = parentOf(node))
    chain.push_back(node);
  for (auto node = chain.rbegin(); node != chain.rend(); ++node) {
    const int parent = parentOf(*node);
    world_[std::size_t(*node)] =
        parent == -1 ? localTransform(*node) : world_[std::size_t(parent)] * localTransform(*node);
    worldKnown_[std::size_t(*node)] = true;
  }
  return checkedWorld(nodeIndex, world_[std::size_t(nodeIndex)]);
}

// World transforms must stay where float rendering stays finite
// (kMaxWorldMagnitude): a translation of 1e39 or nested scales of 1e20 x
// 1e20 are finite doubles but inf or NaN as floats.
glm::mat4 NodeWalk::checkedWorld(int nodeIndex, const glm::dmat4& world) const {
  for (int column = 0; column < 4; ++column) {
    for (int row = 0; row < 4; ++row) {
      const double value = world[column][row];
      if (!(std::abs(value) <= kMaxWorldMagnitude)) {
        char text[32];
        std::snprintf(text, sizeof text, "%g", value);
        source_.fail("node " + std::to_string(nodeIndex) + " has a world transform entry of " + text +
                     " (its own and its ancestors' transforms together), expected magnitude at most " +
                     std::to_string(static_cast<long long>(kMaxWorldMagnitude)) +
                     " so that float rendering stays finite");
      }
    }
  }
  return glm::mat4(world);
}

void NodeWalk::traverse(int root, const std::function<void(int, const glm::mat4&)>& visit) const {
  struct Frame {
    int node;
    glm::dmat4 worldFromNode;
    std::size_t nextChild;
  };
  const auto& nodes = source_.model.nodes;
  std::vector<char> onPath(nodes.size(), 0);
  std::vector<Frame> stack{{root, localTransform(root), 0}};
  onPath[static_cast<std::size_t>(root)] = 1;
  visit(root, checkedWorld(root, stack.back().worldFromNode));
  while (!stack.empty()) {
    Frame& top = stack.back();
    const std::vector<int>& children = nodes[static_cast<std::size_t>(top.node)].children;
    if (top.nextChild == children.size()) {
      onPath[static_cast<std::size_t>(top.node)] = 0;
      stack.pop_back();
      continue;
    }
    const int child = children[top.nextChild++];
    if (onPath[static_cast<std::size_t>(child)]) {
      source_.fail("node " + std::to_string(top.node) + " has child node " + std::to_string(child) +
                   ", which is also its ancestor: the node graph has a cycle");
    }
    const glm::dmat4 worldFromChild = top.worldFromNode * localTransform(child);
    onPath[static_cast<std::size_t>(child)] = 1;
    stack.push_back({child, worldFromChild, 0});  // invalidates `top`
    visit(child, checkedWorld(child, worldFromChild));
  }
}

// ---- Lights

namespace {

tinygltf::Light lightFromJson(const tinygltf::Value& json) {
  tinygltf::Light light;
  auto number = [](const tinygltf::Value& object, const char* key, double fallback) {
    return object.Has(key) ? object.Get(key).GetNumberAsDouble() : fallback;
  };
  light.name = json.Has("name") ? json.Get("name").Get<std::string>() : "";
  light.type = json.Has("type") ? json.Get("type").Get<std::string>() : "";
  light.intensity = number(json, "intensity", 1.0);
  light.range = number(json, "range", 0.0);
  if (json.Has("color")) {
    for (std::size_t channel = 0; channel < json.Get("color").ArrayLen(); ++channel) {
      light.color.push_back(json.Get("color").Get(static_cast<int>(channel)).GetNumberAsDouble());
    }
  }
  if (json.Has("spot")) {
    light.spot.innerConeAngle = number(json.Get("spot"), "innerConeAngle", 0.0);
    light.spot.outerConeAngle = number(json.Get("spot"), "outerConeAngle", 0.7853981634);
  }
  return light;
}

Light::Type lightType(const std::string& type, bool& known) {
  known = true;
  if (type == "directional") return Light::Type::Directional;
  if (type == "point") return Light::Type::Point;
  if (type == "spot") return Light::Type::Spot;
  known = false;
  return Light::Type::Point;
}

// A camera's frame is a rotation and a position: glTF forbids scale on a
// camera's nodes but files have it, so the rotation is re-orthonormalised
// (keeping the view direction exact).
glm::mat4 rigidFrame(const glm::mat4& world) {
  const glm::vec3 back = glm::normalize(glm::vec3(world[2]));
  glm::vec3 right = glm::vec3(world[0]) - glm::dot(glm::vec3(world[0]), back) * back;
  right = glm::normalize(right);
  const glm::vec3 up = glm::cross(back, right);
  return glm::mat4(glm::vec4(right, 0.0f), glm::vec4(up, 0.0f), glm::vec4(back, 0.0f), world[3]);
}

}  // namespace

// tinygltf 2.7 parses KHR_lights_punctual into Model::lights; older and
// newer versions may leave it only in Model::extensions, read the same way.
std::vector<tinygltf::Light> punctualLights(const tinygltf::Model& model) {
  if (!model.lights.empty()) {
    return model.lights;
  }
  std::vector<tinygltf::Light> lights;
  const auto extension = model.extensions.find("KHR_lights_punctual");
  if (extension == model.extensions.end() || !extension->second.Has("lights")) {
    return lights;
  }
  const tinygltf::Value& array = extension->second.Get("lights");
  for (std::size_t index = 0; index < array.ArrayLen(); ++index) {
    lights.push_back(lightFromJson(array.Get(static_cast<int>(index))));
  }
  return lights;
}

int nodeLight(const Source& source, const tinygltf::Node& node, const std::string& nodeName,
              const std::vector<tinygltf::Light>& lights) {
  const auto extension = node.extensions.find("KHR_lights_punctual");
  if (extension == node.extensions.end() || !extension->second.Has("light")) {
    return -1;
  }
  const tinygltf::Value& light = extension->second.Get("light");
  const int lightIndex = light.IsNumber() || light.IsInt() ? light.GetNumberAsInt() : -1;
  source.checkIndex(lightIndex, lights, nodeName + " KHR_lights_punctual", "light");
  return lightIndex;
}

Light readLight(const Source& source, const tinygltf::Light& light, int lightIndex, const glm::mat4& worldFromNode,
                const std::string& nodeName) {
  const std::string name = "light " + std::to_string(lightIndex);
  Light out;
  bool knownType = false;
  out.type = lightType(light.type, knownType);
  if (!knownType) {
    source.fail(name + " has type '" + light.type + "', expected directional, point or spot");
  }
  out.name = light.name.empty() ? name : light.name;
  if (!light.color.empty() && light.color.size() != 3) {
    source.fail(name + " has " + std::to_string(light.color.size()) + " color values, expected 3");
  }
  if (light.color.size() == 3) {
    out.color = glm::vec3(light.color[0], light.color[1], light.color[2]);
  }
  out.intensity = static_cast<float>(light.intensity);
  out.range = static_cast<float>(light.range);
  out.innerConeAngle = static_cast<float>(light.spot.innerConeAngle);
  out.outerConeAngle = static_cast<float>(light.spot.outerConeAngle);
  if (!(out.intensity >= 0.0f) || !(out.range >= 0.0f) || !std::isfinite(out.intensity)) {
    source.fail(name + " has intensity " + std::to_string(out.intensity) + " and range " + std::to_string(out.range) +
                ", expected both >= 0");
  }
  if (out.type == Light::Type::Spot &&
      !(out.innerConeAngle >= 0.0f && out.innerConeAngle < out.outerConeAngle && out.outerConeAngle <= 1.5707964f)) {
    source.fail(name + " has cone angles " + std::to_string(out.innerConeAngle) + ".." +
                std::to_string(out.outerConeAngle) + ", expected 0 <= inner < outer <= pi/2");
  }
  out.position = glm::vec3(worldFromNode[3]);
  const glm::vec3 direction = glm::mat3(worldFromNode) * glm::vec3(0.0f, 0.0f, -1.0f);
  const float length = glm::length(direction);
  if (out.type != Light::Type::Point && !(length > 0.0f && std::isfinite(length))) {
    source.fail(nodeName + " holds " + name + " but its transform has no direction (zero scale)");
  }
  if (length > 0.0f && std::isfinite(length)) {
    out.direction = direction / length;
  }
  return out;
}

// ---- Cameras

Camera readCamera(const Source& source, int cameraIndex, const glm::mat4& worldFromNode, const std::string& nodeName) {
  const tinygltf::Camera& camera = source.model.cameras[static_cast<std::size_t>(cameraIndex)];
  const std::string name = "camera " + std::to_string(cameraIndex);
  Camera out;
  out.name = !camera.name.empty() ? camera.name : name;
  if (camera.type == "perspective") {
    const auto& p = camera.perspective;
    out.projection = Camera::Projection::Perspective;
    out.yfov = static_cast<float>(p.yfov);
    out.aspectRatio = static_cast<float>(p.aspectRatio);
    out.znear = static_cast<float>(p.znear);
    out.zfar = static_cast<float>(p.zfar);
    if (!(out.yfov > 0.0f && out.yfov < 3.1415926f) || !(out.aspectRatio >= 0.0f)) {
      source.fail(name + " has yfov " + std::to_string(p.yfov) + " and aspectRatio " + std::to_string(p.aspectRatio) +
                  ", expected 0 < yfov < pi and aspectRatio >= 0");
    }
  } else if (camera.type == "orthographic") {
    const auto& o = camera.orthographic;
    out.projection = Camera::Projection::Orthographic;
    out.xmag = static_cast<float>(o.xmag);
    out.ymag = static_cast<float>(o.ymag);
    out.znear = static_cast<float>(o.znear);
    out.zfar = static_cast<float>(o.zfar);
    if (out.xmag == 0.0f || out.ymag == 0.0f || !std::isfinite(out.xmag) || !std::isfinite(out.ymag)) {
      source.fail(name + " has xmag " + std::to_string(o.xmag) + " and ymag " + std::to_string(o.ymag) +
                  ", expected nonzero");
    }
  } else {
    source.fail(name + " has type '" + camera.type + "', expected perspective or orthographic");
  }
  if (!(out.znear >= 0.0f) || !(out.zfar >= 0.0f) || (out.zfar != 0.0f && out.zfar <= out.znear)) {
    source.fail(name + " has znear " + std::to_string(out.znear) + " and zfar " + std::to_string(out.zfar) +
                ", expected 0 <= znear < zfar (or zfar absent)");
  }
  if (glm::length(glm::vec3(worldFromNode[2])) == 0.0f || glm::length(glm::vec3(worldFromNode[0])) == 0.0f) {
    source.fail(nodeName + " holds " + name + " but its transform has zero scale");
  }
  out.worldFromCamera = rigidFrame(worldFromNode);
  return out;
}

}  // namespace headlight::gltf

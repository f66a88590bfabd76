#pragma once
// The node walk: glTF's node trees flattened into world transforms, and what
// nodes carry besides meshes (cameras, KHR_lights_punctual lights).
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "gltf/common.hpp"
#include "headlight/scene.hpp"

namespace headlight::gltf {

class NodeWalk {
 public:
  // Checks that the nodes form trees (each node has at most one parent, no
  // cycles), which bounds the walk to one visit per node per root.
  explicit NodeWalk(const Source& source);

  // The roots of scene `sceneIndex` (-1: the file's `scene`, else scene 0),
  // checked to be unique roots; every parentless node when the file has no
  // scenes.
  std::vector<int> rootNodes(int sceneIndex = -1) const;

  // Calls `visit(node, worldFromNode)` for `root` and every node under it,
  // depth first with an explicit stack (a deep hierarchy cannot overflow the
  // call stack). World transforms are composed in double and checked to stay
  // where float rendering stays finite.
  void traverse(int root, const std::function<void(int node, const glm::mat4& worldFromNode)>& visit) const;

  // A node's own transform (matrix, or translation * rotation * scale),
  // checked finite.
  glm::dmat4 localTransform(int nodeIndex) const;

  // A node's world transform, composed up its parent chain (the trees are
  // checked, so the chain ends), checked as traverse() checks it.
  glm::mat4 worldTransform(int nodeIndex) const;

  int parentOf(int nodeIndex) const { return parentOf_[static_cast<std::size_t>(nodeIndex)]; }

 private:
  glm::mat4 checkedWorld(int nodeIndex, const glm::dmat4& world) const;

  const Source& source_;
  std::vector<int> parentOf_;
  // worldTransform's composed transforms, by node, once each.
  mutable std::vector<glm::dmat4> world_;
  mutable std::vector<bool> worldKnown_;
};

// KHR_lights_punctual's lights, wherever this tinygltf version put them.
std::vector<tinygltf::Light> punctualLights(const tinygltf::Model& model);

// The index of the light node `node` holds, checked against `lights`; -1 for none.
int nodeLight(const Source& source, const tinygltf::Node& node, const std::string& nodeName,
              const std::vector<tinygltf::Light>& lights);

Light readLight(const Source& source, const tinygltf::Light& light, int lightIndex, const glm::mat4& worldFromNode,
                const std::string& nodeName);

Camera readCamera(const Source& source, int cameraIndex, const glm::mat4& worldFromNode, const std::string& nodeName);

}  // namespace headlight::gltf

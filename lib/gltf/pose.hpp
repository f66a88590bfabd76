#pragma once
// The static pose, computed on the CPU at load: morph targets blended by the
// node's (else the mesh's) weights, skins posed by their joints' own node
// transforms, and EXT_mesh_gpu_instancing's per-instance transforms.
// Animations are not played (gltf_features names those whose first keyframe leaves this pose).
#include <functional>
#include <vector>

#include <glm/glm.hpp>

#include "gltf/accessors.hpp"
#include "gltf/nodes.hpp"
#include "headlight/scene.hpp"

namespace headlight::gltf {

// The morph weights a node draws its mesh with: node.weights, else
// mesh.weights, checked finite; empty when all are 0 (nothing to blend).
std::vector<float> morphWeights(const Source& source, int nodeIndex, int meshIndex);

// Adds each target's weighted POSITION, NORMAL and TANGENT deltas to
// `primitive` (positions read; normals and tangents where the file has
// them). Checks that the primitive has as many targets as there are
// weights and that each delta accessor has one element per vertex.
void applyMorphTargets(const AccessorReader& accessors, const tinygltf::Primitive& source,
                       const std::string& primitiveName, const std::vector<float>& weights, Primitive& primitive);

// The joint matrices of skin `skinIndex`: world(joint) * inverseBind(joint),
// with the joints' own node transforms (the static pose).
std::vector<glm::mat4> jointMatrices(const AccessorReader& accessors, const NodeWalk& walk, int skinIndex);

// Skins `primitive` in place (positions, normals, tangents) with every
// JOINTS_n/WEIGHTS_n set: joint indices checked < the skin's joint count,
// weights finite. The result is in world space.
void applySkin(const AccessorReader& accessors, const tinygltf::Primitive& source, const std::string& primitiveName,
               const std::vector<glm::mat4>& joints, Primitive& primitive);

// EXT_mesh_gpu_instancing: node-space transforms of the node's instances
// (translation * rotation * scale), checked finite and equal in count;
// empty when the node has none. `checkCount` sees each attribute's count
// before anything of that size is read or allocated (a limit that throws
// there costs nothing: 15 million instances of accessors without a
// bufferView, zeros by glTF's rule, took 1.15 GB before the instance limit
// was checked).
std::vector<glm::mat4> instanceTransforms(const AccessorReader& accessors, const Source& source, int nodeIndex,
                                          const std::function<void(std::size_t count)>& checkCount);

}  // namespace headlight::gltf

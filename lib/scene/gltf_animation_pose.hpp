#pragma once
// Whether an animation starts away from the static pose. Animations are not
// played: Headlight draws the pose the nodes describe. An animation whose
// first keyframe is that pose leaves a still frame right (it is the frame a
// player shows at time 0), so only one that starts elsewhere is named
// (gltf_features.cpp, findAnimations).
#include <cstddef>

#include "scene/gltf_common.hpp"

namespace headlight::gltf {

// True when some channel of animation `animationIndex` has a first keyframe
// (for CUBICSPLINE the value, not the in-tangent) that differs from its
// target's static value: the node's translation, rotation (q and -q are one
// rotation) or scale, or its weights (else the mesh's, else zeros).
//
// Also true when the animation cannot be read (no channels, an index out of
// range, an accessor out of its buffer, of the wrong type or count, a
// non-finite value, a node with a matrix, which glTF forbids animating): the
// animation is not played, so its data cannot make the picture wrong beyond
// the static pose, and refusing would turn a file that draws right into an
// error; naming it keeps the file from being silently different.
bool animationLeavesStaticPose(const tinygltf::Model& model, std::size_t animationIndex);

}  // namespace headlight::gltf

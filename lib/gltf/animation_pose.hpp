#pragma once
// An animation played at a chosen time (--animation, --time), and whether
// one that is not played starts away from the static pose. Unless one is
// chosen, Headlight draws the pose the nodes describe. An animation whose
// first keyframe is that pose leaves a still frame right (it is the frame a
// player shows at time 0), so only one that starts elsewhere is named
// (gltf/features.cpp, findAnimations).
#include <cstddef>
#include <string>

#include "gltf/common.hpp"

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

// The animation `chosen` names: an index, else a name. A SceneError names
// the file's animations when none matches.
int findAnimation(const Source& source, const std::string& chosen);

// Poses the model at `time` seconds of animation `animationIndex` (glTF 2.0
// §3.11): each channel's sampled value replaces its node's translation,
// rotation, scale or morph weights, so the static pose the loader then
// builds (world transforms, skins, morph targets) is the animated one.
// Before the first keyframe the first value holds, after the last the last;
// STEP holds a keyframe's value, LINEAR interpolates (rotations by slerp the
// short way), CUBICSPLINE is the cubic Hermite spline of the in- and
// out-tangents scaled by the keyframe interval. Only the keyframes the time
// falls between are read (a binary search over the times, one element
// each): memory does not grow with an accessor's count. A channel whose
// node has a matrix, an unknown path or interpolation, times that do not
// increase, a non-finite value or a count that disagrees is a SceneError
// naming the animation, the channel and the problem. Channels with an
// extension's target (no node) are skipped: the extension is named as not
// rendered.
void applyAnimation(tinygltf::Model& model, const Source& source, int animationIndex, double time);

}  // namespace headlight::gltf

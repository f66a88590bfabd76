#pragma once
// Never silent: which glTF features a file uses that Headlight does not
// render, and which required extensions make a file impossible to draw.
//
// One table of detectors (gltf/features.cpp, kDetectors) and one list of
// the extensions that are rendered (kRenderedExtensions): when a feature
// becomes rendered, its detector row is removed or its extension added.
#include <vector>

#include "gltf/common.hpp"
#include "headlight/scene.hpp"

namespace headlight::gltf {

// Every feature `model` uses that is not rendered, once each, in the order
// of the detector table.
// `playedAnimation`: the animation the file is posed by (--animation), not named; -1: none.
std::vector<IgnoredFeature> findIgnoredFeatures(const tinygltf::Model& model, int playedAnimation = -1);

// Throws SceneError naming every required extension that is neither
// rendered nor safe to draw without (the geometry would be wrong or absent).
void checkRequiredExtensions(const Source& source);

// True for an extension Headlight renders (KHR_lights_punctual, ...).
bool extensionRendered(const std::string& name);

}  // namespace headlight::gltf

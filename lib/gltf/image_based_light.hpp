#pragma once
// EXT_lights_image_based: the image-based light a glTF scene names, turned
// into the equirectangular EnvironmentMap that --environment would give, so
// it is prefiltered, occluded by SSGI, sampled by the reference and shown as
// the background like any map. Only the specular cube's first level is read:
// Headlight prefilters its own levels and integrates its own irradiance from
// it (the file's lower levels and spherical-harmonic coefficients describe
// the same light).
#include <memory>
#include <vector>

#include "gltf/common.hpp"
#include "headlight/scene.hpp"

namespace headlight::gltf {

// The light that scene `sceneIndex` (-1: the file's default) names, or null
// when it names none. `images` are the file's decoded images. Throws
// SceneError naming the light and what is wrong with it.
std::shared_ptr<const EnvironmentMap> readImageBasedLight(const Source& source, int sceneIndex,
                                                          const std::vector<ImageData>& images);

}  // namespace headlight::gltf

#pragma once
// Which image a texture draws: the extensions that give a texture another
// source than its core `source`. EXT_texture_webp's image is decoded
// (OpenImageIO reads WebP) and preferred; KHR_texture_basisu's KTX2 image is
// not (no Debian package decodes Basis Universal): its core `source` is
// drawn instead, and a texture without one is refused.
#include "gltf/common.hpp"

namespace headlight::gltf {

inline constexpr const char* kTextureWebp = "EXT_texture_webp";
inline constexpr const char* kTextureBasisu = "KHR_texture_basisu";

// Points each texture with EXT_texture_webp at its WebP image; refuses a
// texture whose only image is KHR_texture_basisu's, naming it. Runs before
// materials are read. Throws SceneError.
void resolveTextureSources(tinygltf::Model& model, const Source& source);

}  // namespace headlight::gltf

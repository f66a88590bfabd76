#pragma once
// GPU targets to ImageF: rows flipped from GL's bottom-up order to image
// order (top row first), and depth turned into view-space depth.
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.hpp"
#include "headlight/frame.hpp"

namespace headlight {

// Reads the first channels.size() components of a colour texture as floats.
// sRGB textures come back decoded to linear.
ImageF readColor(const gl::Texture& texture, std::vector<std::string> channels);

// Reads a target held in several textures of one size (headlight/targets.hpp:
// channels 4k..4k+3 in textures[k]) as one image with all `channels`.
ImageF readColor(std::span<const gl::Texture* const> textures, const std::vector<std::string>& channels);

// The coefficients of HL_VIEW_Z_FROM_DEPTH (glsl/shared_layout.h) for the
// view's projection and planes: the inverse of glm::perspective's or
// glm::ortho's depth mapping. FrameBlock::depthToViewZ holds them for the
// shaders; readViewDepth uses the same.
glm::dvec4 viewZCoefficients(const CameraView& view);

// Reads a depth texture and converts window depth to the distance along the
// view direction (view-space -z), using view's projection and planes.
ImageF readViewDepth(const gl::Texture& depth, const CameraView& view, std::string channel);

}  // namespace headlight

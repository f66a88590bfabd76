#pragma once
// GPU targets to ImageF: rows flipped from GL's bottom-up order to image
// order (top row first), and depth turned into view-space depth.
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "gl/objects.hpp"
#include "headlight/frame.hpp"

namespace headlight {

// How a texture's pixels come back. Through a pixel buffer the GPU copies
// them in command order (after what drew them, before what draws into the
// texture next) and the CPU waits for the copy alone when it reads them: the
// frame's GPU work and the copy overlap the CPU's next steps. Direct, they
// are read into client memory at once. A software rasteriser copies on the
// CPU at the call either way, and the pixel buffer only adds a copy there
// (docs/BENCHMARKS.md, "Readback and pipelined frames").
enum class ReadPath { PixelBuffer, Direct };

// A texture's level 0 on its way back as floats.
class PixelRead {
 public:
  // Starts reading `texture` as `format` (GL_RGBA or GL_DEPTH_COMPONENT),
  // `components` floats a pixel.
  PixelRead(const gl::Texture& texture, GLenum format, int components, ReadPath path);
  // The pixels, rows bottom-up as GL has them; once.
  std::vector<float> take();
  int width() const { return width_; }
  int height() const { return height_; }
  GLenum internalFormat() const { return internalFormat_; }

 private:
  gl::Buffer buffer_;          // ReadPath::PixelBuffer
  std::vector<float> pixels_;  // ReadPath::Direct
  int width_ = 0, height_ = 0;
  GLenum internalFormat_ = 0;
};

// An image being read back: a target held in several textures of one size
// (headlight/targets.hpp: channels 4k..4k+3 in textures[k]), or a depth
// texture as view depth. Started when its frame's passes are queued,
// finished when the frame is collected (Renderer::submit, collect).
class PendingImage {
 public:
  static PendingImage color(std::span<const gl::Texture* const> textures, std::vector<std::string> channels,
                            ReadPath path = ReadPath::Direct);
  // Window depth turned into the distance along the view direction (view-space -z).
  static PendingImage viewDepth(const gl::Texture& depth, const CameraView& view, std::string channel,
                                ReadPath path = ReadPath::Direct);
  ImageF finish();  // once

 private:
  std::vector<PixelRead> parts_;
  std::vector<std::string> channels_;
  std::optional<CameraView> depthView_;  // a depth read: the view it converts with
};

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

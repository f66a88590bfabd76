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

// Pixel buffers kept from one frame's readback for the next. A buffer of
// read-back storage is pinned client memory the driver maps into the GPU's
// view: making and freeing one per target per frame cost more than the copy
// (on an H200 under gVisor a 1920x1080 frame's readback took ~480 ms, most of
// it fresh pages; docs/BENCHMARKS.md, "Session 14"). A renderer keeps one
// frame's worth: Renderer::submit holds at most two frames in flight, and each
// collect hands its buffers back for the frame after next.
class ReadbackBuffers {
 public:
  // A kept buffer of exactly `bytes`, else a new one.
  gl::Buffer acquire(std::size_t bytes);
  void release(gl::Buffer buffer);
  // Keeps no more than the bytes released since the last trim (the frame just
  // collected), dropping the oldest: a change of size or targets frees the rest.
  void trim();
  std::size_t keptBytes() const;

 private:
  std::vector<gl::Buffer> kept_;  // oldest first
  std::size_t releasedSinceTrim_ = 0;
};

// How a texture's components travel: in the type it stores them in (a
// half-float texture as halves, an 8-bit one as bytes), converted to float on
// the CPU while the image is assembled. Asked for as floats, a driver converts
// them itself: on an H200 queueing a 1080x1080 frame's copies took ~48 ms
// of the CPU's time, and the copies carried 2-4x the bytes.
// Integer textures come back as their integers (Uint32).
enum class ComponentType { Float, Half, Unorm8, Uint32 };
ComponentType transferType(GLenum internalFormat);

// A texture's level 0 on its way back.
class PixelRead {
 public:
  // Starts reading `texture` as `format` (GL_RGBA or GL_DEPTH_COMPONENT),
  // `components` a pixel; through a pixel buffer from `buffers` when given.
  PixelRead(const gl::Texture& texture, GLenum format, int components, ReadPath path,
            ReadbackBuffers* buffers = nullptr);
  PixelRead(PixelRead&&) noexcept;
  PixelRead& operator=(PixelRead&&) noexcept;
  ~PixelRead();
  // The stored components, rows bottom-up as GL has them: the pixel buffer
  // mapped (the wait for its copy), valid until release().
  const void* data();
  // Unmaps and hands the pixel buffer back to `buffers` (dropped without).
  void release(ReadbackBuffers* buffers);
  int width() const { return width_; }
  int height() const { return height_; }
  GLenum internalFormat() const { return internalFormat_; }
  ComponentType type() const { return type_; }

 private:
  gl::Buffer buffer_;  // ReadPath::PixelBuffer
  const void* mapped_ = nullptr;
  std::vector<unsigned char> bytes_;  // ReadPath::Direct
  int width_ = 0, height_ = 0;
  GLenum internalFormat_ = 0;
  ComponentType type_ = ComponentType::Float;
};

// An image being read back: a target held in several textures of one size
// (headlight/targets.hpp: channels 4k..4k+3 in textures[k]), or a depth
// texture as view depth. Started when its frame's passes are queued,
// finished when the frame is collected (Renderer::submit, collect). Pixel
// buffers come from and go back to `buffers` where one is given.
class PendingImage {
 public:
  static PendingImage color(std::span<const gl::Texture* const> textures, std::vector<std::string> channels,
                            ReadPath path = ReadPath::Direct, ReadbackBuffers* buffers = nullptr);
  // Window depth turned into the distance along the view direction (view-space -z).
  static PendingImage viewDepth(const gl::Texture& depth, const CameraView& view, std::string channel,
                                ReadPath path = ReadPath::Direct, ReadbackBuffers* buffers = nullptr);
  // The image, each texture's pixels visited once: rows flipped, channels
  // interleaved, sRGB decoded, depth converted in one pass into the image's
  // own storage. Once.
  ImageF finish();

 private:
  std::vector<PixelRead> parts_;
  std::vector<std::string> channels_;
  std::optional<CameraView> depthView_;  // a depth read: the view it converts with
  ReadbackBuffers* buffers_ = nullptr;
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

#pragma once
// The GL internal format of each frame target's GPU texture, from the
// frame-target table (headlight/targets.hpp): the G-buffer pass and the
// renderer allocate what the table says, so readback and docs agree.
#include <glad/gl.h>

#include "headlight/error.hpp"
#include "headlight/targets.hpp"

namespace headlight::gl {

inline GLenum internalFormat(GpuFormat format) {
  switch (format) {
    case GpuFormat::Rgba32F:
      return GL_RGBA32F;
    case GpuFormat::Rgba16F:
      return GL_RGBA16F;
    case GpuFormat::Srgb8Alpha8:
      return GL_SRGB8_ALPHA8;
    case GpuFormat::Rgba8:
      return GL_RGBA8;
    case GpuFormat::Depth32F:
      return GL_DEPTH_COMPONENT32F;
  }
  return GL_NONE;
}

// The format the table gives the target Frame keeps in `image`.
inline GLenum targetFormat(ImageF Frame::*image) {
  for (const FrameTarget& target : frameTargets())
    if (target.image == image) return internalFormat(target.gpuFormat);
  throw GlError("no frame-target row for this Frame member");
}

}  // namespace headlight::gl

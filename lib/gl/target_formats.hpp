#pragma once
// The GL internal format of each GpuFormat: the frame plan's attachment
// table (frame/frame_plan.cpp, kAttachmentRows) says which format each
// attachment has, without GL; this maps it for allocation.
#include <glad/gl.h>

#include "gl/gpu_format.hpp"

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
    case GpuFormat::Rgba32Ui:
      return GL_RGBA32UI;
  }
  return GL_NONE;
}

}  // namespace headlight::gl

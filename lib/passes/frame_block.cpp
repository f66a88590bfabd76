#include "passes/frame_block.hpp"

#include "gl/readback.hpp"

namespace headlight {

gpu::FrameBlock makeFrameBlock(const CameraView& view, int width, int height) {
  gpu::FrameBlock block{};
  block.view = view.view;
  block.projection = view.projection;
  block.viewProjection = view.projection * view.view;
  block.cameraPosition = glm::vec4(view.position, view.orthographic ? 1.0f : 0.0f);
  block.viewport = glm::vec4(float(width), float(height), 1.0f / float(width), 1.0f / float(height));
  block.depthToViewZ = glm::vec4(viewZCoefficients(view));
  return block;
}

}  // namespace headlight

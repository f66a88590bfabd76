#pragma once
// The frame block (glsl/shared_layout.h, binding kBindingFrame) for a view:
// what every pass that reads the G-buffer or draws the scene takes its
// matrices, viewport and depth linearisation from. The renderer fills it
// for the frame's camera, the virtual-light pass for each light's views.
#include "headlight/camera.hpp"
#include "shared_layout.h"

namespace headlight {

gpu::FrameBlock makeFrameBlock(const CameraView& view, int width, int height);

}  // namespace headlight

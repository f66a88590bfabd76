#pragma once
// Antialiasing by jittered samples (an accumulation buffer: Haeberli and
// Akeley, "The Accumulation Buffer", SIGGRAPH 1990): each sample renders the
// view through a projection shifted by a sub-pixel offset, and lit is their
// mean, a box filter over the pixel. The offsets are the first `count`
// points of the R2 sequence (Roberts, "The Unreasonable Effectiveness of
// Quasirandom Sequences", 2018), which stratify the pixel for any count
// (4: one in each quadrant, each in its own quarter of x and of y), moved
// by their mean so that they centre on the pixel (unmoved, 4 samples' mean
// lies 0.19 px off). None need be the centre: the frame drawn there keeps
// every other target (frame plan: AntialiasStep, frame/frame_plan.hpp).
#include <glm/glm.hpp>

#include "headlight/camera.hpp"

namespace headlight {

// Sample `index`'s offset from the pixel centre, in pixels, of `count`
// samples (0 <= index < count); their mean is (0, 0).
glm::vec2 antialiasOffset(int index, int count);

// `view` with its projection moved by `offsetPixels` on an image of width x
// height: every point's pixel position shifts by the offset, its depth does not.
CameraView jitteredView(const CameraView& view, glm::vec2 offsetPixels, int width, int height);

}  // namespace headlight

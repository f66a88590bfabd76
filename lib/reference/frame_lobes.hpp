#pragma once
// A frame's lobe targets at one pixel onto a Surface, as surface.glsl's
// LOBES_AT and applyLobes put the G-buffer's on the lighting passes' (the
// frame holds a lobe's target only where the scene uses the lobe; elsewhere
// the surface does not have it): for the Embree reference's pixels and the
// parity tests. The coat, a layer with its own normal, is returned (factor
// 0, changing nothing, without a clearcoat target).
#include <cstddef>
#include <glm/glm.hpp>

#include "frame/frame_plan.hpp"
#include "headlight/frame.hpp"
#include "reference/lobe_clearcoat.hpp"
#include "reference/lobes.hpp"

namespace headlight::reference {

inline Clearcoat frameLobesAt(const Frame& frame, int x, int y, Surface& surface) {
  auto at = [&](const ImageF& image) {
    return glm::vec4(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2), image.at(x, y, 3));
  };
  for (std::size_t i = 0; i < kLobeCount; ++i) {
    const Lobe lobe = Lobe(i);
    const ImageF& image = frame.*lobeTarget(lobe);
    if (lobe != Lobe::Clearcoat && !image.empty() && image.channelCount() >= 4) applyLobe(surface, lobe, at(image));
  }
  return frame.clearcoat.empty() ? Clearcoat{} : makeClearcoat(at(frame.clearcoat), surface.view);
}

}  // namespace headlight::reference

#pragma once
// A frame's lobe targets at one pixel onto a Surface, as surface.glsl's
// applyLobes puts the G-buffer's on the lighting passes' (the frame holds a
// lobe's target only where the scene uses the lobe; elsewhere the surface
// keeps its no-effect values): for the Embree reference's pixels and the
// parity tests. The coat is returned (factor 0, changing nothing, without
// a clearcoat target).
#include <glm/glm.hpp>

#include "headlight/frame.hpp"
#include "reference/lobe_clearcoat.hpp"
#include "reference/lobe_iridescence.hpp"
#include "reference/lobe_specular.hpp"
#include "reference/shading.hpp"

namespace headlight::reference {

inline Clearcoat frameLobesAt(const Frame& frame, int x, int y, Surface& surface) {
  auto at = [&](const ImageF& image) {
    return glm::vec4(image.at(x, y, 0), image.at(x, y, 1), image.at(x, y, 2), image.at(x, y, 3));
  };
  applyIridescence(surface, iridescenceInputsAt(frame, x, y));
  if (!frame.specular.empty()) applySpecularLobe(surface, at(frame.specular));
  if (!frame.sheen.empty()) {
    const glm::vec4 sheen = at(frame.sheen);
    surface.sheenColor = glm::vec3(sheen);
    surface.sheenRoughness = sheen.a;
  }
  if (!frame.anisotropy.empty()) {
    const glm::vec4 anisotropy = at(frame.anisotropy);
    surface.anisotropyTangent = glm::vec3(anisotropy);
    surface.anisotropyStrength = anisotropy.w;
  }
  return frame.clearcoat.empty() ? Clearcoat{} : makeClearcoat(at(frame.clearcoat), surface.view);
}

}  // namespace headlight::reference

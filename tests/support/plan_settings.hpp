#pragma once
// The settings the frame-plan tests plan with: resolved, every auto value
// set (as Renderer::resolve would), so planFrame can be called without a
// scene or a context.
#include "headlight/settings.hpp"

namespace headlight::test {

inline RenderSettings resolvedPlanSettings() {
  RenderSettings settings;
  settings.ssgi.radius = 0.5f;
  settings.ssgi.bias = 0.025f;
  settings.ssgi.thickness = 0.1f;
  settings.ssgi.indirectStrength = 1.0f;
  settings.lighting.shadowMapSize = 1024;
  settings.lighting.skyIntensity = 1.0f;
  return settings;
}

}  // namespace headlight::test

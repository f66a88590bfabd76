#pragma once
// The auto values of RenderSettings, resolved from the scene and the image
// size: pure (no GL), so Renderer::resolve, the frame plan and the unit tests
// share one rule for each.
#include "headlight/scene.hpp"
#include "headlight/settings.hpp"

namespace headlight {

// `settings` with every std::optional auto value set: SSGI radius, bias,
// thickness and indirect strength, shadow-map size, sky intensity. Validates
// first (SettingsError naming the setting).
RenderSettings resolveSettings(const RenderSettings& settings, const Scene& scene);

// The longer image side to the next power of two, held in 512..2048.
int autoShadowMapSize(int width, int height);

// The bitmask SSGI's auto thickness for a scene of this diagonal and radius.
float autoThickness(const Scene& scene, float diagonal, float radius);

}  // namespace headlight

#pragma once
// The auto values of RenderSettings, resolved from the scene and the image
// size: pure (no GL), so Renderer::resolve, the frame plan and the unit tests
// share one rule for each.
#include "headlight/scene.hpp"
#include "headlight/settings.hpp"

namespace headlight {

// `settings` with every std::optional auto value set: SSGI radius, bias,
// thickness and indirect strength, shadow-map size, sky intensity, radiance
// precision. Validates
// first (SettingsError naming the setting).
RenderSettings resolveSettings(const RenderSettings& settings, const Scene& scene);

// 4x the longer image side to the next power of two, held in 1024..2048.
int autoShadowMapSize(int width, int height);

// radiance-precision's auto value: float when the brightest radiance the
// scene's own light sources can put into a pixel, estimated up front
// (brightestRadianceEstimate), comes within kHalfHeadroom of half's 65504;
// half otherwise. Light beyond the estimate (a highlight sharper than it
// allows) is still counted per file when half clamps it, and the warning
// names this setting.
RadiancePrecision autoRadiancePrecision(const Scene& scene, float diagonal);
// The largest of: an emissive material's brightest channel; a directional
// light's illuminance / pi (a white diffuse surface facing it); a point or
// spot light's intensity / (pi d^2) with d = kNearLightFraction x the
// scene's diagonal (a surface that close to the light).
float brightestRadianceEstimate(const Scene& scene, float diagonal);
inline constexpr float kHalfHeadroom = 16.0f;  // specular peaks and several lights add up beyond the estimate
inline constexpr float kNearLightFraction = 0.05f;

// The bitmask SSGI's auto thickness for a scene of this diagonal and radius.
float autoThickness(const Scene& scene, float diagonal, float radius);

}  // namespace headlight

#include "frame/resolve.hpp"

#include <algorithm>
#include <bit>
#include <vector>

#include "frame/frame_plan.hpp"

namespace headlight {

// Four texels per pixel of the longer image side: the reference's shadows
// are hard, and a map as coarse as the image blurs their edges over several
// pixels with the PCF filter (HDR-FLIP of lit at 256x256, 512 -> 1024 texels:
// builtin:slats 0.059 -> 0.044, spheres 0.0493 -> 0.0485, MetalRoughSpheres
// 0.0459 -> 0.0452; docs/BENCHMARKS.md, "Shadow maps"). At most 2048: a
// point light's cube is six of them (96 MiB at 2048).
int autoShadowMapSize(int width, int height) {
  const unsigned side = unsigned(std::min(std::max(width, height), 1 << 20));
  return std::clamp(int(std::bit_ceil(4u * side)), 1024, 2048);
}

// How deep the scene's objects typically are behind what the camera sees,
// taken as 2/3 of the median over instances of the smallest side of their
// world bounds (2/3: a sphere's mean depth over its outline is 2/3 of its
// diameter). Flat instances (a side under 1e-3 of the scene's diagonal:
// walls, floors) say nothing about depth and are left out. Held within
// [kAutoThicknessFraction / 10, 1] x the radius, and
// kAutoThicknessFraction x radius when every instance is flat.
float autoThickness(const Scene& scene, float diagonal, float radius) {
  std::vector<float> depths;
  for (const Instance& instance : scene.instances) {
    const Bounds bounds = scene.primitives[std::size_t(instance.primitive)].bounds.transformed(instance.worldFromLocal);
    if (bounds.empty()) continue;
    const glm::vec3 size = bounds.max - bounds.min;
    const float smallest = std::min({size.x, size.y, size.z});
    if (smallest > 1e-3f * diagonal) depths.push_back(smallest);
  }
  if (depths.empty()) return SsgiSettings::kAutoThicknessFraction * radius;
  std::nth_element(depths.begin(), depths.begin() + std::ptrdiff_t(depths.size() / 2), depths.end());
  return std::clamp(depths[depths.size() / 2] * (2.0f / 3.0f), 0.1f * SsgiSettings::kAutoThicknessFraction * radius,
                    radius);
}

float brightestRadianceEstimate(const Scene& scene, float diagonal) {
  constexpr float kPi = 3.14159265f;
  float brightest = 0.0f;
  for (const Material& material : scene.materials)
    brightest = std::max({brightest, material.emissiveFactor.r, material.emissiveFactor.g, material.emissiveFactor.b});
  const float near = kNearLightFraction * diagonal;
  for (const Light& light : scene.lights) {
    const float power = light.intensity * std::max({light.color.r, light.color.g, light.color.b});
    brightest = std::max(brightest, light.type == Light::Type::Directional ? power / kPi : power / (kPi * near * near));
  }
  return brightest;
}

RadiancePrecision autoRadiancePrecision(const Scene& scene, float diagonal) {
  constexpr float kHalfMax = 65504.0f;
  return brightestRadianceEstimate(scene, diagonal) * kHalfHeadroom > kHalfMax ? RadiancePrecision::Float
                                                                               : RadiancePrecision::Half;
}

RenderSettings resolveSettings(const RenderSettings& settings, const Scene& scene) {
  settings.validate();
  RenderSettings used = settings;
  // An empty scene has no size; 1 keeps every derived value finite.
  const float sceneRadius = scene.worldBounds().radius();
  const float diagonal = sceneRadius > 0.0f ? 2.0f * sceneRadius : 1.0f;
  if (!used.ssgi.radius) used.ssgi.radius = std::max(used.ssgi.radiusFraction * diagonal, 1e-30f);
  if (!used.ssgi.bias) used.ssgi.bias = SsgiSettings::kAutoBiasFraction * *used.ssgi.radius;
  if (!used.ssgi.thickness) used.ssgi.thickness = autoThickness(scene, diagonal, *used.ssgi.radius);
  if (!used.lighting.shadowMapSize) used.lighting.shadowMapSize = autoShadowMapSize(used.width, used.height);
  if (!used.lighting.skyIntensity) used.lighting.skyIntensity = scene.sky.intensity;
  if (!used.radiancePrecision) used.radiancePrecision = autoRadiancePrecision(scene, diagonal);
  if (!used.ssgi.indirectStrength)
    used.ssgi.indirectStrength = ssgiMethodTraits(used.ssgi.method).defaultIndirectStrength;
  return used;
}

}  // namespace headlight

#pragma once
// The per-pixel work of traceReference: from one G-buffer pixel, the
// cosine-weighted rays (AO, sky visibility, one-bounce indirect) and the
// lit reference (direct light with shadow rays, sky ambient with true
// visibility, emission). docs/ACCURACY.md defines every quantity.
#include <embree3/rtcore.h>

#include <atomic>
#include <vector>

#include "environment/environment_sampler.hpp"
#include "headlight/reference.hpp"
#include "reference/traced_scene.hpp"

namespace headlight::reference {

// An environment map as the reference sees it: the map (looked up bilinear,
// as the renderer's background is), its importance sampler, its turn about
// +Y and whether it shows as the background. Intensity: TraceInputs::skyIntensity.
struct EnvironmentLight {
  environment::EquirectImage map;
  environment::EnvironmentSampler sampler;
  float cosRotation = 1.0f, sinRotation = 0.0f;
  bool background = true;

  glm::vec3 radiance(const glm::vec3& worldDirection) const {
    return map.lookup(environment::worldToMap(worldDirection, cosRotation, sinRotation));
  }
};

// Everything a worker reads; nothing here changes while tracing.
struct TraceInputs {
  const Scene& scene;
  const Frame& frame;
  const ReferenceSettings& settings;
  RTCScene rtcScene;
  RTCScene blendedScene;  // alphaMode BLEND instances, composited along primary rays; null when none
  const std::vector<InstanceShading>& instances;
  float epsilon;       // world units: how far ray origins leave their surface
  float skyIntensity;  // the frame's, resolved; with an environment map, its intensity
  int specularSamples;
  const EnvironmentLight* environment = nullptr;  // null: the procedural sky
  bool transmissiveScene = false;  // a material is Material::transmissive (transmission_trace.hpp)
};

// Where a worker writes: each pixel only its own entries, so workers need
// no lock.
struct Outputs {
  ReferenceImages& images;                     // ao, indirect and lit, sized as the frame
  std::vector<double>& aoStandardError;        // per pixel; NaN on background
  std::vector<double>& indirectStandardError;  // per pixel, mean of the three channels
};

// Traces every pixel of each row that `nextRow` hands out (nextRow++) until
// it reaches the frame's height. Call it on each worker thread; it sets the
// thread's float mode (denormals flushed, Embree's advice). Each pixel's
// result depends only on its own random stream, so which thread traces it
// does not matter. Throws SettingsError for a non-finite G-buffer position.
void traceRows(const TraceInputs& inputs, const Outputs& outputs, std::atomic<int>& nextRow);

}  // namespace headlight::reference

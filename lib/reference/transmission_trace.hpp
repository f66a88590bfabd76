#pragma once
// The Embree reference's view of KHR_materials_transmission and
// KHR_materials_volume (tracer.cpp uses it): which transmissive surface a
// primary ray meets, with its material's values where the ray hits it, and
// the first surface behind it that is not transmissive. The reference's
// model (docs/ACCURACY.md): one straight ray through the surface, leaving
// where the volume's refracted path (lobe_transmission.hpp's
// volumeTransmissionRay, the renderer's) leaves, along the view direction;
// transmissive surfaces behind it are passed, as the renderer's background
// holds none; no roughness blur.
#include <embree3/rtcore.h>

#include <glm/glm.hpp>
#include <vector>

#include "headlight/scene.hpp"
#include "reference/traced_scene.hpp"

namespace headlight::reference {

struct TransmissiveSurface {
  float share = 0.0f;  // transmissionFactor x texture R; 0: not a transmissive surface
  float ior = 1.5f;
  float thickness = 0.0f;      // thicknessFactor x texture G, mesh units; 0: thin-walled
  glm::vec3 modelScale{1.0f};  // the instance's scale per axis
  glm::vec3 attenuationColor{1.0f};
  float attenuationDistance = 0.0f;  // 0: infinite (as the renderer's material block)
  float blur = 0.0f;                 // transmissionRoughness of the surface's roughness (set by the tracer)
};

// What the primary ray (origin, unit direction) meets first in `rtcScene`:
// its transmission where that is a surface the transmission pass draws,
// else share 0.
TransmissiveSurface transmissiveSurfaceAt(const Scene& scene, const std::vector<InstanceShading>& instances,
                                          RTCScene rtcScene, RTCIntersectContext& context, const glm::vec3& origin,
                                          const glm::vec3& direction);

// The first hit from `origin` along unit `direction` past `tnear` whose
// surface the transmission pass does not draw (geomID
// RTC_INVALID_GEOMETRY_ID: none).
RTCRayHit firstOpaqueHit(const std::vector<InstanceShading>& instances, RTCScene rtcScene, RTCIntersectContext& context,
                         const glm::vec3& origin, const glm::vec3& direction, float tnear);

// What a shadow ray from `origin` along unit `direction` brings of `light`
// over `far` (the light's distance; infinite for directional lights): 0
// where it meets a surface the transmission pass does not draw, else what
// the transmissive surfaces it crosses let through (lobe_transmission.hpp's
// shadowLayerOpticalDepth summed, as the renderer's transmittance maps sum
// them). More than kMaxShadowLayers crossings count as blocked.
glm::vec3 shadowRayTransmittance(const Scene& scene, const std::vector<InstanceShading>& instances, RTCScene rtcScene,
                                 RTCIntersectContext& context, const Light& light, const glm::vec3& origin,
                                 const glm::vec3& direction, float far);
inline constexpr int kMaxShadowLayers = 64;

// A ray's first hit `first` (from `origin` along unit `direction`, found by
// the caller), walked on through transmissive surfaces: the first other
// surface it meets (geomID RTC_INVALID_GEOMETRY_ID: none, the sky) and
// what the crossed ones let through of the light coming back along it (the
// shadow rays' model). For the cosine rays: sky and indirect light reach a
// surface through glass as a light does.
struct PassedHit {
  RTCRayHit hit;
  glm::vec3 transmittance{1.0f};
};
PassedHit passTransmissive(const Scene& scene, const std::vector<InstanceShading>& instances, RTCScene rtcScene,
                           RTCIntersectContext& context, const glm::vec3& origin, const glm::vec3& direction,
                           const RTCRayHit& first);

}  // namespace headlight::reference

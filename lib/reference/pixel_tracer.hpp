#pragma once
// The reference tracer's per-worker class (internal to lib/reference), shared
// by its two source files: tracer.cpp defines the per-pixel path (tracePixel,
// the lobe reads, the rays it casts) and traceRows; tracer_hits.cpp what the
// rays meet (blended layers, the radiance leaving a hit, direct light and the
// ambient and environment sampling).
#include <embree3/rtcore.h>

#include <cmath>
#include <cstdint>
#include <utility>

#include "reference/lobe_clearcoat.hpp"
#include "reference/shading.hpp"
#include "reference/tracer.hpp"
#include "reference/transmission_trace.hpp"

namespace headlight::reference {

inline bool isFinite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// One worker's tracer: its own Embree intersect context over the shared
// inputs.
class Tracer {
 public:
  explicit Tracer(const TraceInputs& in)
      : in_(in),
        clipFromWorld_(in.frame.view.projection * in.frame.view.view),
        worldFromClip_(glm::inverse(clipFromWorld_)) {
    rtcInitIntersectContext(&context_);
  }
  void tracePixel(int x, int y, const Outputs& out);

 private:
  // The per-pixel path and the rays it casts (tracer.cpp).
  glm::vec3 coatAmbient(const Clearcoat& coat, const glm::vec3& view, const glm::vec3& origin, Pcg32& random);
  RTCRayHit traceFromSurface(const glm::vec3& origin, const glm::vec3& direction, const glm::vec3& toEye);
  bool unoccluded(const glm::vec3& origin, const glm::vec3& direction, float far);
  // A cosine ray's first hit `first`, walked on through transmissive
  // surfaces (passTransmissive) in a scene that has them: what sends the
  // ray its light, and how much of that comes through.
  PassedHit pastTransmissive(const glm::vec3& origin, const glm::vec3& direction, const RTCRayHit& first);
  bool shownOnScreen(const glm::vec3& point);
  TransmissiveSurface transmissiveSurfaceHere(int x, int y);
  glm::vec3 transmittedLight(const Surface& surface, const glm::vec3& position, const TransmissiveSurface& t,
                             const glm::vec3& specularAlbedo, const Clearcoat& coat, Pcg32& random);
  glm::vec3 backgroundRay(int x, int y) const;
  std::pair<glm::vec3, glm::vec3> primaryRay(int x, int y) const;

  // Blended layers and the light at what rays meet (tracer_hits.cpp).
  void compositeBlended(int x, int y, const glm::vec3* opaque, float* lit, Pcg32& random);
  // `rays`: its cosine rays (0: samplesPerPixel) and, over 4, its GGX rays.
  bool shadeBlendedHit(const RTCRayHit& rayHit, const glm::vec3& rayDirection, Pcg32& random, glm::vec3& radiance,
                       float& alpha, int rays = 0);
  glm::vec3 lightVisibility(const Light& light, const glm::vec3& origin, const glm::vec3& toLight, float distance);
  glm::vec3 directLight(const Surface& surface, const glm::vec3& position, const glm::vec3& origin,
                        const Clearcoat& coat, const TransmissiveSurface& transmissive = {});
  glm::vec3 ambientLight(const Surface& surface, const glm::vec3& origin, const Basis& basis, const glm::vec3& skyMean,
                         Pcg32& random, glm::vec3* specularAlbedoOut = nullptr, float* specularVisibilityOut = nullptr,
                         int specularRays = 0);
  glm::vec3 layersAmbient(const Surface& surface, const glm::vec3& origin, const Basis& basis, Pcg32& random);
  glm::vec3 environmentIrradianceOverPi(const Surface& surface, const glm::vec3& origin, int count, Pcg32& random);
  glm::vec3 radianceLeaving(const RTCRayHit& rayHit, const glm::vec3& rayDirection);

  // What the layers over the base (sheen) leave of its light from `direction` (1 without).
  static float layerScaleToward(const Surface& s, const glm::vec3& direction) {
    return baseLayerScale(s, glm::dot(s.normal, direction));
  }

  bool unlitPixel(int x, int y) const {
    const ImageF& material = in_.frame.material;
    return material.channelCount() > 3 && material.channels[3] == "material.unlit" && material.at(x, y, 3) > 0.5f;
  }

  static RTCRayHit makeRayHit(const glm::vec3& origin, const glm::vec3& direction, float far) {
    RTCRayHit rayHit;
    rayHit.ray.org_x = origin.x, rayHit.ray.org_y = origin.y, rayHit.ray.org_z = origin.z;
    rayHit.ray.dir_x = direction.x, rayHit.ray.dir_y = direction.y, rayHit.ray.dir_z = direction.z;
    rayHit.ray.tnear = 0.0f;
    rayHit.ray.tfar = far;
    rayHit.ray.time = 0.0f;
    rayHit.ray.mask = 0xFFFFFFFFu;
    rayHit.ray.id = 0;
    rayHit.ray.flags = 0;
    rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    return rayHit;
  }

  // surface.glsl viewDirection.
  glm::vec3 viewDirection(const glm::vec3& worldPosition) const {
    const CameraView& view = in_.frame.view;
    if (view.orthographic) return glm::normalize(glm::vec3(view.view[0][2], view.view[1][2], view.view[2][2]));
    return glm::normalize(view.position - worldPosition);
  }

  // composite.frag's background: the sky or the environment map along `ray`.
  glm::vec3 backgroundRadiance(const glm::vec3& ray) const {
    return (!in_.environment ? skyRadiance(in_.scene.sky, ray)
                             : in_.environment->background ? in_.environment->radiance(ray) : glm::vec3(0.0f)) *
           in_.skyIntensity;
  }

  // The ambient light arriving from `direction` (unit), before intensity.
  glm::vec3 ambientRadiance(const glm::vec3& direction) const {
    return in_.environment ? in_.environment->radiance(direction) : skyRadiance(in_.scene.sky, direction);
  }

  const TraceInputs& in_;
  glm::mat4 clipFromWorld_, worldFromClip_;  // the frame's view (shownOnScreen, primaryRay)
  RTCIntersectContext context_;
};

}  // namespace headlight::reference

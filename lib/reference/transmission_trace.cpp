#include "reference/transmission_trace.hpp"

#include <cmath>
#include <limits>

#include "reference/lobe_transmission.hpp"
#include "reference/texture_sampler.hpp"

namespace headlight::reference {

namespace {

// Passed transmissive layers along one ray, at most (a closed thin-walled
// sphere is two).
constexpr int kMaxPassedLayers = 16;

RTCRayHit rayHitFrom(const glm::vec3& origin, const glm::vec3& direction, float tnear) {
  RTCRayHit rayHit{};
  rayHit.ray.org_x = origin.x, rayHit.ray.org_y = origin.y, rayHit.ray.org_z = origin.z;
  rayHit.ray.dir_x = direction.x, rayHit.ray.dir_y = direction.y, rayHit.ray.dir_z = direction.z;
  rayHit.ray.tnear = tnear;
  rayHit.ray.tfar = std::numeric_limits<float>::infinity();
  rayHit.ray.mask = 0xFFFFFFFFu;
  rayHit.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rayHit.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
  return rayHit;
}

bool transmissive(const std::vector<InstanceShading>& instances, const RTCRayHit& rayHit) {
  return rayHit.hit.geomID != RTC_INVALID_GEOMETRY_ID && instances[rayHit.hit.geomID].material->transmissive();
}

}  // namespace

TransmissiveSurface transmissiveSurfaceAt(const Scene& scene, const std::vector<InstanceShading>& instances,
                                          RTCScene rtcScene, RTCIntersectContext& context, const glm::vec3& origin,
                                          const glm::vec3& direction) {
  RTCRayHit rayHit = rayHitFrom(origin, direction, 0.0f);
  rtcIntersect1(rtcScene, &context, &rayHit);
  if (!transmissive(instances, rayHit)) return {};
  const InstanceShading& instance = instances[rayHit.hit.geomID];
  const Material& material = *instance.material;
  const Primitive& primitive = *instance.primitive;
  const std::uint32_t* corner = &primitive.indices[std::size_t(rayHit.hit.primID) * 3];
  // gbuffer.frag samples textures only where the primitive has texcoords.
  auto sample = [&](const TextureRef& ref) {
    return !primitive.texcoords.empty() && ref.present()
               ? sampleTexture(scene, ref, textureUv(primitive, ref, corner, rayHit.hit.u, rayHit.hit.v), false)
               : glm::vec4(1.0f);
  };
  TransmissiveSurface surface;
  surface.share = material.transmission->transmissionFactor * sample(material.transmission->transmissionTexture).r;
  surface.ior = material.ior;
  if (material.volume) {
    surface.thickness = material.volume->thicknessFactor * sample(material.volume->thicknessTexture).g;
    surface.attenuationColor = material.volume->attenuationColor;
    const float distance = material.volume->attenuationDistance;
    surface.attenuationDistance = std::isinf(distance) ? 0.0f : distance;
  }
  const glm::mat4& worldFromLocal = scene.instances[rayHit.hit.geomID].worldFromLocal;
  surface.modelScale = glm::vec3(glm::length(glm::vec3(worldFromLocal[0])), glm::length(glm::vec3(worldFromLocal[1])),
                                 glm::length(glm::vec3(worldFromLocal[2])));
  return surface;
}

RTCRayHit firstOpaqueHit(const std::vector<InstanceShading>& instances, RTCScene rtcScene, RTCIntersectContext& context,
                         const glm::vec3& origin, const glm::vec3& direction, float tnear) {
  RTCRayHit rayHit = rayHitFrom(origin, direction, tnear);
  for (int layer = 0; layer < kMaxPassedLayers; ++layer) {
    rtcIntersect1(rtcScene, &context, &rayHit);
    if (!transmissive(instances, rayHit)) return rayHit;
    rayHit = rayHitFrom(origin, direction, std::nextafter(rayHit.ray.tfar, std::numeric_limits<float>::infinity()));
  }
  rtcIntersect1(rtcScene, &context, &rayHit);
  return rayHit;
}

}  // namespace headlight::reference

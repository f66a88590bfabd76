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

namespace {

// What one crossing of the transmissive surface `rayHit` meets adds to a
// walk's optical depth (lobe_transmission.hpp's shadowLayerOpticalDepth):
// shadow_transmittance.frag's inputs, the textures where the primitive has
// texcoords, COLOR_0, the metallic factor, the vertex normal.
// `distanceFromLight` of the hit, as the shadow pass measures it.
glm::vec3 layerOpticalDepthAt(const Scene& scene, const InstanceShading& instance, const RTCRayHit& rayHit,
                              const glm::vec3& direction, float distanceFromLight) {
  const Material& material = *instance.material;
  const Primitive& primitive = *instance.primitive;
  const std::uint32_t* corner = &primitive.indices[std::size_t(rayHit.hit.primID) * 3];
  const float u = rayHit.hit.u, v = rayHit.hit.v, w = 1.0f - u - v;
  auto sample = [&](const TextureRef& ref, bool srgb) {
    return !primitive.texcoords.empty() && ref.present()
               ? sampleTexture(scene, ref, textureUv(primitive, ref, corner, u, v), srgb)
               : glm::vec4(1.0f);
  };
  glm::vec3 baseColor = glm::vec3(material.baseColorFactor) * glm::vec3(sample(material.baseColorTexture, true));
  if (!primitive.colors.empty())
    baseColor *=
        glm::vec3(w * primitive.colors[corner[0]] + u * primitive.colors[corner[1]] + v * primitive.colors[corner[2]]);
  const float transmission =
      material.transmission->transmissionFactor * sample(material.transmission->transmissionTexture, false).r;
  const glm::vec3 normal =
      instance.normalFromLocal *
      (w * primitive.normals[corner[0]] + u * primitive.normals[corner[1]] + v * primitive.normals[corner[2]]);
  const float normalLength = glm::length(normal);
  const float cosine = normalLength > 0.0f ? glm::dot(normal / normalLength, direction) : 1.0f;
  const bool volume = material.volume && material.volume->thicknessFactor > 0.0f;
  const glm::vec3 extinction =
      volume && std::isfinite(material.volume->attenuationDistance)
          ? volumeExtinction(material.volume->attenuationColor, material.volume->attenuationDistance)
          : glm::vec3(0.0f);
  return shadowLayerOpticalDepth(baseColor, material.metallicFactor, transmission, material.ior, cosine, volume,
                                 extinction, distanceFromLight);
}

}  // namespace

glm::vec3 shadowRayTransmittance(const Scene& scene, const std::vector<InstanceShading>& instances, RTCScene rtcScene,
                                 RTCIntersectContext& context, const Light& light, const glm::vec3& origin,
                                 const glm::vec3& direction, float far) {
  glm::vec3 opticalDepth(0.0f);
  float tnear = 0.0f;
  for (int layer = 0; layer < kMaxShadowLayers; ++layer) {
    RTCRayHit rayHit = rayHitFrom(origin, direction, tnear);
    rayHit.ray.tfar = far;
    rtcIntersect1(rtcScene, &context, &rayHit);
    if (rayHit.hit.geomID == RTC_INVALID_GEOMETRY_ID) return shadowTransmittance(opticalDepth);
    if (!transmissive(instances, rayHit)) return glm::vec3(0.0f);
    const glm::vec3 position = origin + direction * rayHit.ray.tfar;
    const bool directional = light.type == Light::Type::Directional;
    const float distanceFromLight =
        directional ? glm::dot(position, glm::normalize(light.direction)) : glm::length(position - light.position);
    opticalDepth += layerOpticalDepthAt(scene, instances[rayHit.hit.geomID], rayHit, direction, distanceFromLight);
    tnear = std::nextafter(rayHit.ray.tfar, std::numeric_limits<float>::infinity());
  }
  return glm::vec3(0.0f);
}

PassedHit passTransmissive(const Scene& scene, const std::vector<InstanceShading>& instances, RTCScene rtcScene,
                           RTCIntersectContext& context, const glm::vec3& origin, const glm::vec3& direction,
                           const RTCRayHit& first) {
  glm::vec3 opticalDepth(0.0f);
  RTCRayHit rayHit = first;
  for (int layer = 0; layer < kMaxShadowLayers; ++layer) {
    if (!transmissive(instances, rayHit)) return {rayHit, shadowTransmittance(opticalDepth)};
    // Light travelling back along the ray: its distance from a source at
    // infinity, as a directional light's (any offset cancels in a volume).
    const glm::vec3 position = origin + direction * rayHit.ray.tfar;
    opticalDepth +=
        layerOpticalDepthAt(scene, instances[rayHit.hit.geomID], rayHit, -direction, glm::dot(position, -direction));
    rayHit = rayHitFrom(origin, direction, std::nextafter(rayHit.ray.tfar, std::numeric_limits<float>::infinity()));
    rtcIntersect1(rtcScene, &context, &rayHit);
  }
  return {rayHitFrom(origin, direction, 0.0f), glm::vec3(0.0f)};  // too many layers: nothing comes through
}

}  // namespace headlight::reference

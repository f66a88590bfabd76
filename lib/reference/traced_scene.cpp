#include "reference/traced_scene.hpp"

#include <cstdint>
#include <string>

#include "headlight/error.hpp"
#include "headlight/limits.hpp"
#include "reference/texture_sampler.hpp"

namespace headlight::reference {

namespace {

// glTF's default material: white, fully metallic, fully rough.
const Material& defaultMaterial() {
  static const Material material;
  return material;
}

// Embree's intersect and occluded filter: a hit on a cut-out texel is
// rejected, so the ray goes on through the hole.
void skipCutOuts(const RTCFilterFunctionNArguments* args) {
  const auto& instance = *static_cast<const InstanceShading*>(args->geometryUserPtr);
  for (unsigned lane = 0; lane < args->N; ++lane) {
    if (args->valid[lane] != -1) continue;
    if (cutOut(instance, RTCHitN_primID(args->hit, args->N, lane), RTCHitN_u(args->hit, args->N, lane),
               RTCHitN_v(args->hit, args->N, lane)))
      args->valid[lane] = 0;
  }
}

}  // namespace

bool cutOut(const InstanceShading& instance, unsigned triangle, float u, float v) {
  const Material& material = *instance.material;
  if (!material.masked()) return false;
  float alpha = material.baseColorFactor.a;
  const Primitive& primitive = *instance.primitive;
  if (!primitive.texcoords.empty() && material.baseColorTexture.present()) {
    const std::uint32_t* corner = &primitive.indices[3 * std::size_t(triangle)];
    alpha *= sampleTexture(*instance.scene, material.baseColorTexture,
                           textureUv(primitive, material.baseColorTexture, corner, u, v), true)
                 .a;
  }
  if (!primitive.colors.empty()) {
    const std::uint32_t* corner = &primitive.indices[3 * std::size_t(triangle)];
    alpha *= (1.0f - u - v) * primitive.colors[corner[0]].a + u * primitive.colors[corner[1]].a +
             v * primitive.colors[corner[2]].a;
  }
  return alpha < material.alphaCutoff;
}

TracedScene buildScene(const Scene& scene, int threads) {
  // The renderer's contract for a scene (its instances, primitives and
  // materials name what exists, attribute counts match): the embedder's
  // scene may not have been through setScene or the loader.
  checkSceneRanges(scene);
  // "threads=N" also bounds Embree's own BVH-building threads.
  TracedScene traced{EmbreeDevice(threads > 0 ? "threads=" + std::to_string(threads) : std::string()),
                     EmbreeScene(),
                     EmbreeScene(),
                     false,
                     {}};
  traced.device.check("rtcNewDevice");
  traced.scene = EmbreeScene(traced.device.get());
  traced.blended = EmbreeScene(traced.device.get());
  traced.device.check("rtcNewScene");
  traced.instances.resize(scene.instances.size());
  for (std::size_t id = 0; id < scene.instances.size(); ++id) {
    const Instance& instance = scene.instances[id];
    const Primitive& primitive = scene.primitives[std::size_t(instance.primitive)];
    const Material& material =
        instance.material >= 0 ? scene.materials[std::size_t(instance.material)] : defaultMaterial();
    const std::size_t triangleCount = primitive.indices.size() / 3;
    const std::size_t vertexCount = primitive.positions.size();
    // Rays cannot hit a point or a line: the reference does not see them
    // (their G-buffer pixels are still shading points).
    if (triangleCount == 0 || vertexCount == 0 || primitive.mode != PrimitiveMode::Triangles) continue;

    // The scene keeps its own reference to an attached geometry; this one
    // goes at the end of the iteration.
    const EmbreeGeometry geometry(traced.device.get(), RTC_GEOMETRY_TYPE_TRIANGLE);
    auto* positions = static_cast<float*>(rtcSetNewGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_VERTEX, 0,
                                                                  RTC_FORMAT_FLOAT3, 3 * sizeof(float), vertexCount));
    if (positions) {
      for (std::size_t v = 0; v < vertexCount; ++v) {
        const glm::vec3 world = glm::vec3(instance.worldFromLocal * glm::vec4(primitive.positions[v], 1.0f));
        positions[3 * v + 0] = world.x;
        positions[3 * v + 1] = world.y;
        positions[3 * v + 2] = world.z;
      }
      // The scene outlives the Embree scene (the caller's promise), so its
      // indices are shared rather than copied.
      rtcSetSharedGeometryBuffer(geometry.get(), RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, primitive.indices.data(),
                                 0, 3 * sizeof(std::uint32_t), triangleCount);
      if (material.masked()) {
        rtcSetGeometryUserData(geometry.get(), &traced.instances[id]);
        rtcSetGeometryIntersectFilterFunction(geometry.get(), skipCutOuts);
        rtcSetGeometryOccludedFilterFunction(geometry.get(), skipCutOuts);
      }
      rtcCommitGeometry(geometry.get());
      rtcAttachGeometryByID(material.blended() ? traced.blended.get() : traced.scene.get(), geometry.get(),
                            unsigned(id));
      traced.hasBlended = traced.hasBlended || material.blended();
    }
    traced.device.check(scene.source + ": instance " + std::to_string(id) + " (" + std::to_string(triangleCount) +
                        " triangles)");

    InstanceShading& shading = traced.instances[id];
    shading.scene = &scene;
    shading.primitive = &primitive;
    shading.material = &material;
    shading.normalFromLocal = normalMatrix(instance.worldFromLocal);
    shading.worldPositions = positions;
    shading.frontSign = mirrors(instance.worldFromLocal) ? -1.0f : 1.0f;
  }
  rtcCommitScene(traced.scene.get());
  rtcCommitScene(traced.blended.get());
  traced.device.check("building the BVH of " + scene.source);
  return traced;
}

}  // namespace headlight::reference

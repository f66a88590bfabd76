#include "passes/shadow.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "gl/shader_library.hpp"
#include "headlight/error.hpp"
#include "scene/look_up.hpp"

namespace headlight {
namespace {

int shaderType(Light::Type type) {
  switch (type) {
    case Light::Type::Directional:
      return gpu::kLightDirectional;
    case Light::Type::Point:
      return gpu::kLightPoint;
    case Light::Type::Spot:
      return gpu::kLightSpot;
  }
  return gpu::kLightPoint;
}

// The square, in the light's view (looking along `direction` at the scene's
// centre), that holds the scene's bounding sphere: every caster.
glm::mat4 directionalView(const Light& light, const Bounds& bounds) {
  const float radius = std::max(bounds.radius(), 1e-30f);
  const glm::vec3 center = bounds.center();
  return glm::lookAt(center - light.direction * (2.0f * radius), center, upFor(light.direction));
}

// The part of the sphere's square (light view x, y) that the camera can
// see: its frustum's corners (near and far planes fitted to the scene) in the
// light's view, met with the square, as (min x, min y, max x, max y). Only
// receivers in view need texels; a caster that shades one lies on the same
// line along the light, so inside the same rectangle, and the depth range
// stays the whole sphere's.
glm::vec4 visibleRectangle(const glm::mat4& lightView, float radius, const CameraView& camera) {
  const glm::mat4 lightFromClip = lightView * glm::inverse(camera.projection * camera.view);
  glm::vec2 low(radius), high(-radius);
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec4 clip((corner & 1) ? 1.0f : -1.0f, (corner & 2) ? 1.0f : -1.0f, (corner & 4) ? 1.0f : -1.0f, 1.0f);
    const glm::vec4 point = lightFromClip * clip;
    const glm::vec2 xy = glm::vec2(point) / point.w;
    low = glm::min(low, xy);
    high = glm::max(high, xy);
  }
  // A frustum wider than the sphere keeps the square; the floor keeps a
  // degenerate one from collapsing to no texels.
  const float floor = 1e-3f * radius;
  low = glm::clamp(low, glm::vec2(-radius), glm::vec2(radius - floor));
  high = glm::clamp(high, low + floor, glm::vec2(radius));
  return {low, high};
}

// What a directional light's map covers for `camera`: the visible part of
// the square where that is at most kFittedArea of it, else the whole square,
// which does not depend on the view (a batch's views then share the maps;
// MetalRoughSpheresNoTextures' framing sees all of it from every side).
// builtin:slats' view covers 0.68 of its square, builtin:spheres' 0.67.
constexpr float kFittedArea = 0.8f;
glm::vec4 directionalRectangle(const Light& light, const Bounds& bounds, const CameraView* camera) {
  const float radius = std::max(bounds.radius(), 1e-30f);
  const glm::vec4 square(-radius, -radius, radius, radius);
  if (camera == nullptr) return square;
  const glm::vec4 seen = visibleRectangle(directionalView(light, bounds), radius, *camera);
  return (seen.z - seen.x) * (seen.w - seen.y) <= kFittedArea * 4.0f * radius * radius ? seen : square;
}

// Light view and orthographic projection for a directional light.
glm::mat4 directionalViewProjection(const Light& light, const Bounds& bounds, const glm::vec4& rectangle, int size,
                                    float& texelWorldSize) {
  const float radius = std::max(bounds.radius(), 1e-30f);
  // The PCF radius and the normal offset are in texels: the wider side's.
  texelWorldSize = std::max(rectangle.z - rectangle.x, rectangle.w - rectangle.y) / float(size);
  return glm::ortho(rectangle.x, rectangle.z, rectangle.y, rectangle.w, radius, 3.0f * radius) *
         directionalView(light, bounds);
}

// Distance from `point` to the farthest corner of the bounds' sphere.
float farDistance(const glm::vec3& point, const Bounds& bounds) {
  return glm::length(bounds.center() - point) + bounds.radius();
}

// texelPerDistance: a texel's world size at unit distance from the light.
glm::mat4 spotViewProjection(const Light& light, const Bounds& bounds, int size, float& texelPerDistance) {
  const float far = std::max(farDistance(light.position, bounds), 1e-30f);
  // The cone plus a margin for the PCF filter, and never wider than 170
  // degrees, past which a perspective map has no resolution left.
  const float fov = std::min(2.0f * light.outerConeAngle + 0.1f, glm::radians(170.0f));
  texelPerDistance = 2.0f * std::tan(0.5f * fov) / float(size);
  const glm::mat4 view = glm::lookAt(light.position, light.position + light.direction, upFor(light.direction));
  return glm::perspective(fov, 1.0f, far * 1e-4f, far) * view;
}

// Cube faces in GL's order (+X, -X, +Y, -Y, +Z, -Z) with the up vectors that
// match how samplerCube picks texels.
glm::mat4 cubeFaceView(const glm::vec3& position, int face) {
  static const glm::vec3 directions[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  static const glm::vec3 ups[6] = {{0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}, {0, -1, 0}, {0, -1, 0}};
  return glm::lookAt(position, position + directions[face], ups[face]);
}

}  // namespace

int cubeFaceSize(int size) { return std::max(size / 2, 1); }

void appendShadowDefines(const ShadowLookups& lookups, std::vector<std::string>& defines) {
  if (lookups.planar) defines.emplace_back("HAS_PLANAR_SHADOWS");
  if (lookups.cube) defines.emplace_back("HAS_CUBE_SHADOWS");
  if (lookups.transmittance) defines.emplace_back("HAS_SHADOW_TRANSMITTANCE");
}

void bindShadowMaps(const ShadowMaps& maps, const ShadowLookups& lookups) {
  if (lookups.planar) maps.planar.bind(gpu::kUnitShadowMaps2D);
  if (lookups.cube) maps.cube.bind(gpu::kUnitShadowMapsCube);
  if (lookups.transmittance && lookups.planar) maps.planarTransmittance.bind(gpu::kUnitShadowTransmittance2D);
  if (lookups.transmittance && lookups.cube) maps.cubeTransmittance.bind(gpu::kUnitShadowTransmittanceCube);
}

ShadowCasters countShadowCasters(const std::vector<Light>& lights) {
  ShadowCasters casters;
  for (const Light& light : lights)
    if (light.castsShadows) (light.type == Light::Type::Point ? casters.cube : casters.planar)++;
  return casters;
}

std::uint64_t shadowMapBytes(const ShadowCasters& casters, int size, bool transmittance) {
  const std::uint64_t texelBytes = transmittance ? 4 + 16 : 4;
  const std::uint64_t planar = std::uint64_t(size) * std::uint64_t(size);
  const std::uint64_t cube = 6 * std::uint64_t(cubeFaceSize(size)) * std::uint64_t(cubeFaceSize(size));
  return texelBytes * (std::uint64_t(casters.planar) * planar + std::uint64_t(casters.cube) * cube);
}

std::uint64_t checkShadowMapsFit(const std::string& source, const ShadowCasters& casters, int size, bool transmittance,
                                 std::uint64_t otherBytes, const ResourceLimits& limits) {
  const std::uint64_t bytes = shadowMapBytes(casters, size, transmittance);
  const std::uint64_t limit = maxMemoryBytes(limits);
  if (bytes + otherBytes <= limit) return bytes;
  auto mib = [](std::uint64_t b) { return std::to_string((b + (1u << 20) - 1) >> 20) + " MiB"; };
  throw LimitError(source + ": the shadow maps of its " + std::to_string(casters.planar + casters.cube) +
                       " shadow-casting lights (" + std::to_string(casters.cube) + " point, " +
                       std::to_string(casters.planar) + " directional or spot) need " + mib(bytes) + " at " +
                       std::to_string(size) + " texels a side" + (transmittance ? " with transmittance maps" : "") +
                       ", and the frame and scene " + mib(otherBytes) + ": more than max-memory allows (" + mib(limit) +
                       "); lower --shadow-map-size, render with --no-shadows or raise --max-memory",
                   {"max-memory"});
}

std::vector<glm::vec4> directionalCoverage(const std::vector<Light>& lights, const Bounds& bounds,
                                           const CameraView* camera) {
  std::vector<glm::vec4> coverage;
  for (const Light& light : lights)
    if (light.castsShadows && light.type == Light::Type::Directional)
      coverage.push_back(directionalRectangle(light, bounds, camera));
  return coverage;
}

std::vector<gpu::GpuLight> packLights(const std::vector<Light>& lights, std::span<const ShadowSlot> slots) {
  std::vector<gpu::GpuLight> packed;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& light = lights[i];
    const ShadowSlot slot = i < slots.size() ? slots[i] : ShadowSlot{};
    gpu::GpuLight gpu{};
    gpu.position = light.position;
    gpu.range = light.range;
    gpu.direction = glm::normalize(light.direction);
    gpu.type = shaderType(light.type);
    gpu.radiance = light.color * light.intensity;
    gpu.castsShadows = slot.layer >= 0 ? 1 : 0;
    gpu.cosOuterCone = std::cos(light.outerConeAngle);
    gpu.cosInnerCone = std::cos(light.innerConeAngle);
    gpu.shadowLayer = slot.layer;
    gpu.shadowFar = slot.far;
    gpu.shadowTexelSize = slot.texelSize;
    gpu.shadowViewProjection = slot.viewProjection;
    packed.push_back(gpu);
  }
  return packed;
}

ShadowPass::ShadowPass()
    : program_(detail::buildProgram(std::array<std::string_view, 2>{"shadow.vert", "shadow.frag"})),
      maskedPrograms_("shadow.vert", "shadow.frag", featureDefines),
      transmittancePrograms_("shadow.vert", "shadow_transmittance.frag",
                             [](FeatureBits features) {
                               std::vector<std::string> defines = featureDefines(features);
                               defines.emplace_back("SHADOW_TRANSMITTANCE");
                               return defines;
                             }),
      block_(gl::Buffer::create(sizeof(gpu::ShadowBlock))),
      framebuffer_(gl::Framebuffer::create()) {
  framebuffer_.setDrawBuffers({});
}

ShadowOutputs ShadowPass::run(const GpuScene& scene, const std::vector<Light>& lights, int size,
                              const CameraView* camera, bool transmittance) {
  const ShadowCasters casters = countShadowCasters(lights);
  ShadowOutputs out;
  ShadowMaps& maps = out.maps;
  maps.size = size;
  if (casters.planar > 0) {
    maps.planar = gl::Texture::create2DArray(GL_DEPTH_COMPONENT32F, size, size, casters.planar);
    if (transmittance) maps.planarTransmittance = gl::Texture::create2DArray(GL_RGBA32F, size, size, casters.planar);
  }
  if (casters.cube > 0) {
    maps.cube = gl::Texture::createCubeArray(GL_DEPTH_COMPONENT32F, cubeFaceSize(size), casters.cube);
    if (transmittance)
      maps.cubeTransmittance = gl::Texture::createCubeArray(GL_RGBA32F, cubeFaceSize(size), casters.cube);
  }
  // Read texel by texel: a layer's depth (a) must not blend with its neighbour's.
  for (const gl::Texture* map : {&maps.planarTransmittance, &maps.cubeTransmittance}) {
    if (!*map) continue;
    glTextureParameteri(map->id(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTextureParameteri(map->id(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTextureParameteri(map->id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(map->id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
  }
  for (const gl::Texture* map : {&maps.planar, &maps.cube}) {
    if (!*map) continue;
    glTextureParameteri(map->id(), GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    glTextureParameteri(map->id(), GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    glTextureParameteri(map->id(), GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTextureParameteri(map->id(), GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    glTextureParameteri(map->id(), GL_TEXTURE_COMPARE_MODE, GL_COMPARE_REF_TO_TEXTURE);
    glTextureParameteri(map->id(), GL_TEXTURE_COMPARE_FUNC, GL_LEQUAL);
  }

  out.slots.resize(lights.size());
  int planarLayer = 0, cubeLayer = 0;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& light = lights[i];
    if (!light.castsShadows) continue;
    ShadowSlot& slot = out.slots[i];
    if (light.type == Light::Type::Point) {
      const float far = std::max(farDistance(light.position, scene.bounds), 1e-30f);
      const glm::mat4 projection = glm::perspective(glm::radians(90.0f), 1.0f, far * 1e-4f, far);
      for (int face = 0; face < 6; ++face)
        renderView(scene, maps, true, 6 * cubeLayer + face,
                   {projection * cubeFaceView(light.position, face), glm::vec4(light.position, far),
                    glm::vec4(light.position, 1.0f)});
      slot.layer = cubeLayer++;
      slot.far = far;
    } else {
      const glm::mat4 viewProjection = light.type == Light::Type::Directional
                                           ? directionalViewProjection(light, scene.bounds, directionalRectangle(light, scene.bounds, camera),
                                                                       size, slot.texelSize)
                                           : spotViewProjection(light, scene.bounds, size, slot.texelSize);
      const glm::vec4 origin = light.type == Light::Type::Directional ? glm::vec4(glm::normalize(light.direction), 0.0f)
                                                                      : glm::vec4(light.position, 1.0f);
      renderView(scene, maps, false, planarLayer, {viewProjection, glm::vec4(0.0f), origin});
      slot.viewProjection = viewProjection;
      slot.layer = planarLayer++;
    }
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);
  framebuffer_.detach(GL_DEPTH_ATTACHMENT);
  return out;
}

void ShadowPass::renderView(const GpuScene& scene, const ShadowMaps& maps, bool cube, int layer,
                            const gpu::ShadowBlock& block) {
  const gl::Texture& target = cube ? maps.cube : maps.planar;
  block_.update(block);
  block_.bindUniform(gpu::ShadowBlock::kBinding);
  framebuffer_.attach(GL_DEPTH_ATTACHMENT, target, layer);
  framebuffer_.checkComplete("shadow map");
  framebuffer_.bind();
  glViewport(0, 0, target.width(), target.height());
  const float farDepth = 1.0f;
  glClearNamedFramebufferfv(framebuffer_.id(), GL_DEPTH, 0, &farDepth);
  glEnable(GL_DEPTH_TEST);
  glDepthFunc(GL_LESS);
  // Both faces: single-sided walls must still block light from behind.
  glDisable(GL_CULL_FACE);
  scene.objects.bindStorage(gpu::ObjectBuffer::kBinding);
  // Every instance of a primitive in one draw, whatever its material, unless
  // one of its materials cuts out (alphaMode MASK) or transmits.
  for (const GpuPrimitiveRun& run : scene.primitiveRuns) {
    if (run.masked || run.transmissive) {
      drawGroups(scene, run, false);
      continue;
    }
    const GpuPrimitive& primitive = scene.primitives[std::size_t(run.primitive)];
    program_.use();
    primitive.vertexArray.bind();
    glDrawElementsInstancedBaseInstance(GL_TRIANGLES, primitive.indexCount, GL_UNSIGNED_INT, nullptr,
                                        run.instanceCount, run.firstInstance);
  }

  const gl::Texture& transmittance = cube ? maps.cubeTransmittance : maps.planarTransmittance;
  if (!transmittance) return;
  // The transmissive layers in front of the depth map's surfaces: summed
  // optical depth (rgb, added) and the nearest layer's depth (a, the least).
  framebuffer_.attach(GL_COLOR_ATTACHMENT0, transmittance, layer);
  const GLenum drawBuffers[] = {GL_COLOR_ATTACHMENT0};
  framebuffer_.setDrawBuffers(drawBuffers);
  framebuffer_.checkComplete("shadow transmittance map");
  const float noLayers[] = {0.0f, 0.0f, 0.0f, 1.0f};
  glClearNamedFramebufferfv(framebuffer_.id(), GL_COLOR, 0, noLayers);
  glDepthMask(GL_FALSE);
  glEnablei(GL_BLEND, 0);
  glBlendEquationSeparatei(0, GL_FUNC_ADD, GL_MIN);
  glBlendFuncSeparatei(0, GL_ONE, GL_ONE, GL_ONE, GL_ONE);
  for (const GpuPrimitiveRun& run : scene.primitiveRuns)
    if (run.transmissive) drawGroups(scene, run, true);
  glDisablei(GL_BLEND, 0);
  glDepthMask(GL_TRUE);
  framebuffer_.detach(GL_COLOR_ATTACHMENT0);
  framebuffer_.setDrawBuffers({});
}

// A run group by group: with `transmissive`, only its transmissive groups
// (into the transmittance map); else the others, masked groups sampling
// their base colour alpha and discarding below the cutoff, the rest depth
// only.
void ShadowPass::drawGroups(const GpuScene& scene, const GpuPrimitiveRun& run, bool transmissive) {
  const GpuPrimitive& primitive = scene.primitives[std::size_t(run.primitive)];
  primitive.vertexArray.bind();
  const MaterialTextureRow& transmissionRow = materialTextureRows()[std::size_t(MaterialTexture::Transmission)];
  for (std::size_t g = run.firstGroup; g < run.firstGroup + run.groupCount; ++g) {
    const GpuDrawGroup& group = scene.drawGroups[g];
    const GpuMaterial& material = scene.materials[std::size_t(group.material)];
    if (material.transmissive != transmissive) continue;
    constexpr FeatureBits kMaskFeatures = kFeatureAlphaMask | kFeatureTexcoords | kFeatureBaseColorTexture |
                                          kFeatureVertexColors | kFeatureTexcoords1 | kFeatureBaseColorTexcoord1 |
                                          kFeatureTextureTransform;
    const FeatureBits all = drawFeatures(primitive, material);
    auto bindTexture = [&](MaterialTexture id, int unit) {
      const GpuTexture& texture = scene.textures[std::size_t(material.textures[std::size_t(id)])];
      texture.texture.bind(unit);
      texture.sampler.bind(unit);
    };
    if (transmissive) {
      const FeatureBits features = all & (kMaskFeatures | transmissionRow.feature | transmissionRow.texcoord1);
      transmittancePrograms_.get(features).use();
      material.block.bindUniform(gpu::MaterialBlock::kBinding);
      if (features & kFeatureBaseColorTexture) bindTexture(MaterialTexture::BaseColor, gpu::kUnitBaseColorTexture);
      if (features & transmissionRow.feature) bindTexture(MaterialTexture::Transmission, transmissionRow.unit);
    } else if (const FeatureBits features = all & kMaskFeatures; features & kFeatureAlphaMask) {
      maskedPrograms_.get(features).use();
      material.block.bindUniform(gpu::MaterialBlock::kBinding);
      if (features & kFeatureBaseColorTexture) bindTexture(MaterialTexture::BaseColor, gpu::kUnitBaseColorTexture);
    } else {
      program_.use();
    }
    glDrawElementsInstancedBaseInstance(GL_TRIANGLES, primitive.indexCount, GL_UNSIGNED_INT, nullptr,
                                        group.instanceCount, group.firstInstance);
  }
}

}  // namespace headlight

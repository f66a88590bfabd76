#include "passes/virtual_lights.hpp"

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "gl/readback.hpp"
#include "gl/target_formats.hpp"
#include "reference/shading.hpp"
#include "scene/look_up.hpp"
#include "shared_layout.h"

namespace headlight {
namespace {

// A light's perspective view from `position` along `direction`.
LightView perspectiveView(std::size_t light, const glm::vec3& position, const glm::vec3& direction, float fov,
                          const Bounds& bounds) {
  LightView view;
  view.light = light;
  view.tanHalfFov = std::tan(0.5f * fov);
  view.camera = perspectiveCamera(position, direction, fov, bounds);
  return view;
}

// A directional light's view: the square round the scene's bounding sphere,
// seen along the light.
LightView directionalView(std::size_t light, const glm::vec3& direction, const Bounds& bounds) {
  LightView view;
  view.light = light;
  const float radius = std::max(bounds.radius(), 1e-30f);
  view.halfWidth = radius;
  CameraView& camera = view.camera;
  camera.orthographic = true;
  camera.position = bounds.center() - direction * (2.0f * radius);
  camera.nearPlane = radius;
  camera.farPlane = 3.0f * radius;
  camera.view = glm::lookAt(camera.position, bounds.center(), upFor(direction));
  camera.projection = glm::ortho(-radius, radius, -radius, radius, camera.nearPlane, camera.farPlane);
  return view;
}

// The power the surface at texel (x, y) of `view` reflects diffusely: the
// light's radiant intensity times the texel's measure (texelMeasure), as
// far as the surface faces the light, times (1 - metallic) albedo. The
// texel's area on the surface, solid angle x distance^2 / cos, cancels the
// irradiance's cos / distance^2.
glm::vec3 reflectedFlux(const Light& light, const LightView& view, int x, int y, int size, const glm::vec3& position,
                        const glm::vec3& normal, const glm::vec3& diffuse) {
  glm::vec3 toLight;
  float distance = 0.0f;
  const float attenuation = reference::lightAttenuation(light, position, toLight, distance);
  if (attenuation <= 0.0f || glm::dot(normal, toLight) <= 0.0f) return glm::vec3(0.0f);
  const glm::vec3 intensity = light.color * light.intensity;
  const float measure = texelMeasure(view, x, y, size);
  if (light.type == Light::Type::Directional) return diffuse * intensity * measure;
  return diffuse * intensity * (attenuation * distance * distance * measure);
}

// The area of the surface texel (x, y) of `view` covers: its measure across
// the light's rays, times the distance squared for a perspective view,
// over the cosine to the light (no more than 20 times the texel's area
// across the rays: a surface seen edge-on).
float texelSurfaceArea(const Light& light, const LightView& view, int x, int y, int size, const glm::vec3& position,
                       const glm::vec3& normal) {
  glm::vec3 toLight;
  float distance = 0.0f;
  reference::lightAttenuation(light, position, toLight, distance);
  const float across =
      texelMeasure(view, x, y, size) * (light.type == Light::Type::Directional ? 1.0f : distance * distance);
  return across / std::max(glm::dot(normal, toLight), 0.05f);
}

}  // namespace

CameraView perspectiveCamera(const glm::vec3& position, const glm::vec3& direction, float fov, const Bounds& bounds) {
  CameraView camera;
  camera.farPlane = std::max(glm::length(bounds.center() - position) + bounds.radius(), 1e-30f);
  camera.nearPlane = camera.farPlane * 1e-4f;
  camera.position = position;
  camera.view = glm::lookAt(position, position + direction, upFor(direction));
  camera.projection = glm::perspective(fov, 1.0f, camera.nearPlane, camera.farPlane);
  return camera;
}

std::vector<LightView> lightViews(const std::vector<Light>& lights, const Bounds& bounds) {
  std::vector<LightView> views;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    const Light& light = lights[i];
    // A light that casts no shadow gets no views: the views a scene's lights
    // add are then its shadow maps' views, which --max-draws bounds
    // (checkDrawBudget), once per scene.
    if (!light.castsShadows) continue;
    const glm::vec3 direction = glm::normalize(light.direction);
    switch (light.type) {
      case Light::Type::Point:
        for (const glm::vec3& face : kCubeFaceDirections)
          views.push_back(perspectiveView(i, light.position, face, glm::radians(90.0f), bounds));
        break;
      case Light::Type::Spot:
        // The cone, never wider than 170 degrees (a perspective view has no
        // texels left past that; the light there is faint at most).
        views.push_back(perspectiveView(i, light.position, direction,
                                        std::min(2.0f * light.outerConeAngle, glm::radians(170.0f)), bounds));
        break;
      case Light::Type::Directional:
        views.push_back(directionalView(i, direction, bounds));
        break;
    }
  }
  return views;
}

float texelMeasure(const LightView& view, int x, int y, int size) {
  if (view.camera.orthographic) {
    const float side = 2.0f * view.halfWidth / float(size);
    return side * side;
  }
  // The texel's centre on the image plane at unit distance, and its solid
  // angle: area / distance^3 there.
  const float t = view.tanHalfFov, side = 2.0f * t / float(size);
  const float u = t * ((2.0f * float(x) + 1.0f) / float(size) - 1.0f);
  const float v = t * ((2.0f * float(y) + 1.0f) / float(size) - 1.0f);
  const float planeDistance2 = 1.0f + u * u + v * v;
  return side * side / (planeDistance2 * std::sqrt(planeDistance2));
}

int lightViewSize(int budget, std::size_t viewCount) {
  if (viewCount == 0) return 0;
  return std::max(1, int(std::sqrt(double(budget) / double(viewCount))));
}

VirtualLights VirtualLightPass::run(const GpuScene& scene, GBufferPass& gbuffer, const GBufferVariant& variant,
                                    const std::vector<Light>& lights, int budget, const BindView& bindView) {
  VirtualLights out;
  const std::vector<LightView> views = lightViews(lights, scene.bounds);
  const int size = lightViewSize(budget, views.size());
  if (size == 0) return out;

  const auto create = [size](GpuFormat format) { return gl::Texture::create2D(gl::internalFormat(format), size, size); };
  const gl::Texture position = create(GpuFormat::Rgba32F), normal = create(GpuFormat::Rgba16F),
                    albedo = create(GpuFormat::Srgb8Alpha8), material = create(GpuFormat::Rgba8),
                    depth = create(GpuFormat::Depth32F);
  GBufferTargets targets{std::vector<const gl::Texture*>(variant.colorAttachments.size(), nullptr), &depth, size,
                         size};
  for (std::size_t location = 0; location < variant.colorAttachments.size(); ++location) {
    switch (variant.colorAttachments[location]) {
      case Attachment::GbufferPosition: targets.colors[location] = &position; break;
      case Attachment::GbufferNormal: targets.colors[location] = &normal; break;
      case Attachment::GbufferAlbedo: targets.colors[location] = &albedo; break;
      case Attachment::GbufferMaterial: targets.colors[location] = &material; break;
      default: break;  // emission and the lobes: not needed here
    }
  }

  std::vector<gpu::GpuVirtualLight> virtualLights;
  for (const LightView& view : views) {
    bindView(view.camera, size);
    gbuffer.run(scene, targets, variant);
    const ImageF positions = readColor(position, {"x", "y", "z", "a"});
    const ImageF normals = readColor(normal, {"x", "y", "z"});
    const ImageF albedos = readColor(albedo, {"r", "g", "b"});
    const ImageF materials = readColor(material, {"metallic"});
    for (int y = 0; y < size; ++y)
      for (int x = 0; x < size; ++x) {
        if (positions.at(x, y, 3) == 0.0f) continue;  // the light sees nothing here
        const glm::vec3 p(positions.at(x, y, 0), positions.at(x, y, 1), positions.at(x, y, 2));
        const glm::vec3 n(normals.at(x, y, 0), normals.at(x, y, 1), normals.at(x, y, 2));
        const glm::vec3 diffuse =
            (1.0f - materials.at(x, y, 0)) * glm::vec3(albedos.at(x, y, 0), albedos.at(x, y, 1), albedos.at(x, y, 2));
        const glm::vec3 flux = reflectedFlux(lights[view.light], view, x, y, size, p, n, diffuse);
        if (flux == glm::vec3(0.0f)) continue;
        virtualLights.push_back({glm::vec4(p, float(view.light)),
                                 glm::vec4(n, texelSurfaceArea(lights[view.light], view, x, y, size, p, n)),
                                 glm::vec4(flux, 0.0f)});
      }
  }
  out.count = int(virtualLights.size());
  // At least one entry: a zero-sized buffer cannot be bound.
  out.buffer = gl::Buffer::create(std::max<std::size_t>(1, virtualLights.size()) * sizeof(gpu::GpuVirtualLight));
  if (!virtualLights.empty())
    out.buffer.update(virtualLights.data(), virtualLights.size() * sizeof(gpu::GpuVirtualLight));
  out.entries = std::move(virtualLights);
  return out;
}

}  // namespace headlight

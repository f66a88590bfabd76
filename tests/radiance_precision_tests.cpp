// radiance-precision without GL: its auto value from the scene's light
// sources, and the formats the frame plan gives the attachments that hold
// light. (The hostile suite renders a bright scene and checks the files.)
#include <doctest/doctest.h>

#include "frame/frame_plan.hpp"
#include "frame/resolve.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"

namespace headlight {
namespace {

// A 2-unit box (diagonal 2 sqrt 3) with one light or one emitter.
Scene boxWith(Light light, glm::vec3 emissive = glm::vec3(0.0f)) {
  Scene scene;
  Material material;
  material.emissiveFactor = emissive;
  addInstance(scene, makeBox(glm::vec3(2.0f)), addMaterial(scene, material));
  scene.lights.push_back(light);
  return scene;
}

Light lightOf(Light::Type type, float intensity) {
  Light light;
  light.type = type;
  light.intensity = intensity;
  return light;
}

RadiancePrecision resolvedPrecision(const Scene& scene) {
  return *resolveSettings(RenderSettings{}, scene).radiancePrecision;
}

}  // namespace

TEST_CASE("radiance-precision auto: half for the built-ins, float where a light source may pass half's range") {
  for (const char* name : {"builtin:cornell", "builtin:spheres", "builtin:slats"}) {
    CAPTURE(name);
    CHECK(resolvedPrecision(loadScene(name)) == RadiancePrecision::Half);
  }
  constexpr float kPi = 3.14159265f;
  const float threshold = 65504.0f / kHalfHeadroom;  // radiance the estimate may reach and stay half
  // Directional: illuminance / pi.
  CHECK(resolvedPrecision(boxWith(lightOf(Light::Type::Directional, 0.99f * threshold * kPi))) ==
        RadiancePrecision::Half);
  CHECK(resolvedPrecision(boxWith(lightOf(Light::Type::Directional, 1.01f * threshold * kPi))) ==
        RadiancePrecision::Float);
  // Point: intensity / (pi d^2) at d = 5 % of the diagonal.
  const float diagonal = 2.0f * std::sqrt(3.0f), near = kNearLightFraction * diagonal;
  CHECK(brightestRadianceEstimate(boxWith(lightOf(Light::Type::Point, 100.0f)), diagonal) ==
        doctest::Approx(100.0f / (kPi * near * near)));
  CHECK(resolvedPrecision(boxWith(lightOf(Light::Type::Point, 0.99f * threshold * kPi * near * near))) ==
        RadiancePrecision::Half);
  CHECK(resolvedPrecision(boxWith(lightOf(Light::Type::Spot, 1.01f * threshold * kPi * near * near))) ==
        RadiancePrecision::Float);
  // An emitter: its brightest channel.
  CHECK(resolvedPrecision(boxWith(lightOf(Light::Type::Point, 0.0f), glm::vec3(0.0f, 1e6f, 0.0f))) ==
        RadiancePrecision::Float);
  // Asked for, not auto: kept.
  RenderSettings half;
  half.radiancePrecision = RadiancePrecision::Half;
  CHECK(*resolveSettings(half, boxWith(lightOf(Light::Type::Directional, 1e9f))).radiancePrecision ==
        RadiancePrecision::Half);
}

TEST_CASE("frame plan: float radiance makes exactly the light-holding attachments float32") {
  Scene scene = boxWith(lightOf(Light::Type::Directional, 1.0f), glm::vec3(1.0f));
  for (const RadiancePrecision precision : {RadiancePrecision::Half, RadiancePrecision::Float}) {
    RenderSettings settings;
    settings.radiancePrecision = precision;
    const FramePlan plan = planFrame(summarizeScene(scene), resolveSettings(settings, scene), {});
    for (const AttachmentRow& row : attachmentRows()) {
      CAPTURE(row.name);
      const bool floatLight = row.radiance && precision == RadiancePrecision::Float;
      CHECK(plan.formatOf(row.id) == (floatLight ? GpuFormat::Rgba32F : row.format));
    }
  }
  // The rows that hold light: the images made of it, never the G-buffer's surface data.
  for (const Attachment id : {Attachment::Lit, Attachment::GbufferEmissive, Attachment::DirectTowardEye,
                              Attachment::DirectDiffuse, Attachment::Ssgi, Attachment::SsgiRaw})
    CHECK(attachmentRow(id).radiance);
  for (const Attachment id : {Attachment::GbufferPosition, Attachment::GbufferNormal, Attachment::GbufferAlbedo,
                              Attachment::GbufferMaterial, Attachment::GbufferDepth, Attachment::SsgiSky})
    CHECK(!attachmentRow(id).radiance);
}

}  // namespace headlight

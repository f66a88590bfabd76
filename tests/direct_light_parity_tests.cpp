// GPU against CPU on direct light: a small scene lit only by punctual lights
// (no SSGI, sky intensity 0) is rendered, and every covered pixel of `lit`
// is compared with the CPU ports of the GLSL (lib/reference/shading.hpp)
// evaluated on the G-buffer read back. With no ambient term, lit is the
// direct-light pass's output; a difference beyond storage precision is a
// port that no longer says what the shader says (or the other way round).
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "context/context_access.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/shapes.hpp"
#include "reference/shading.hpp"
#include "support/gl.hpp"
#include "support/parity.hpp"

using namespace headlight;

namespace {

// A floor, a rough dielectric sphere and a half-metal sphere, lit by one
// light of each kind, none casting shadows (the shadow maps are the GPU's
// own business and have no CPU port). Base colours are 0 or 1 per channel:
// the G-buffer's albedo is sRGB8, which the shader decodes with llvmpipe's
// approximation and the readback with the exact curve; they differ by up to
// 0.7% in between, and agree at 0 and 1.
Scene directOnlyScene() {
  Scene scene;
  scene.source = "test:direct-only";
  scene.sky.intensity = 0.0f;
  addInstance(scene, makeFloor(4.0f), addMaterial(scene, makeMaterial({1.0f, 1.0f, 1.0f}, 0.8f)));
  addInstance(scene, makeUvSphere(0.6f, 48, 24), addMaterial(scene, makeMaterial({1.0f, 0.0f, 0.0f}, 0.35f)),
              moved({-0.8f, 0.6f, 0.0f}));
  addInstance(scene, makeUvSphere(0.5f, 48, 24), addMaterial(scene, makeMaterial({1.0f, 1.0f, 0.0f}, 0.5f, 0.6f)),
              moved({0.8f, 0.5f, 0.3f}));
  scene.cameras.push_back(makeLookAtCamera({0.0f, 2.2f, 4.5f}, {0.0f, 0.4f, 0.0f}, 0.7f));

  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = {-0.3f, -1.0f, -0.5f};  // not unit: packLights and the port both normalise
  sun.intensity = 2.0f;
  sun.color = {1.0f, 0.95f, 0.9f};
  Light point;
  point.type = Light::Type::Point;
  point.position = {1.5f, 1.5f, 1.5f};
  point.intensity = 8.0f;
  point.range = 6.0f;  // the range window is on inside the frame
  point.color = {0.6f, 0.8f, 1.0f};
  Light spot;
  spot.type = Light::Type::Spot;
  spot.position = {-1.0f, 2.5f, 1.0f};
  spot.direction = {0.3f, -1.0f, -0.4f};
  spot.intensity = 15.0f;
  spot.innerConeAngle = 0.25f;
  spot.outerConeAngle = 0.5f;
  for (Light light : {sun, point, spot}) {
    light.castsShadows = false;
    scene.lights.push_back(light);
  }
  return scene;
}

}  // namespace

TEST_CASE("direct light on the GPU matches the CPU ports per pixel") {
  const Scene scene = directOnlyScene();
  RenderSettings settings = test::smallSettings(96, 72);
  settings.ssgi.enabled = false;
  Renderer renderer(test::sharedContext());
  renderer.setScene(scene);
  const Frame frame = renderer.render(settings);
  REQUIRE(frame.view.orthographic == false);

  // 2e-3 relative: the direct and lit targets are RGBA16F, 10 mantissa
  // bits, and llvmpipe's conversion can leave a value up to 2^-10 (9.8e-4)
  // low; twice that leaves room for its float pow/normalize against the C
  // library's. 1e-5 absolute: where the spot's cone or N.L makes a value tiny.
  test::ParityTally tally{2e-3f, 1e-5f};
  int covered = 0, lit = 0;
  for (int y = 0; y < frame.lit.height; ++y)
    for (int x = 0; x < frame.lit.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      ++covered;
      const glm::vec3 position = test::pixel3(frame.position, x, y);
      const reference::Surface surface = reference::makeSurface(
          test::pixel3(frame.albedo, x, y), frame.material.at(x, y, 0), frame.material.at(x, y, 1),
          test::pixel3(frame.normal, x, y), glm::normalize(frame.view.position - position));
      const glm::vec3 expected = test::punctualLight(
          scene, position, [&](const glm::vec3& toLight) { return reference::cookTorrance(surface, toLight); });
      tally.compare(x, y, test::pixel3(frame.lit, x, y), expected);
      lit += expected.r + expected.g + expected.b > 1e-3f;
    }
  MESSAGE("direct light: " << covered << " covered pixels, " << lit << " lit, worst relative error "
                          << tally.worstRelative);
  CHECK(tally.outside == 0);
  // The scene does what it is for: most of the frame is geometry, and lit.
  CHECK(covered > frame.lit.width * frame.lit.height / 2);
  CHECK(lit > covered / 2);
  CHECK(headlight::detail::ContextAccess::pendingErrorCount(test::sharedContext()) == 0);
}

// GPU against CPU on the specular and clearcoat lobes (KHR_materials_ior,
// _specular, _clearcoat), in the style of direct_light_parity_tests.cpp: a
// small scene lit only by punctual lights (no SSGI, sky intensity 0) is
// rendered, and every covered pixel of `lit` is compared with the CPU ports
// (lib/reference/shading.hpp, lobe_specular.hpp, lobe_clearcoat.hpp)
// evaluated on the G-buffer and lobe targets read back. A difference beyond
// storage precision is a port that no longer says what the shader says.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "context/context_access.hpp"
#include "headlight/reference.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/shapes.hpp"
#include "reference/lobe_clearcoat.hpp"
#include "reference/lobe_specular.hpp"
#include "reference/shading.hpp"
#include "support/gl.hpp"
#include "support/parity.hpp"

using namespace headlight;

namespace {

// A floor without either extension, a red dielectric with a coloured
// specular lobe and IOR 1.8, a half-metal under a clear coat, and a sphere
// with both. Base colours are 0 or 1 per channel (direct_light_parity_tests.cpp
// says why); the lobes' factors are plain numbers (half floats in their targets,
// read back as the shader read them).
Scene layeredScene() {
  Scene scene;
  scene.source = "test:layers";
  scene.sky.intensity = 0.0f;
  addInstance(scene, makeFloor(4.0f), addMaterial(scene, makeMaterial({1.0f, 1.0f, 1.0f}, 0.8f)));
  Material specular = makeMaterial({1.0f, 0.0f, 0.0f}, 0.35f);
  specular.ior = 1.8f;
  specular.specular = MaterialSpecular{};
  specular.specular->specularFactor = 0.6f;
  specular.specular->specularColorFactor = {1.0f, 0.5f, 0.25f};
  addInstance(scene, makeUvSphere(0.6f, 48, 24), addMaterial(scene, specular), moved({-1.0f, 0.6f, 0.0f}));
  Material coated = makeMaterial({1.0f, 1.0f, 0.0f}, 0.5f, 0.6f);
  coated.clearcoat = MaterialClearcoat{};
  coated.clearcoat->clearcoatFactor = 0.9f;
  coated.clearcoat->clearcoatRoughnessFactor = 0.3f;
  addInstance(scene, makeUvSphere(0.5f, 48, 24), addMaterial(scene, coated), moved({0.3f, 0.5f, 0.3f}));
  Material both = makeMaterial({0.0f, 0.0f, 1.0f}, 0.7f);
  both.specular = MaterialSpecular{};
  both.specular->specularFactor = 0.3f;
  both.clearcoat = MaterialClearcoat{};
  both.clearcoat->clearcoatFactor = 0.5f;
  both.clearcoat->clearcoatRoughnessFactor = 0.5f;
  addInstance(scene, makeUvSphere(0.4f, 48, 24), addMaterial(scene, both), moved({1.3f, 0.4f, -0.4f}));
  scene.cameras.push_back(makeLookAtCamera({0.0f, 2.2f, 4.5f}, {0.2f, 0.4f, 0.0f}, 0.7f));

  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = {-0.3f, -1.0f, -0.5f};
  sun.intensity = 2.0f;
  Light point;
  point.type = Light::Type::Point;
  point.position = {1.5f, 1.5f, 1.5f};
  point.intensity = 8.0f;
  point.color = {0.6f, 0.8f, 1.0f};
  for (Light light : {sun, point}) {
    light.castsShadows = false;
    scene.lights.push_back(light);
  }
  return scene;
}

// The punctual lights through the coat over the base (direct_light.frag's
// layering, lib/reference/lobe_clearcoat.hpp).
glm::vec3 coatedDirectLight(const Scene& scene, const glm::vec3& position, const reference::Surface& surface,
                            const reference::Clearcoat& coat, const glm::vec3& view) {
  return test::punctualLight(scene, position, [&](const glm::vec3& toLight) {
    return reference::clearcoatLayer(coat, reference::cookTorrance(surface, toLight),
                                     glm::vec3(reference::clearcoatSpecular(coat, view, toLight)));
  });
}

}  // namespace

TEST_CASE("octahedral normals: encoded and decoded to within 1e-6 on both sides of the equator") {
  for (const glm::vec3 n : {glm::vec3(0, 0, 1), glm::vec3(0, 0, -1), glm::vec3(1, 0, 0), glm::vec3(0.3f, -0.5f, 0.8f),
                            glm::vec3(-0.6f, 0.2f, -0.7f), glm::vec3(0.1f, 0.9f, -0.2f)}) {
    const glm::vec3 unit = glm::normalize(n);
    const glm::vec2 e = reference::octahedralEncode(unit);
    CAPTURE(unit.x);
    CAPTURE(unit.y);
    CAPTURE(unit.z);
    CHECK(std::abs(e.x) <= 1.0f);
    CHECK(std::abs(e.y) <= 1.0f);
    CHECK(glm::length(reference::octahedralDecode(e) - unit) < 1e-6f);
  }
}

TEST_CASE("specular and clearcoat lobes on the GPU match the CPU ports per pixel") {
  const Scene scene = layeredScene();
  RenderSettings settings = test::smallSettings(96, 72);
  settings.ssgi.enabled = false;
  Renderer renderer(test::sharedContext());
  renderer.setScene(scene);
  const Frame frame = renderer.render(settings);
  REQUIRE(!frame.specular.empty());
  REQUIRE(!frame.clearcoat.empty());
  REQUIRE(frame.specular.channelCount() == 4);
  REQUIRE(frame.clearcoat.channelCount() == 4);

  // As direct_light_parity_tests.cpp: RGBA16F targets, llvmpipe's float
  // pow/normalize against the C library's.
  test::ParityTally tally{2e-3f, 1e-5f};
  int covered = 0, coated = 0, tinted = 0;
  float worstNormal = 0.0f;
  for (int y = 0; y < frame.lit.height; ++y)
    for (int x = 0; x < frame.lit.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      ++covered;
      const glm::vec3 position = test::pixel3(frame.position, x, y), normal = test::pixel3(frame.normal, x, y);
      const glm::vec3 view = glm::normalize(frame.view.position - position);
      reference::Surface surface = reference::makeSurface(test::pixel3(frame.albedo, x, y), frame.material.at(x, y, 0),
                                                          frame.material.at(x, y, 1), normal, view);
      const glm::vec4 specularLobe = test::pixel4(frame.specular, x, y);
      const glm::vec4 clearcoatLobe = test::pixel4(frame.clearcoat, x, y);
      reference::applyLobe(surface, Lobe::Specular, specularLobe);
      const reference::Clearcoat coat = reference::makeClearcoat(clearcoatLobe, view);
      coated += coat.factor > 0.0f;
      tinted += specularLobe.r != specularLobe.b;
      // No clearcoat normal map: the coat's normal is the surface's.
      worstNormal = std::max(worstNormal, glm::length(coat.normal - normal));
      const glm::vec3 expected = coatedDirectLight(scene, position, surface, coat, view);
      tally.compare(x, y, test::pixel3(frame.lit, x, y), expected);
    }
  MESSAGE("lobes: " << covered << " covered pixels, " << coated << " coated, " << tinted
                    << " with a coloured F0, worst relative error " << tally.worstRelative);
  CHECK(tally.outside == 0);
  // 2e-3: the normal target and the coat's octahedral pair are both half floats.
  CHECK(worstNormal < 2e-3f);
  // The scene does what it is for: both lobes cover a good part of the frame.
  CHECK(coated > covered / 10);
  CHECK(tinted > covered / 20);
  CHECK(headlight::detail::ContextAccess::pendingErrorCount(test::sharedContext()) == 0);
}

TEST_CASE("a blended material with both lobes is lit by the blend pass's lobe variant") {
  Scene scene = layeredScene();
  scene.sky.intensity = 1.0f;  // the blend pass's ambient term, the coat's included
  Material& both = scene.materials.back();
  both.alphaMode = AlphaMode::Blend;
  both.baseColorFactor.a = 0.5f;
  RenderSettings settings = test::smallSettings(64, 48);
  const Frame blended = test::renderFresh(scene, settings);
  both.specular.reset();
  both.clearcoat.reset();
  const Frame plain = test::renderFresh(scene, settings);
  REQUIRE(!blended.coverage.empty());
  // The lobes change the blended sphere's light, and only where it is.
  double changed = 0.0;
  int covered = 0;
  for (int y = 0; y < blended.lit.height; ++y)
    for (int x = 0; x < blended.lit.width; ++x) {
      for (int c = 0; c < 3; ++c) CHECK(std::isfinite(blended.lit.at(x, y, c)));
      const float difference = std::abs(blended.lit.at(x, y, 0) - plain.lit.at(x, y, 0));
      if (blended.coverage.at(x, y, 0) == 0.0f) {
        // Elsewhere only the other spheres' own lobes differ: none (the scene keeps them).
        CHECK(difference <= 1e-6f);
        continue;
      }
      ++covered;
      changed += difference;
    }
  REQUIRE(covered > 20);
  CHECK(changed / covered > 1e-3);
}

TEST_CASE("the Embree reference shades both lobes with the CPU ports" * doctest::skip(!referenceAvailable())) {
  const Scene scene = layeredScene();  // sky 0, no shadows: its lit is direct light + one-bounce indirect
  RenderSettings settings = test::smallSettings(48, 36);
  settings.ssgi.enabled = false;
  const Frame frame = test::renderFresh(scene, settings);
  ReferenceSettings reference;
  reference.samplesPerPixel = 4;
  reference.radius = 1.0f;
  const ReferenceImages images = traceReference(scene, frame, reference);
  // The reference's lit is the lobes' direct light, from the G-buffer with
  // its normal renormalized (a half-float normal is up to ~5e-4 short, which
  // moves a highlight by a few percent: why this is not the renderer's lit),
  // plus the one-bounce light under the coat, (1 - c Fc) indirect.
  int compared = 0, coated = 0;
  for (int y = 0; y < frame.lit.height; ++y)
    for (int x = 0; x < frame.lit.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      ++compared;
      const glm::vec3 position = test::pixel3(frame.position, x, y);
      const glm::vec3 view = glm::normalize(frame.view.position - position);
      reference::Surface surface =
          reference::makeSurface(test::pixel3(frame.albedo, x, y), frame.material.at(x, y, 0),
                                 frame.material.at(x, y, 1), glm::normalize(test::pixel3(frame.normal, x, y)), view);
      reference::applyLobe(surface, Lobe::Specular, test::pixel4(frame.specular, x, y));
      const reference::Clearcoat coat = reference::makeClearcoat(test::pixel4(frame.clearcoat, x, y), view);
      coated += coat.weight > 0.0f;
      const glm::vec3 expected = coatedDirectLight(scene, position, surface, coat, view);
      for (int c = 0; c < 3; ++c) {
        CAPTURE(x);
        CAPTURE(y);
        CAPTURE(c);
        // 1e-4: the same float functions, summed in another order.
        CHECK(images.lit.at(x, y, c) ==
              doctest::Approx(expected[c] + (1.0f - coat.weight) * images.indirect.at(x, y, 3 + c)).epsilon(1e-4));
      }
    }
  CHECK(compared > frame.lit.width * frame.lit.height / 2);
  CHECK(coated > compared / 10);
}

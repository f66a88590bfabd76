// GPU against CPU on KHR_materials_iridescence's thin-film Fresnel, in the
// style of tests/direct_light_parity_tests.cpp: a scene lit only by punctual
// lights (no SSGI, sky intensity 0), so lit is the direct-light pass's
// output, compared per covered pixel with the CPU port
// (lib/reference/lobe_iridescence.hpp through shading.hpp's cookTorrance)
// evaluated on the G-buffer read back, iridescence.exr included. Then the
// ambient term (ambient.glsl), under the sky alone, without needing the
// split-sum table on the CPU: a white metal's specular albedo is the table's
// A + B, so a filmed metal's ambient must be the port's film Fresnel times
// the white metal's, pixel by pixel.
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

Material iridescent(glm::vec3 color, float roughness, float metallic, float strength, float thicknessNm,
                    float filmIor, float baseIor) {
  Material material = makeMaterial(color, roughness, metallic);
  material.ior = baseIor;
  MaterialIridescence film;
  film.iridescenceFactor = strength;
  film.iridescenceIor = filmIor;
  film.iridescenceThicknessMaximum = thicknessNm;  // no thickness texture: the maximum (specification)
  material.iridescence = film;
  return material;
}

// A floor without the extension (its pixels write "no film"), a dielectric
// sphere with a full-strength film on a base of IOR 2 (IridescenceSuzanne's
// left), and a half-metal sphere with a half-strength thicker film. Base
// colours 0 or 1 per channel, as in the direct-light parity test (sRGB8
// albedo decodes exactly there).
Scene iridescentScene() {
  Scene scene;
  scene.source = "test:iridescence-direct";
  scene.sky.intensity = 0.0f;
  addInstance(scene, makeFloor(4.0f), addMaterial(scene, makeMaterial({1.0f, 1.0f, 1.0f}, 0.8f)));
  addInstance(scene, makeUvSphere(0.6f, 48, 24),
              addMaterial(scene, iridescent({1.0f, 0.0f, 0.0f}, 0.3f, 0.0f, 1.0f, 400.0f, 1.33f, 2.0f)),
              moved({-0.8f, 0.6f, 0.0f}));
  addInstance(scene, makeUvSphere(0.5f, 48, 24),
              addMaterial(scene, iridescent({1.0f, 1.0f, 0.0f}, 0.4f, 0.5f, 0.5f, 650.0f, 1.8f, 1.5f)),
              moved({0.8f, 0.5f, 0.3f}));
  scene.cameras.push_back(makeLookAtCamera({0.0f, 2.2f, 4.5f}, {0.0f, 0.4f, 0.0f}, 0.7f));
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

// The CPU surface of a pixel: makeSurface on the read-back G-buffer, then
// the film from iridescence.exr.
reference::Surface cpuSurface(const Frame& frame, int x, int y) {
  const glm::vec3 position = test::pixel3(frame.position, x, y);
  reference::Surface surface =
      reference::makeSurface(test::pixel3(frame.albedo, x, y), frame.material.at(x, y, 0), frame.material.at(x, y, 1),
                             test::pixel3(frame.normal, x, y), glm::normalize(frame.view.position - position));
  reference::applyLobe(surface, Lobe::Iridescence, reference::filmValue(reference::iridescenceInputsAt(frame, x, y)));
  return surface;
}

}  // namespace

TEST_CASE("iridescent direct light on the GPU matches the CPU port per pixel") {
  const Scene scene = iridescentScene();
  RenderSettings settings = test::smallSettings(96, 72);
  settings.ssgi.enabled = false;
  Renderer renderer(test::sharedContext());
  renderer.setScene(scene);
  const Frame frame = renderer.render(settings);
  REQUIRE(!frame.iridescence.empty());

  // As the direct-light parity test: 2e-3 relative for half storage and
  // llvmpipe's float functions, 1e-5 absolute where a value is tiny; the
  // film adds cos and exp of arguments up to ~25 rad, where llvmpipe's
  // and the C library's float results agree to a few ulps.
  test::ParityTally tally{2e-3f, 1e-5f};
  int covered = 0, filmed = 0;
  for (int y = 0; y < frame.lit.height; ++y)
    for (int x = 0; x < frame.lit.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      ++covered;
      filmed += frame.iridescence.at(x, y, 0) > 0.0f;
      const reference::Surface surface = cpuSurface(frame, x, y);
      const glm::vec3 expected =
          test::punctualLight(scene, test::pixel3(frame.position, x, y),
                              [&](const glm::vec3& toLight) { return reference::cookTorrance(surface, toLight); });
      tally.compare(x, y, test::pixel3(frame.lit, x, y), expected);
    }
  MESSAGE("iridescent direct light: " << covered << " covered, " << filmed << " with a film, worst relative error "
                                      << tally.worstRelative);
  CHECK(tally.outside == 0);
  // Both spheres are in the frame with their films, and the floor without.
  CHECK(filmed > covered / 10);
  CHECK(filmed < covered);
  CHECK(headlight::detail::ContextAccess::pendingErrorCount(test::sharedContext()) == 0);
}

namespace {

// A metal sphere under the default sky alone: a light of intensity 0 keeps
// the renderer's default key light away, SSGI is off (sky visibility 1).
Scene skyLitSphere(const Material& material) {
  Scene scene;
  scene.source = "test:iridescence-ambient";
  addInstance(scene, makeUvSphere(0.8f, 64, 32), addMaterial(scene, material));
  scene.cameras.push_back(makeLookAtCamera({0.0f, 0.8f, 3.0f}, {0.0f, 0.0f, 0.0f}, 0.8f));
  Light dark;
  dark.type = Light::Type::Directional;
  dark.direction = {0.0f, -1.0f, 0.0f};
  dark.intensity = 0.0f;
  dark.castsShadows = false;
  scene.lights.push_back(dark);
  return scene;
}

}  // namespace

TEST_CASE("iridescent ambient light on the GPU is the CPU port's film Fresnel times the split-sum integral") {
  RenderSettings settings = test::smallSettings(64, 64);
  settings.ssgi.enabled = false;
  // Base colours 0 or 1 (exact through sRGB8). Metal: no diffuse term, and
  // the specular albedo f0 A + B of a white base is A + B.
  const Material white = makeMaterial({1.0f, 1.0f, 1.0f}, 0.25f, 1.0f);
  const Material filmed = iridescent({1.0f, 0.0f, 1.0f}, 0.25f, 1.0f, 1.0f, 400.0f, 1.33f, 1.5f);
  const Frame whiteFrame = test::renderFresh(skyLitSphere(white), settings);
  const Frame frame = test::renderFresh(skyLitSphere(filmed), settings);
  REQUIRE(!frame.iridescence.empty());
  // Half storage of both lits (2^-11 each) and the film's parity above (1e-3).
  test::ParityTally tally{4e-3f, 1e-5f};
  int compared = 0;
  for (int y = 0; y < frame.lit.height; ++y)
    for (int x = 0; x < frame.lit.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      ++compared;
      const reference::Surface surface = cpuSurface(frame, x, y);
      tally.compare(x, y, test::pixel3(frame.lit, x, y),
                    glm::vec3(surface.value(Lobe::Iridescence)) * test::pixel3(whiteFrame.lit, x, y));
    }
  MESSAGE("iridescent ambient light: " << compared << " pixels, worst relative error " << tally.worstRelative);
  CHECK(tally.outside == 0);
  CHECK(compared > 64 * 64 / 4);
}

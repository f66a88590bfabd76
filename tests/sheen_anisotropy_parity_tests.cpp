// GPU against CPU on the sheen and anisotropy lobes' direct light, in the
// style of direct_light_parity_tests.cpp: spheres with each lobe, lit only
// by punctual lights (no SSGI, sky intensity 0), and every covered pixel of
// `lit` compared with the CPU ports (lib/reference/shading.hpp with
// lobe_sheen.hpp and lobe_anisotropy.hpp) evaluated on the G-buffer read
// back, the lobe's target included. A difference beyond storage precision is
// a port that no longer says what the shader says.
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

// Two lights from the front and from behind the spheres (the back light
// makes the grazing rims sheen is about), neither casting shadows (the maps
// have no CPU port). Colours 0 or 1 per channel: sRGB8 targets (albedo,
// sheen colour) decode exactly there on both sides.
Scene lobeScene(const std::vector<Material>& sphereMaterials) {
  Scene scene;
  scene.source = "test:lobe-parity";
  scene.sky.intensity = 0.0f;
  addInstance(scene, makeFloor(4.0f), addMaterial(scene, makeMaterial({1.0f, 1.0f, 1.0f}, 0.8f)));
  float x = -1.2f;
  for (const Material& material : sphereMaterials) {
    addInstance(scene, makeUvSphere(0.5f, 48, 24), addMaterial(scene, material), moved({x, 0.5f, 0.0f}));
    x += 1.2f;
  }
  scene.cameras.push_back(makeLookAtCamera({0.0f, 1.6f, 4.0f}, {0.0f, 0.4f, 0.0f}, 0.75f));
  Light front;
  front.type = Light::Type::Directional;
  front.direction = {-0.3f, -0.8f, -0.5f};
  front.intensity = 2.0f;
  Light back;
  back.type = Light::Type::Point;
  back.position = {0.5f, 1.8f, -1.5f};
  back.intensity = 10.0f;
  back.color = {0.8f, 0.9f, 1.0f};
  for (Light light : {front, back}) {
    light.castsShadows = false;
    scene.lights.push_back(light);
  }
  return scene;
}

struct ParityCount {
  int covered = 0, lit = 0;
  test::ParityTally tally;
};

// Every covered pixel of `frame`'s lit against the port's direct light on
// the read-back G-buffer, `lobes` filling in the surface's lobe inputs.
template <class Lobes>
ParityCount compareDirectLight(const Scene& scene, const Frame& frame, Lobes lobes) {
  // As direct_light_parity_tests.cpp: RGBA16F lit, 2^-10 plus llvmpipe's
  // float pow/exp/normalize against the C library's; the sheen lobe's
  // exp of a ~17 exponent adds a few float ulps of it.
  ParityCount count{.tally = {2e-3f, 1e-5f}};
  for (int y = 0; y < frame.lit.height; ++y)
    for (int x = 0; x < frame.lit.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      ++count.covered;
      const glm::vec3 position = test::pixel3(frame.position, x, y);
      reference::Surface surface = reference::makeSurface(test::pixel3(frame.albedo, x, y), frame.material.at(x, y, 0),
                                                          frame.material.at(x, y, 1), test::pixel3(frame.normal, x, y),
                                                          glm::normalize(frame.view.position - position));
      lobes(surface, x, y);
      const glm::vec3 expected = test::punctualLight(
          scene, position, [&](const glm::vec3& toLight) { return reference::cookTorrance(surface, toLight); });
      count.tally.compare(x, y, test::pixel3(frame.lit, x, y), expected);
      count.lit += expected.r + expected.g + expected.b > 1e-3f;
    }
  return count;
}

Frame renderDirectOnly(const Scene& scene) {
  RenderSettings settings = test::smallSettings(96, 64);
  settings.ssgi.enabled = false;
  Renderer renderer(test::sharedContext());
  renderer.setScene(scene);
  return renderer.render(settings);
}

Material withSheen(const glm::vec3& base, float roughness, const glm::vec3& sheenColor, float sheenRoughness) {
  Material material = makeMaterial(base, roughness);
  material.sheen = MaterialSheen{};
  material.sheen->sheenColorFactor = sheenColor;
  material.sheen->sheenRoughnessFactor = sheenRoughness;
  return material;
}

}  // namespace

TEST_CASE("sheen: direct light on the GPU matches the CPU ports per pixel") {
  // The floor has no sheen: it writes the no-effect values and must light as before.
  const Scene scene = lobeScene({withSheen({0.0f, 0.0f, 1.0f}, 0.7f, {1.0f, 1.0f, 1.0f}, 0.3f),
                                 withSheen({1.0f, 0.0f, 0.0f}, 0.5f, {1.0f, 1.0f, 0.0f}, 0.6f),
                                 withSheen({0.0f, 0.0f, 0.0f}, 0.9f, {0.0f, 1.0f, 1.0f}, 1.0f)});
  const Frame frame = renderDirectOnly(scene);
  REQUIRE(!frame.sheen.empty());
  int sheened = 0;
  const ParityCount count = compareDirectLight(scene, frame, [&](reference::Surface& surface, int x, int y) {
    reference::applyLobe(surface, Lobe::Sheen, test::pixel4(frame.sheen, x, y));
    sheened += glm::vec3(surface.value(Lobe::Sheen)) != glm::vec3(0.0f);
  });
  MESSAGE("sheen: " << count.covered << " covered pixels, " << sheened << " with sheen, " << count.lit
                    << " lit, worst relative error " << count.tally.worstRelative);
  CHECK(count.tally.outside == 0);
  CHECK(sheened > count.covered / 5);  // the spheres are in view, and their sheen reached the target
  CHECK(count.lit > count.covered / 2);
  CHECK(headlight::detail::ContextAccess::pendingErrorCount(test::sharedContext()) == 0);
}

namespace {

Material withAnisotropy(const glm::vec3& base, float roughness, float metallic, float strength, float rotation) {
  Material material = makeMaterial(base, roughness, metallic);
  material.anisotropy = MaterialAnisotropy{};
  material.anisotropy->anisotropyStrength = strength;
  material.anisotropy->anisotropyRotation = rotation;
  return material;
}

}  // namespace

TEST_CASE("anisotropy: direct light on the GPU matches the CPU ports per pixel") {
  // The spheres have no TANGENT: their frame comes from the UV derivatives
  // (gbuffer.frag), and the target holds the direction it gave.
  const Scene scene = lobeScene({withAnisotropy({1.0f, 1.0f, 1.0f}, 0.3f, 1.0f, 0.8f, 0.0f),
                                 withAnisotropy({1.0f, 0.0f, 0.0f}, 0.5f, 0.0f, 0.5f, 1.0f),
                                 withAnisotropy({1.0f, 1.0f, 0.0f}, 0.15f, 1.0f, 1.0f, -0.7f)});
  const Frame frame = renderDirectOnly(scene);
  REQUIRE(!frame.anisotropy.empty());
  int stretched = 0;
  const ParityCount count = compareDirectLight(scene, frame, [&](reference::Surface& surface, int x, int y) {
    reference::applyLobe(surface, Lobe::Anisotropy, test::pixel4(frame.anisotropy, x, y));
    stretched += surface.value(Lobe::Anisotropy).w > 0.0f;
  });
  MESSAGE("anisotropy: " << count.covered << " covered pixels, " << stretched << " anisotropic, " << count.lit
                         << " lit, worst relative error " << count.tally.worstRelative);
  CHECK(count.tally.outside == 0);
  CHECK(stretched > count.covered / 5);
  CHECK(count.lit > count.covered / 2);
  CHECK(headlight::detail::ContextAccess::pendingErrorCount(test::sharedContext()) == 0);
}

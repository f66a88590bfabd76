// Shadows through transmissive casters (lib/passes/shadow.hpp's
// transmittance maps, glsl/shadow_transmittance.glsl): a glass pane and a
// tinted glass slab over a white floor, lit by one light at 45 degrees, no
// sky and no SSGI, seen from straight above. Where the light reaches the
// floor through the caster, lit with the caster over lit without it is what
// the caster lets through: the CPU port's shadowCrossing (and, in the slab,
// Beer-Lambert over the straight path between its faces). Before the maps,
// every transmissive caster was opaque to its lights (ratio 0).
#include <doctest/doctest.h>

#include <cmath>
#include <vector>

#include "context/context_access.hpp"
#include "headlight/reference.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/shapes.hpp"
#include "reference/lobe_transmission.hpp"
#include "support/gl.hpp"
#include "support/parity.hpp"

using namespace headlight;

namespace {

enum class Caster { None, Pane, Slab };

constexpr float kIor = 1.5f;
const glm::vec3 kPaneColour{1.0f, 0.5f, 0.2f};
constexpr float kSlabThickness = 0.1f, kSlabAttenuationDistance = 0.2f;
const glm::vec3 kSlabAttenuationColour{0.2f, 0.6f, 0.9f};
// The caster's centre: the light at 45 degrees (directional) casts its
// shadow 0.6 further along +x, clear of the caster's own footprint.
const glm::vec3 kCasterCentre{-0.9f, 0.6f, 0.0f};
const glm::vec3 kPointLight{-1.5f, 1.2f, 0.0f};  // twice the caster's height: its shadow twice its size

Scene shadowScene(Caster caster, Light::Type lightType) {
  Scene scene;
  scene.source = "test:shadow-transmittance";
  scene.sky.intensity = 0.0f;
  addInstance(scene, makeFloor(2.0f), addMaterial(scene, makeMaterial({1.0f, 1.0f, 1.0f}, 0.8f)));
  if (caster == Caster::Pane) {
    // Thin-walled: the base colour tints at its one crossing.
    Material glass = makeMaterial(kPaneColour, 0.1f);
    glass.transmission = MaterialTransmission{1.0f, {}};
    glass.ior = kIor;
    addInstance(scene, makeSquare(kCasterCentre, {0, 1, 0}, 0.25f), addMaterial(scene, glass));
  } else if (caster == Caster::Slab) {
    // A volume: light crosses its top and bottom faces and the medium between.
    Material glass = makeMaterial({1.0f, 1.0f, 1.0f}, 0.1f);
    glass.transmission = MaterialTransmission{1.0f, {}};
    glass.volume = MaterialVolume{kSlabThickness, {}, kSlabAttenuationDistance, kSlabAttenuationColour};
    glass.ior = kIor;
    addInstance(scene, makeBox({0.6f, kSlabThickness, 0.6f}), addMaterial(scene, glass), moved(kCasterCentre));
  }
  scene.cameras.push_back(makeLookAtCamera({-0.3f, 3.0f, 0.01f}, {-0.3f, 0.0f, 0.0f}, 0.9f));
  Light light;
  light.type = lightType;
  light.intensity = lightType == Light::Type::Directional ? 3.0f : 6.0f;
  light.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
  light.position = kPointLight;
  light.castsShadows = true;
  scene.lights.push_back(light);
  return scene;
}

RenderSettings settings() {
  RenderSettings s = test::smallSettings(96, 96);
  s.ssgi.enabled = false;
  return s;
}

// Where the light's path to the floor point `p` crosses the caster's
// plane y = kCasterCentre.y, and the cosine there with the plane's normal.
struct Crossing {
  glm::vec3 point;
  float cosine;
};
Crossing crossingTowardLight(const glm::vec3& p, Light::Type type) {
  const glm::vec3 toLight = type == Light::Type::Directional ? -glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f))
                                                             : glm::normalize(kPointLight - p);
  return {p + toLight * (kCasterCentre.y / toLight.y), toLight.y};
}

// What the caster lets through to floor point `p` by the CPU ports, or -1
// where `p` is not in the core of its shadow (every PCF tap and both faces'
// crossings inside the caster, `margin` from its edges).
glm::vec3 expectedTransmittance(Caster caster, Light::Type type, const glm::vec3& p, float margin) {
  const Crossing at = crossingTowardLight(p, type);
  const float half = caster == Caster::Pane ? 0.25f : 0.3f - kSlabThickness;  // the slab's faces shift by 0.05 each
  if (std::abs(at.point.x - kCasterCentre.x) > half - margin || std::abs(at.point.z) > half - margin)
    return glm::vec3(-1.0f);
  if (caster == Caster::Pane) return reference::shadowCrossing(kPaneColour, 0.0f, 1.0f, kIor, at.cosine, true);
  const glm::vec3 extinction = reference::volumeExtinction(kSlabAttenuationColour, kSlabAttenuationDistance);
  const float path = kSlabThickness / at.cosine;
  return reference::shadowCrossing(glm::vec3(1.0f), 0.0f, 1.0f, kIor, at.cosine, true) *
         reference::shadowCrossing(glm::vec3(1.0f), 0.0f, 1.0f, kIor, at.cosine, false) * glm::exp(-extinction * path);
}

struct Compared {
  int pixels = 0, outside = 0;
  glm::vec3 meanRatio{0.0f};
};

// lit(caster) / lit(no caster) against the ports over the shadow's core.
Compared compareShadow(Caster caster, Light::Type type) {
  const Frame with = test::renderFresh(shadowScene(caster, type), settings());
  const Frame without = test::renderFresh(shadowScene(Caster::None, type), settings());
  // lit's half floats (2e-3) and the floor's sRGB8 albedo, the same in both.
  constexpr float kRelative = 5e-3f, kAbsolute = 2e-3f;
  Compared result;
  for (int y = 0; y < with.lit.height; ++y)
    for (int x = 0; x < with.lit.width; ++x) {
      const glm::vec3 p = test::pixel3(with.position, x, y);
      if (with.position.at(x, y, 3) == 0.0f || std::abs(p.y) > 1e-3f) continue;  // the floor only
      const glm::vec3 expected = expectedTransmittance(caster, type, p, 0.06f);
      if (expected.x < 0.0f) continue;
      ++result.pixels;
      for (int c = 0; c < 3; ++c) {
        const float open = without.lit.at(x, y, c);
        REQUIRE(open > 0.01f);
        const float ratio = with.lit.at(x, y, c) / open;
        result.meanRatio[c] += ratio;
        if (std::abs(ratio - expected[c]) <= kRelative * expected[c] + kAbsolute) continue;
        if (++result.outside <= 5) {
          CAPTURE(x);
          CAPTURE(y);
          CAPTURE(c);
          CHECK(ratio == doctest::Approx(expected[c]).epsilon(kRelative));
        }
      }
    }
  if (result.pixels > 0) result.meanRatio /= float(result.pixels);
  CHECK(headlight::detail::ContextAccess::pendingErrorCount(test::sharedContext()) == 0);
  return result;
}

}  // namespace

TEST_CASE("shadow transmittance: a glass pane tints its directional light's shadow by its colour and Fresnel") {
  const Compared compared = compareShadow(Caster::Pane, Light::Type::Directional);
  MESSAGE("pane, directional: " << compared.pixels << " core pixels, mean ratio " << compared.meanRatio.x << ", "
                                << compared.meanRatio.y << ", " << compared.meanRatio.z);
  CHECK(compared.pixels > 100);
  CHECK(compared.outside == 0);
  // Tinted, not blocked: red passes most (0.96 x 1.0 less grazing Fresnel), blue least.
  CHECK(compared.meanRatio.x > 0.9f);
  CHECK(compared.meanRatio.z < 0.25f);
}

TEST_CASE("shadow transmittance: a point light's cube maps tint through the pane with each ray's own Fresnel") {
  const Compared compared = compareShadow(Caster::Pane, Light::Type::Point);
  MESSAGE("pane, point: " << compared.pixels << " core pixels");
  CHECK(compared.pixels > 100);
  CHECK(compared.outside == 0);
}

TEST_CASE("shadow transmittance: a glass slab absorbs by Beer-Lambert over the light's path through it") {
  const Compared compared = compareShadow(Caster::Slab, Light::Type::Directional);
  MESSAGE("slab, directional: " << compared.pixels << " core pixels, mean ratio " << compared.meanRatio.x << ", "
                                << compared.meanRatio.y << ", " << compared.meanRatio.z);
  CHECK(compared.pixels > 50);
  CHECK(compared.outside == 0);
  CHECK(compared.meanRatio.x < compared.meanRatio.z);  // attenuationColor's blue passes most
}

TEST_CASE("shadow transmittance: the Embree reference's shadow rays see through the casters as the maps do" *
          doctest::skip(!referenceAvailable())) {
  for (const Caster caster : {Caster::Pane, Caster::Slab})
    for (const Light::Type type : {Light::Type::Directional, Light::Type::Point}) {
      CAPTURE(int(caster));
      CAPTURE(int(type));
      const Scene scene = shadowScene(caster, type);
      RenderSettings small = settings();
      small.width = small.height = 48;
      const Frame frame = test::renderFresh(scene, small);
      ReferenceSettings referenceSettings;
      referenceSettings.samplesPerPixel = 4;
      referenceSettings.radius = 1.0f;
      const ReferenceImages reference = traceReference(scene, frame, referenceSettings);
      int compared = 0;
      for (int y = 0; y < frame.lit.height; ++y)
        for (int x = 0; x < frame.lit.width; ++x) {
          const glm::vec3 p = test::pixel3(frame.position, x, y);
          if (frame.position.at(x, y, 3) == 0.0f || std::abs(p.y) > 1e-3f) continue;
          // The pane is thin; the slab's core is the same test: inside its shadow by a margin.
          if (expectedTransmittance(caster == Caster::Pane ? caster : Caster::Slab, type, p, 0.06f).x < 0.0f) continue;
          ++compared;
          for (int c = 0; c < 3; ++c) {
            CAPTURE(x);
            CAPTURE(y);
            CAPTURE(c);
            // The reference's direct light: lit less its one-bounce indirect (no sky, no emission).
            const float direct = reference.lit.at(x, y, c) - reference.indirect.at(x, y, 3 + c);
            CHECK(direct == doctest::Approx(frame.lit.at(x, y, c)).epsilon(0.01).scale(0.1));
          }
        }
      CHECK(compared > 10);
    }
}

TEST_CASE("shadow transmittance: the reference's sky reaches a floor through a glass roof, tinted as a light is" *
          doctest::skip(!referenceAvailable())) {
  // A white floor under a clear glass roof, lit only by the sky (a sun
  // grazing everything). Glass blocked every cosine ray before: the floor
  // under it got no sky at all. Now each ray goes on through the roof and
  // brings the sky times what the roof lets through, (1 - F) for clear
  // glass: about 0.9 of the open floor's sky light, less where rays cross
  // the roof at a slant.
  auto floorSky = [](bool roof) {
    Scene scene;
    scene.source = "test:glass-roof";
    scene.sky.intensity = 1.0f;
    addInstance(scene, makeFloor(4.0f), addMaterial(scene, makeMaterial({1.0f, 1.0f, 1.0f}, 0.9f)));
    if (roof) {
      Material glass = makeMaterial({1.0f, 1.0f, 1.0f}, 0.0f);
      glass.transmission = MaterialTransmission{1.0f, {}};
      addInstance(scene, makeSquare({0.0f, 0.3f, 0.0f}, {0, 1, 0}, 4.0f), addMaterial(scene, glass));
    }
    scene.cameras.push_back(makeLookAtCamera({0.0f, 0.25f, 0.01f}, {0.0f, 0.0f, 0.0f}, 0.5f));
    Light sun;
    sun.type = Light::Type::Directional;
    sun.direction = {1.0f, 0.0f, 0.0f};
    scene.lights.push_back(sun);
    RenderSettings settings = test::smallSettings(16, 16);
    settings.ssgi.enabled = false;
    const Frame frame = test::renderFresh(scene, settings);
    ReferenceSettings referenceSettings;
    referenceSettings.samplesPerPixel = 256;
    referenceSettings.radius = 1.0f;
    const ReferenceImages reference = traceReference(scene, frame, referenceSettings);
    double sum = 0.0;
    for (int y = 0; y < 16; ++y)
      for (int x = 0; x < 16; ++x) sum += reference.lit.at(x, y, 1);
    return sum / 256.0;
  };
  const double open = floorSky(false), covered = floorSky(true);
  MESSAGE("floor's sky light: open " << open << ", under the glass roof " << covered);
  REQUIRE(open > 0.05);
  CHECK(covered / open > 0.75);
  CHECK(covered / open < 0.97);
}

// GPU against CPU on the transmission pass (lib/passes/transmission.hpp):
// two transmissive squares over an opaque wall, lit only by punctual lights
// (no SSGI, sky intensity 0, no shadows), one of them lit from behind. At
// every pixel the pass drew, lit must be the CPU ports' direct light
// (lib/reference/lobe_transmission.hpp, on the G-buffer read back) plus the
// throughput times the opaque image behind, which is the same scene's lit
// with the squares taken away; the throughput must be the port's.
#include <doctest/doctest.h>

#include <algorithm>
#include <bit>
#include <cmath>

#include "context/context_access.hpp"
#include "headlight/reference.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/shapes.hpp"
#include "reference/lobe_transmission.hpp"
#include "support/gl.hpp"
#include "support/parity.hpp"

using namespace headlight;

namespace {

constexpr float kThinTransmission = 0.75f;
constexpr float kVolumeThickness = 0.4f, kVolumeScale = 1.5f, kAttenuationDistance = 0.5f;
const glm::vec3 kAttenuationColour{0.2f, 0.6f, 0.9f};

// Base colours 0 or 1 per channel: the G-buffer's sRGB8 albedo agrees with
// the readback's exact curve there (tests/direct_light_parity_tests.cpp).
Scene glassScene(bool withGlass) {
  Scene scene;
  scene.source = "test:transmission-parity";
  scene.sky.intensity = 0.0f;
  addInstance(scene, makeSquare({0.0f, 0.0f, -1.0f}, {0, 0, 1}, 2.0f),
              addMaterial(scene, makeMaterial({1.0f, 1.0f, 1.0f}, 0.7f)));
  if (withGlass) {
    // Thin-walled, partly transmissive, smooth: the opaque image at its own pixel.
    Material thin = makeMaterial({1.0f, 1.0f, 0.0f}, 0.0f);
    thin.transmission = MaterialTransmission{kThinTransmission, {}};
    addInstance(scene, makeSquare({-0.6f, 0.0f, 0.0f}, {0, 0, 1}, 0.45f), addMaterial(scene, thin));
    // A volume at ior 1: the path runs along the view ray, so it also reads
    // its own pixel, through Beer-Lambert over thickness x the instance's
    // scale. The two squares do not overlap (coplanar surfaces z-fight).
    Material volume = makeMaterial({1.0f, 1.0f, 1.0f}, 0.3f);
    volume.transmission = MaterialTransmission{1.0f, {}};
    volume.volume = MaterialVolume{kVolumeThickness, {}, kAttenuationDistance, kAttenuationColour};
    volume.ior = 1.0f;
    addInstance(scene, makeSquare({0.0f, 0.0f, 0.0f}, {0, 0, 1}, 0.5f), addMaterial(scene, volume),
                moved({0.7f, 0.0f, 0.0f}) * glm::scale(glm::mat4(1.0f), glm::vec3(kVolumeScale)));
  }
  scene.cameras.push_back(makeLookAtCamera({0.3f, 0.4f, 3.0f}, {0.0f, 0.0f, -0.5f}, 0.8f));
  Light front;
  front.type = Light::Type::Point;
  front.position = {0.8f, 1.0f, 2.0f};
  front.intensity = 6.0f;
  // Between the squares and the wall: it lights the wall and reaches the eye through the squares.
  Light behind;
  behind.type = Light::Type::Point;
  behind.position = {-0.2f, 0.1f, -0.4f};
  behind.intensity = 0.5f;
  behind.color = {1.0f, 0.8f, 0.6f};
  for (Light light : {front, behind}) {
    light.castsShadows = false;
    scene.lights.push_back(light);
  }
  return scene;
}

}  // namespace

TEST_CASE("transmission on the GPU matches the CPU ports per pixel") {
  RenderSettings settings = test::smallSettings(96, 72);
  settings.ssgi.enabled = false;
  const Scene scene = glassScene(true);
  const Frame frame = test::renderFresh(scene, settings);
  const Frame behind = test::renderFresh(glassScene(false), settings);
  REQUIRE(!frame.transmission.empty());

  // lit: 2e-3 relative (RGBA16F storage, llvmpipe's float maths; as the
  // direct-light parity test) and 2e-3 absolute for the split-sum table's
  // bilinear interpolation (64 x 64 half floats) in the throughput, times a
  // background of radiance up to ~1. Throughput: 3e-3 absolute (the table).
  constexpr float kRelative = 2e-3f, kAbsolute = 2e-3f, kThroughput = 3e-3f;
  int thin = 0, volume = 0, litFromBehind = 0, outside = 0;
  for (int y = 0; y < frame.lit.height; ++y)
    for (int x = 0; x < frame.lit.width; ++x) {
      const float pathLength = frame.transmission.at(x, y, 3);
      const glm::vec3 throughputGpu(frame.transmission.at(x, y, 0), frame.transmission.at(x, y, 1),
                                    frame.transmission.at(x, y, 2));
      if (throughputGpu == glm::vec3(0.0f)) continue;
      const bool isVolume = pathLength > 0.0f;
      (isVolume ? volume : thin)++;
      const glm::vec3 position = test::pixel3(frame.position, x, y), normal = test::pixel3(frame.normal, x, y);
      const Material& material = scene.materials[isVolume ? 2 : 1];
      const float transmission = material.transmission->transmissionFactor;
      reference::Surface surface =
          reference::makeSurface(test::pixel3(frame.albedo, x, y), frame.material.at(x, y, 0),
                                 frame.material.at(x, y, 1), normal, glm::normalize(frame.view.position - position));
      surface.f0 = reference::iorF0(material.ior, surface.albedo, surface.metallic);
      surface.transmission = transmission;
      const float blur = reference::transmissionRoughness(frame.material.at(x, y, 1), material.ior);
      const auto transmissive = [&](const glm::vec3& toLight) {
        return reference::transmissiveCookTorrance(surface, toLight, blur);
      };
      glm::vec3 expected = test::punctualLight(scene, position, transmissive);
      // The light that reaches the pixel through the glass, from lights behind it.
      const glm::vec3 fromBehind = test::punctualLight(scene, position, [&](const glm::vec3& toLight) {
        return glm::dot(normal, toLight) < 0.0f ? transmissive(toLight) : glm::vec3(0.0f);
      });
      if (fromBehind.r > 1e-4f) ++litFromBehind;
      const glm::vec2 scaleBias = test::splitSum(surface.nDotV, surface.roughness);
      const glm::vec3 specularAlbedo = surface.f0 * scaleBias.x + scaleBias.y;
      const float path = isVolume ? kVolumeThickness * kVolumeScale : 0.0f;
      const glm::vec3 throughput = reference::transmissionThroughput(
          surface, specularAlbedo,
          reference::volumeAttenuation(path, material.volume ? material.volume->attenuationColor : glm::vec3(1.0f),
                                       material.volume ? material.volume->attenuationDistance : 0.0f));
      CHECK(pathLength == doctest::Approx(path).epsilon(1e-3));
      const glm::vec3 background(behind.lit.at(x, y, 0), behind.lit.at(x, y, 1), behind.lit.at(x, y, 2));
      expected += throughputGpu * background;
      for (int c = 0; c < 3; ++c) {
        const float gpu = frame.lit.at(x, y, c);
        const bool litOk = std::abs(gpu - expected[c]) <= kRelative * std::abs(expected[c]) + kAbsolute;
        const bool throughputOk = std::abs(throughputGpu[c] - throughput[c]) <= kThroughput;
        if (litOk && throughputOk) continue;
        if (++outside <= 5) {
          CAPTURE(x);
          CAPTURE(y);
          CAPTURE(c);
          CHECK(gpu == doctest::Approx(expected[c]).epsilon(kRelative));
          CHECK(throughputGpu[c] == doctest::Approx(throughput[c]).epsilon(kThroughput));
        }
      }
    }
  MESSAGE("transmission parity: " << thin << " thin-walled pixels, " << volume << " volume pixels, " << litFromBehind
                                  << " lit through from behind");
  CHECK(outside == 0);
  // The scene does what it is for: both squares cover a good part of the
  // image, and the light behind them shines through (the BTDF).
  CHECK(thin > 200);
  CHECK(volume > 200);
  CHECK(litFromBehind > 20);
  CHECK(headlight::detail::ContextAccess::pendingErrorCount(test::sharedContext()) == 0);
}

TEST_CASE("transmission: the G-buffer holds the transmissive surface and lit the opaque image elsewhere") {
  RenderSettings settings = test::smallSettings(64, 48);
  settings.ssgi.enabled = false;
  const Frame frame = test::renderFresh(glassScene(true), settings);
  const Frame behind = test::renderFresh(glassScene(false), settings);
  int glass = 0, wall = 0, unchanged = 0;
  for (int y = 0; y < frame.lit.height; ++y)
    for (int x = 0; x < frame.lit.width; ++x) {
      const float z = frame.position.at(x, y, 2);
      if (frame.transmission.at(x, y, 0) > 0.0f) {
        ++glass;
        CHECK(std::abs(z) < 1e-3f);  // the squares lie at z = 0, the wall at -1
        CHECK(frame.depth.at(x, y, 0) < behind.depth.at(x, y, 0));
        continue;
      }
      ++wall;
      // The volume's ior of 1 gives the scene the specular lobe (KHR_materials_ior),
      // so the opaque pixels' F0 of 0.04 comes from a half-float target: 2e-4
      // relative off the constant the opaque frame uses.
      bool same = true;
      for (int c = 0; c < 4; ++c) {
        const float a = frame.lit.at(x, y, c), b = behind.lit.at(x, y, c);
        same = same && std::abs(a - b) <= 1e-3f * std::abs(b) + 1e-6f;
      }
      unchanged += same ? 1 : 0;
    }
  CHECK(glass > 0);
  // Away from the squares the frame is the opaque frame (the squares cast
  // no shadow here: no light casts one).
  CHECK(unchanged == wall);
}

namespace {

// The squares of glassScene over a wall that only emits (black metal), lit
// by a sun that grazes every surface (N.L = 0: no direct light), sky 0: lit
// through a square is its throughput times the wall's emission, in the
// renderer and in the reference alike.
Scene emittingWallScene() {
  Scene scene = glassScene(true);
  Material wall = makeMaterial(glm::vec3(0.0f), 1.0f, 1.0f);
  wall.emissiveFactor = {0.9f, 0.6f, 0.3f};
  scene.materials[std::size_t(scene.instances.front().material)] = wall;
  scene.lights.clear();
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = {1.0f, 0.0f, 0.0f};
  sun.intensity = 3.0f;
  scene.lights.push_back(sun);
  return scene;
}

}  // namespace

TEST_CASE("transmission: the Embree reference sees the wall through the squares as the renderer does" *
          doctest::skip(!referenceAvailable())) {
  const Scene scene = emittingWallScene();
  RenderSettings settings = test::smallSettings(48, 36);
  settings.ssgi.enabled = false;
  const Frame frame = test::renderFresh(scene, settings);
  ReferenceSettings referenceSettings;
  referenceSettings.samplesPerPixel = 16;
  referenceSettings.radius = 1.0f;
  const ReferenceImages reference = traceReference(scene, frame, referenceSettings);
  int compared = 0;
  for (int y = 0; y < frame.lit.height; ++y)
    for (int x = 0; x < frame.lit.width; ++x) {
      if (frame.transmission.at(x, y, 0) + frame.transmission.at(x, y, 1) == 0.0f) continue;
      ++compared;
      for (int c = 0; c < 3; ++c) {
        CAPTURE(x);
        CAPTURE(y);
        CAPTURE(c);
        // 2 % + 2e-3: lit's half floats, and the reference's sampled split-sum
        // specular albedo in the throughput (a smooth surface: little spread).
        CHECK(reference.lit.at(x, y, c) == doctest::Approx(frame.lit.at(x, y, c)).epsilon(0.02).scale(0.1));
      }
    }
  CHECK(compared > 200);
}

namespace {

// A glass square in front of a wall whose left half glows and right half
// is black; sky 0 and no light, so lit through the glass is the wall's
// emission, spread by the glass's roughness. The number of pixels along the
// middle row whose lit lies between a tenth and nine tenths of the glowing
// half's: how wide the glass blurs the wall's edge.
int blurredEdgeWidth(float roughness, float ior, const ImageF& lit, const Frame& frame) {
  const int y = frame.lit.height / 2;
  float bright = 0.0f;
  for (int x = 0; x < lit.width; ++x) bright = std::max(bright, lit.at(x, y, 0));
  int between = 0;
  for (int x = 0; x < lit.width; ++x) {
    if (frame.transmission.at(x, y, 0) == 0.0f) continue;  // through the glass only
    const float value = lit.at(x, y, 0);
    if (value > 0.1f * bright && value < 0.9f * bright) ++between;
  }
  MESSAGE("roughness " << roughness << ", ior " << ior << ": " << between << " pixels across the edge");
  return between;
}

Scene edgeBehindGlass(float roughness, float ior, float wallDistance) {
  Scene scene;
  scene.source = "test:rough-transmission";
  scene.sky.intensity = 0.0f;
  Material glow = makeMaterial(glm::vec3(0.0f), 1.0f, 1.0f);
  glow.emissiveFactor = {1.0f, 1.0f, 1.0f};
  addInstance(scene, makeQuad({-2.0f, -1.0f, -wallDistance}, {2.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f}),
              addMaterial(scene, glow));
  addInstance(scene, makeQuad({0.0f, -1.0f, -wallDistance}, {2.0f, 0.0f, 0.0f}, {0.0f, 2.0f, 0.0f}),
              addMaterial(scene, makeMaterial(glm::vec3(0.0f), 1.0f, 1.0f)));
  Material glass = makeMaterial({1.0f, 1.0f, 1.0f}, roughness);
  glass.transmission = MaterialTransmission{1.0f, {}};
  glass.ior = ior;
  addInstance(scene, makeSquare({0.0f, 0.0f, 0.0f}, {0, 0, 1}, 0.6f), addMaterial(scene, glass));
  scene.cameras.push_back(makeLookAtCamera({0.0f, 0.0f, 2.0f}, {0.0f, 0.0f, 0.0f}, 0.7f));
  Light sun;  // grazing every surface: no direct light, and the scene is not "unlit"
  sun.type = Light::Type::Directional;
  sun.direction = {0.0f, 1.0f, 0.0f};
  scene.lights.push_back(sun);
  return scene;
}

}  // namespace

TEST_CASE("transmission: rough glass blurs what lies behind it as far as it lies, except at ior 1" *
          doctest::skip(!referenceAvailable())) {
  // TransmissionRoughnessTest's rule: microfacets bend light by refraction,
  // so a rough surface blurs at ior 1.5 and not at all at ior 1; and the
  // blur's width on screen grows with the distance to what lies behind.
  // Before, the reference's one straight ray made every case sharp and the
  // renderer blurred by the image's size whatever the distance (11 pixels
  // where the reference now has 22 at 1 unit, and the same 11 at 0.25).
  struct Widths {
    int renderer, reference;
  };
  auto widths = [](float roughness, float ior, float wallDistance) {
    const Scene scene = edgeBehindGlass(roughness, ior, wallDistance);
    RenderSettings settings = test::smallSettings(64, 48);
    settings.ssgi.enabled = false;
    const Frame frame = test::renderFresh(scene, settings);
    ReferenceSettings referenceSettings;
    referenceSettings.samplesPerPixel = 64;
    referenceSettings.radius = 1.0f;
    const ImageF lit = traceReference(scene, frame, referenceSettings).lit;
    MESSAGE("wall " << wallDistance << " behind the glass:");
    return Widths{blurredEdgeWidth(roughness, ior, frame.lit, frame), blurredEdgeWidth(roughness, ior, lit, frame)};
  };
  const Widths smooth = widths(0.0f, 1.5f, 1.0f);
  CHECK(smooth.reference <= 1);  // the pixel on the edge at most
  CHECK(smooth.renderer <= 1);
  const Widths air = widths(0.6f, 1.0f, 1.0f);  // rough, but ior 1 bends nothing
  CHECK(air.reference <= 1);
  CHECK(air.renderer <= 1);
  for (const auto& [roughness, distance] : {std::pair{0.6f, 1.0f}, std::pair{0.6f, 0.25f}, std::pair{0.4f, 1.0f}}) {
    CAPTURE(roughness);
    CAPTURE(distance);
    const Widths rough = widths(roughness, 1.5f, distance);
    CHECK(rough.reference >= 3);
    // Within a third of the reference's width, and 2 pixels.
    CHECK(std::abs(rough.renderer - rough.reference) <= std::max(2, rough.reference / 3));
  }
}

// GL tests of the bitmask SSGI's specular sky visibility (issue 16): the
// share of the GGX lobe about the reflection that escapes, read from the
// slices' masks (ssgi.exr specular.Y), against what it must be on a mirror
// ball over a floor and the reference's specular.Y, and the grain it left on
// polished metal (issue 33).
#include <doctest/doctest.h>

#include <glm/glm.hpp>

#include <cmath>
#include <functional>

#include "headlight/reference.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"
#include "support/environment_maps.hpp"
#include "support/gl.hpp"
#include "support/temp_folder.hpp"
#include "tooling/bench.hpp"

using namespace headlight;
using namespace headlight::test;

namespace {

constexpr int kSpecularChannel = 8;  // ssgi's specular.Y
constexpr int kSkyChannel = 4;       // ssgi's sky.Y
const glm::vec3 kEye(0.0f, 2.2f, 2.6f);

// A near-mirror metal ball (roughness 0.1) resting on a large floor, seen
// from above: its lower half reflects the floor, its upper half the open
// sky.
Scene mirrorBallScene() {
  Scene scene;
  scene.source = "test:mirror-ball";
  addInstance(scene, makeFloor(20.0f), addMaterial(scene, makeMaterial(glm::vec3(0.8f), 0.9f)));
  addInstance(scene, makeUvSphere(0.5f, 64, 32), addMaterial(scene, makeMaterial(glm::vec3(0.9f), 0.1f, 1.0f)),
              moved({0.0f, 0.5f, 0.0f}));
  scene.cameras.push_back(makeLookAtCamera(kEye, {0.0f, 0.45f, 0.0f}, 0.6f));
  return scene;
}

// The world reflection of the view ray at a ball pixel; false elsewhere
// (the floor, the background).
bool ballReflection(const Frame& frame, int x, int y, glm::vec3& reflected) {
  if (frame.position.at(x, y, 3) == 0.0f || frame.position.at(x, y, 1) < 0.02f) return false;
  const glm::vec3 position(frame.position.at(x, y, 0), frame.position.at(x, y, 1), frame.position.at(x, y, 2));
  const glm::vec3 normal(frame.normal.at(x, y, 0), frame.normal.at(x, y, 1), frame.normal.at(x, y, 2));
  if (normal.y > 0.99f) return false;  // the floor
  reflected = glm::reflect(glm::normalize(position - kEye), normal);
  return true;
}

// Where a ball pixel's reflection goes: up to the open sky, down into a
// stretch of floor some floor pixel shows (screen space can know it is
// blocked), or elsewhere (into the floor under the ball or behind the eye,
// off screen: taken as open, as all that is off screen).
enum class Reflects { Sky, FloorOnScreen, Elsewhere, NotBall };
Reflects reflects(const Frame& frame, int x, int y) {
  glm::vec3 reflected;
  if (!ballReflection(frame, x, y, reflected)) return Reflects::NotBall;
  if (reflected.y > 0.3f) return Reflects::Sky;
  if (reflected.y > -0.3f) return Reflects::Elsewhere;
  const glm::vec3 position(frame.position.at(x, y, 0), frame.position.at(x, y, 1), frame.position.at(x, y, 2));
  const glm::vec3 floorHit = position - reflected * (position.y / reflected.y);
  for (int v = 0; v < frame.position.height; ++v)
    for (int u = 0; u < frame.position.width; ++u) {
      if (frame.position.at(u, v, 3) == 0.0f || frame.normal.at(u, v, 1) < 0.99f) continue;
      const glm::vec3 shown(frame.position.at(u, v, 0), frame.position.at(u, v, 1), frame.position.at(u, v, 2));
      if (glm::distance(shown, floorHit) < 0.05f) return Reflects::FloorOnScreen;
    }
  return Reflects::Elsewhere;
}

// The mean of `value` over the ball pixels whose reflection goes `where`.
double ballMean(const Frame& frame, Reflects where, const std::function<double(int, int)>& value, int& count) {
  double sum = 0.0;
  count = 0;
  for (int y = 0; y < frame.position.height; ++y)
    for (int x = 0; x < frame.position.width; ++x)
      if (reflects(frame, x, y) == where) {
        sum += value(x, y);
        ++count;
      }
  return count > 0 ? sum / count : 0.0;
}

// Three polished metal balls (roughness 0.05) in a row on a floor under a
// uniform map, no light: the reflections near each ball's silhouette graze
// past its neighbours and the floor, where the slices' reading of a narrow
// lobe decides the lit value. Seen from the front and a little above.
Scene mirrorRowScene(std::shared_ptr<const EnvironmentMap> environment) {
  Scene scene;
  scene.source = "test:mirror-row";
  addInstance(scene, makeFloor(20.0f), addMaterial(scene, makeMaterial(glm::vec3(0.8f), 0.9f)));
  const int mirror = addMaterial(scene, makeMaterial(glm::vec3(0.95f), 0.05f, 1.0f));
  for (float x : {-1.2f, 0.0f, 1.2f}) addInstance(scene, makeUvSphere(0.5f, 64, 32), mirror, moved({x, 0.5f, 0.0f}));
  scene.lights.push_back(darkLight());
  scene.environment = std::move(environment);
  scene.cameras.push_back(makeLookAtCamera({0.0f, 1.4f, 3.6f}, {0.0f, 0.5f, 0.0f}, 0.8f));
  return scene;
}

// The luminance of `lit` (`frame.lit` or a reference's of the same camera)
// at `frame`'s ball pixels (not the floor, not the background), in one order.
std::vector<double> ballLuminance(const Frame& frame, const ImageF& lit) {
  std::vector<double> values;
  for (int y = 0; y < lit.height; ++y)
    for (int x = 0; x < lit.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f || frame.normal.at(x, y, 1) > 0.99f) continue;
      values.push_back(0.2126 * lit.at(x, y, 0) + 0.7152 * lit.at(x, y, 1) + 0.0722 * lit.at(x, y, 2));
    }
  return values;
}
std::vector<double> ballLuminance(const Frame& frame) { return ballLuminance(frame, frame.lit); }

// The RMS of a - b over the RMS of b.
double relativeRms(const std::vector<double>& a, const std::vector<double>& b) {
  double difference = 0.0, norm = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    difference += (a[i] - b[i]) * (a[i] - b[i]);
    norm += b[i] * b[i];
  }
  return std::sqrt(difference / std::max(norm, 1e-30));
}

}  // namespace

TEST_CASE("bitmask SSGI specular visibility: polished metal shows no grain against 32 accumulated frames") {
  // Issue 33 item 1: the default's one frame of the same camera against 32
  // accumulated ones (each with rotated slices and jittered steps), over
  // the balls' pixels: what one frame adds beyond their mean is grain.
  const TempFolder folder("ssgi-specular");
  Renderer renderer(sharedContext());
  renderer.setScene(
      mirrorRowScene(loadEnvironmentMap(writeEnvironmentMap(folder.path() / "uniform.exr", 64, 32, uniformRadiance))));
  RenderSettings settings = smallSettings(192, 128);
  const Frame single = renderer.render(settings);
  settings.ssgi.frames = 32;
  const std::vector<double> accumulated = ballLuminance(renderer.render(settings));
  settings.ssgi.enabled = false;
  const Frame withoutSsgi = renderer.render(settings);
  const std::vector<double> one = ballLuminance(single), unoccluded = ballLuminance(withoutSsgi);
  REQUIRE(one.size() == accumulated.size());
  REQUIRE(one.size() > 2000);
  const double grain = relativeRms(one, accumulated);
  CAPTURE(one.size());
  CAPTURE(grain);
  // Before: 0.156 (the lobe read by whichever slice the random rotation
  // brought near R, at most 1/4 sector wide, and only the 3x3 upsample to
  // average it); measured 0.041 after.
  CHECK(grain < 0.05);
  if (!referenceAvailable()) return;  // the rest needs the ray-traced truth
  ReferenceSettings reference;
  reference.samplesPerPixel = 64;
  reference.radius = *single.settings.ssgi.radius;
  const ReferenceImages traced = traceReference(renderer.scene(), single, reference);
  const std::vector<double> truth = ballLuminance(single, traced.lit);
  const double error = relativeRms(one, truth), errorWithoutSsgi = relativeRms(unoccluded, truth);
  CAPTURE(error);
  CAPTURE(errorWithoutSsgi);
  // Measured 0.543 against 1.006 (0.616 before): a one-frame default
  // closer to the truth than no SSGI, on the pixels where it was grainy.
  CHECK(error < errorWithoutSsgi);
}

TEST_CASE("bitmask SSGI specular visibility: a mirror ball is closed toward the floor and open toward the sky") {
  Renderer renderer(sharedContext());
  renderer.setScene(mirrorBallScene());
  const Frame frame = renderer.render(smallSettings(128, 128));
  REQUIRE(frame.ssgi.channels.size() == 9);
  REQUIRE(frame.ssgi.channels[kSpecularChannel] == "specular.Y");
  auto specular = [&](int x, int y) { return double(frame.ssgi.at(x, y, kSpecularChannel)); };
  auto sky = [&](int x, int y) { return double(frame.ssgi.at(x, y, kSkyChannel)); };
  int floorCount = 0, skyCount = 0;
  const double towardFloor = ballMean(frame, Reflects::FloorOnScreen, specular, floorCount);
  const double towardSky = ballMean(frame, Reflects::Sky, specular, skyCount);
  const double diffuseTowardFloor = ballMean(frame, Reflects::FloorOnScreen, sky, floorCount);
  REQUIRE(floorCount > 30);
  REQUIRE(skyCount > 200);
  CAPTURE(floorCount);
  CAPTURE(skyCount);
  CAPTURE(towardFloor);
  CAPTURE(towardSky);
  CAPTURE(diffuseTowardFloor);
  // A reflection 17 degrees or more below the horizon meets the floor: 0
  // in truth. These reflections start near the ball's foot, where the floor
  // they meet is a thin sliver on screen that few steps hit; measured 0.68
  // (0.61 before the lobe floor of two sectors, issue 33).
  CHECK(towardFloor < 0.7);
  // The diffuse sky visibility there, which occluded the specular before,
  // is far more open (the ball's upper hemisphere sees the sky): measured
  // 0.91.
  CHECK(diffuseTowardFloor > towardFloor + 0.2);
  // Reflections above the horizon escape.
  CHECK(towardSky > 0.95);
}

TEST_CASE("bitmask SSGI specular visibility against the reference's specular.Y on builtin:spheres" *
          doctest::skip(!HEADLIGHT_HAS_EMBREE)) {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:spheres"));  // roughness 0.2..0.9, one metal ball
  const Frame frame = renderer.render(smallSettings(128, 128));
  ReferenceSettings reference;
  reference.samplesPerPixel = 256;  // 64 GGX samples: the escaped share's standard error <= 0.06 per pixel
  reference.radius = *frame.settings.ssgi.radius;
  const ReferenceImages truth = traceReference(renderer.scene(), frame, reference);
  REQUIRE(truth.ao.channels.size() == 3);
  REQUIRE(truth.ao.channels[2] == "specular.Y");
  // Ours, and the diffuse sky visibility in its place (what occluded the
  // specular before), over the geometry pixels.
  const ErrorStats specular = maskedError(frame.ssgi, kSpecularChannel, truth.ao, 2, frame.position);
  const ErrorStats sky = maskedError(frame.ssgi, kSkyChannel, truth.ao, 2, frame.position);
  CAPTURE(specular.rmse);
  CAPTURE(sky.rmse);
  CAPTURE(specular.referenceMean);
  // Measured 0.096 (0.099 before issue 33's lobe floor) against the sky
  // visibility's 0.131 (128x128, 256 rays):
  // 0.11 leaves room for another rasteriser's silhouettes; the ratio fails
  // an estimate no better than the diffuse visibility it replaced.
  CHECK(specular.rmse < 0.11);
  CHECK(specular.rmse < 0.8 * sky.rmse);
}

TEST_CASE("The kernel methods write their AO as the specular visibility") {
  // They estimate no lobe: the specular IBL is occluded as the diffuse is.
  RenderSettings settings = smallSettings(64, 64);
  settings.ssgi.method = SsgiMethod::Hemisphere;
  const Frame frame = renderFresh(mirrorBallScene(), settings);
  REQUIRE(frame.ssgi.channels.size() == 9);
  int count = 0;
  for (int y = 0; y < frame.ssgi.height; ++y)
    for (int x = 0; x < frame.ssgi.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      // The blur averages the specular over its inner 5x5 taps, the AO over
      // 7x7: measured up to 0.020 apart.
      CHECK(std::abs(frame.ssgi.at(x, y, kSpecularChannel) - frame.ssgi.at(x, y, 0)) < 0.03f);
      ++count;
    }
  CHECK(count > 1000);
}

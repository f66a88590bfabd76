// GL tests of the SSGI methods: analytic AO on open planes and corners, the
// light they gather, resolutions and the bitmask method's sky visibility
// beyond R, against closed forms and the Embree reference.
#include <doctest/doctest.h>

#include <glad/gl.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "context/context_access.hpp"
#include "gl/shader_library.hpp"
#include "headlight/error.hpp"
#include "headlight/reference.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"
#include "shared_layout.h"
#include "support/assets.hpp"
#include "support/gl.hpp"
#include "tooling/bench.hpp"

using namespace headlight;
using namespace headlight::test;

TEST_CASE("SSGI on a flat open plane finds no occlusion away from the edges") {
  for (const std::string preset : {"default", "seed"}) {
    CAPTURE(preset);
    RenderSettings settings = smallSettings(96, 72);
    applyPreset(settings, preset);
    const Frame frame = renderFresh(openPlaneScene(), settings);
    float minimum = 1.0f;
    int count = 0;
    for (int y = 4; y < frame.ssgi.height - 4; ++y)
      for (int x = 4; x < frame.ssgi.width - 4; ++x) {
        if (frame.position.at(x, y, 3) == 0.0f) continue;
        minimum = std::min(minimum, frame.ssgi.at(x, y, 0));
        ++count;
      }
    CHECK(count > 2000);
    CHECK(minimum >= 0.95f);
  }
}

TEST_CASE("bitmask SSGI: an open plane is exactly unoccluded at any slice count") {
  // The AO is the ratio of visible to total cosine-weighted slice measure,
  // so a plane with nothing above it is 1 however few slices there are.
  // Away from the image's edges, as for the other methods: the rows next to
  // the plane's far edge see it within a degree of edge-on, where a depth
  // sample's point is taken at its pixel centre, up to half a pixel off the
  // slice.
  for (const int slices : {1, 2, 5}) {
    CAPTURE(slices);
    RenderSettings settings = smallSettings(96, 72);
    settings.ssgi.method = SsgiMethod::Bitmask;
    settings.ssgi.sliceCount = slices;
    settings.ssgi.blur = false;
    const Frame frame = renderFresh(openPlaneScene(), settings);
    float minimum = 1.0f, indirect = 0.0f;
    int count = 0, minimumX = -1, minimumY = -1;
    for (int y = 4; y < frame.ssgi.height - 4; ++y)
      for (int x = 4; x < frame.ssgi.width - 4; ++x) {
        if (frame.position.at(x, y, 3) == 0.0f) continue;
        if (frame.ssgi.at(x, y, 0) < minimum) minimum = frame.ssgi.at(x, y, 0), minimumX = x, minimumY = y;
        for (int c = 1; c < 4; ++c) indirect = std::max(indirect, frame.ssgi.at(x, y, c));
        ++count;
      }
    CAPTURE(minimumX);
    CAPTURE(minimumY);
    CHECK(count > 2000);
    CHECK(minimum >= 0.999f);  // half-float storage of 1 is exact; a stray sector would cost >= 0.002
    CHECK(indirect == 0.0f);
  }
}

TEST_CASE("bitmask SSGI: a floor before a wall matches the analytic AO within R") {
  // The floor y = 0 meets the wall z = 0. For a floor point a distance d in
  // front of the (effectively infinite) wall, cosine-weighted directions
  // project to a uniform point on the unit disc, and a direction meets the
  // wall within R when its z component is below -d / R, so
  //   ao_R(d) = 1 - (acos(a) - a sqrt(1 - a^2)) / pi,  a = min(d / R, 1),
  // which is 0.5 at the crease. Tolerances: sectors are whole (1/32 of the
  // slice's angle), the floor's depth is rasterised, and the wall above the
  // image's top edge is assumed open.
  Scene scene;
  scene.source = "test:corner";
  const int grey = addMaterial(scene, makeMaterial(glm::vec3(0.5f), 1.0f));
  addInstance(scene, makeSquare({0, 0, 0}, {0, 1, 0}, 100.0f), grey);
  addInstance(scene, makeSquare({0, 0, 0}, {0, 0, 1}, 100.0f), grey);
  scene.cameras.push_back(makeLookAtCamera({0.0f, 1.5f, 4.0f}, {0.0f, 0.4f, 0.0f}, 0.8f));
  RenderSettings settings = smallSettings(128, 128);
  settings.ssgi.method = SsgiMethod::Bitmask;
  settings.ssgi.radius = 1.0f;
  settings.ssgi.sliceCount = 4;
  settings.ssgi.stepCount = 16;
  // Either the 4x4 blur or 8 accumulated frames (--ssgi-frames) without it.
  for (const bool accumulate : {false, true}) {
    CAPTURE(accumulate);
    settings.ssgi.blur = !accumulate;
    settings.ssgi.frames = accumulate ? 8 : 1;
    const Frame frame = renderFresh(scene, settings);
    constexpr double kPi = 3.14159265358979;
    double errorSum = 0.0, creaseSum = 0.0, creaseExpected = 0.0;
    int count = 0, creaseCount = 0;
    for (int y = 0; y < frame.ssgi.height; ++y)
      for (int x = 16; x < frame.ssgi.width - 16; ++x) {
        if (frame.position.at(x, y, 3) == 0.0f || frame.normal.at(x, y, 1) < 0.9f) continue;  // floor only
        const double d = frame.position.at(x, y, 2);
        if (d > 1.5) continue;
        const double a = std::min(d / 1.0, 1.0);
        const double expected = 1.0 - (std::acos(a) - a * std::sqrt(1.0 - a * a)) / kPi;
        const double ao = frame.ssgi.at(x, y, 0);
        errorSum += std::abs(ao - expected);
        ++count;
        if (d < 0.1) creaseSum += ao, creaseExpected += expected, ++creaseCount;
      }
    REQUIRE(count > 500);
    REQUIRE(creaseCount > 10);
    CAPTURE(creaseSum / creaseCount);
    CAPTURE(creaseExpected / creaseCount);
    CAPTURE(errorSum / count);
    CHECK(errorSum / count < 0.03);
    // The floor's first 0.1 in front of the wall (0.5 at the crease).
    CHECK(std::abs(creaseSum - creaseExpected) / creaseCount < 0.06);  // measured 0.044 (blur), 0.003 (8 frames)
  }
}

TEST_CASE("Cornell box: a corner is darker than the middle of the back wall, and the red wall bleeds red") {
  const Frame frame = renderFresh(loadScene("builtin:cornell"), smallSettings(128, 128));
  int cornerCount = 0, wallCount = 0, floorCount = 0;
  // The back wall's top right corner, where it meets the ceiling and the green wall.
  const double cornerAo = meanWhere(
      frame, frame.ssgi, 0, [](glm::vec3 p, glm::vec3 n) { return n.z > 0.9f && p.x > 0.9f && p.y > 1.9f; },
      cornerCount);
  // The back wall's middle, well away from both blocks and every edge.
  const double wallAo = meanWhere(
      frame, frame.ssgi, 0,
      [](glm::vec3 p, glm::vec3 n) { return n.z > 0.9f && std::abs(p.x) < 0.2f && p.y > 1.3f && p.y < 1.6f; },
      wallCount);
  REQUIRE(cornerCount > 5);
  REQUIRE(wallCount > 20);
  CHECK(wallAo > 0.95);
  CHECK(cornerAo < wallAo - 0.1);  // "clearly lower": at least 0.1 of AO

  // Floor along the red (left) wall, in front of the tall block.
  const auto nearRedWall = [](glm::vec3 p, glm::vec3 n) { return n.y > 0.9f && p.x < -0.85f && p.z > 0.1f; };
  const double red = meanWhere(frame, frame.ssgi, 1, nearRedWall, floorCount);
  const double green = meanWhere(frame, frame.ssgi, 2, nearRedWall, floorCount);
  REQUIRE(floorCount > 5);
  CHECK(red > 0.0);
  CHECK(red > 2.0 * green);
}

TEST_CASE("SSGI radiance method gathers light, not albedo") {
  Scene dark = loadScene("builtin:cornell");
  for (Light& light : dark.lights) light.intensity = 0.0f;
  for (Material& material : dark.materials) material.emissiveFactor = glm::vec3(0.0f);
  RenderSettings settings = smallSettings(64, 64);
  auto maxIndirect = [](const Frame& frame) {
    float maximum = 0;
    for (int y = 0; y < frame.ssgi.height; ++y)
      for (int x = 0; x < frame.ssgi.width; ++x)
        for (int c = 1; c < 4; ++c) maximum = std::max(maximum, frame.ssgi.at(x, y, c));
    return maximum;
  };
  settings.ssgi.method = SsgiMethod::Hemisphere;
  CHECK(maxIndirect(renderFresh(dark, settings)) > 0.05f);  // albedo, whatever the light
  settings.ssgi.method = SsgiMethod::Radiance;
  CHECK(maxIndirect(renderFresh(dark, settings)) == 0.0f);  // no direct light, nothing to bounce

  // Lit, the red wall still bleeds red onto the floor beside it.
  const Frame lit = renderFresh(loadScene("builtin:cornell"), settings);
  int count = 0;
  const auto nearRedWall = [](glm::vec3 p, glm::vec3 n) { return n.y > 0.9f && p.x < -0.85f && p.z > 0.1f; };
  const double red = meanWhere(lit, lit.ssgi, 1, nearRedWall, count);
  const double green = meanWhere(lit, lit.ssgi, 2, nearRedWall, count);
  REQUIRE(count > 5);
  CHECK(red > 2.0 * green);
}

namespace {

// The Cornell box with the bitmask method and R = 0.35: the room is 2
// across, so most of it is beyond R.
RenderSettings bitmaskBeyondRSettings() {
  RenderSettings settings = smallSettings(64, 64);
  settings.ssgi.method = SsgiMethod::Bitmask;
  settings.ssgi.radiusFraction = 0.1f;
  return settings;
}

}  // namespace

// ssgi.exr's sky.Y (channel 4): the sky visibility at any distance that
// occludes ambient light (docs/ACCURACY.md §2.4, §3.3).
TEST_CASE("Bitmask sky visibility beyond R: the Cornell box's closed walls") {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:cornell"));
  RenderSettings settings = bitmaskBeyondRSettings();
  const Frame frame = renderer.render(settings);
  REQUIRE(frame.ssgi.channels.size() == 9);
  REQUIRE(frame.ssgi.channels[4] == "sky.Y");
  REQUIRE(frame.ssgi.channels[5] == "indirectFar.R");

  // The back wall's middle and the floor's middle, away from the blocks:
  // nothing within R, but the room closes round them beyond it.
  const auto backWall = [](glm::vec3 p, glm::vec3 n) {
    return n.z > 0.9f && std::abs(p.x) < 0.5f && p.y > 1.2f && p.y < 1.7f;
  };
  const auto floor = [](glm::vec3 p, glm::vec3 n) { return n.y > 0.9f && std::abs(p.x) < 0.3f && p.z > 0.65f; };
  for (const auto& [name, select] : {std::pair{"back wall", std::function<bool(glm::vec3, glm::vec3)>(backWall)},
                                     std::pair{"floor", std::function<bool(glm::vec3, glm::vec3)>(floor)}}) {
    CAPTURE(name);
    int count = 0;
    const double ao = meanWhere(frame, frame.ssgi, 0, select, count);
    const double sky = meanWhere(frame, frame.ssgi, 4, select, count);
    REQUIRE(count > 10);
    CAPTURE(ao);
    CAPTURE(sky);
    CHECK(ao > 0.9);
    CHECK(sky < ao - 0.3);
  }

  // Sky visibility never exceeds AO within R: what is near is also in the way.
  for (int y = 0; y < frame.ssgi.height; ++y)
    for (int x = 0; x < frame.ssgi.width; ++x) CHECK(frame.ssgi.at(x, y, 4) <= frame.ssgi.at(x, y, 0) + 1e-3f);

  // With no steps beyond R the sky visibility is the AO within R (1e-3:
  // the blur sums the two in different registers; half rounds at 4.9e-4).
  settings.ssgi.skyStepCount = 0;
  const Frame near = renderer.render(settings);
  for (int y = 0; y < near.ssgi.height; ++y)
    for (int x = 0; x < near.ssgi.width; ++x) REQUIRE(std::abs(near.ssgi.at(x, y, 4) - near.ssgi.at(x, y, 0)) <= 1e-3f);
}

TEST_CASE("Bitmask sky visibility and light beyond R against the reference's sky.Y, indirect and lit" *
          doctest::skip(!HEADLIGHT_HAS_EMBREE)) {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:cornell"));
  const RenderSettings settings = bitmaskBeyondRSettings();
  const Frame frame = renderer.render(settings);
  ReferenceSettings reference;
  reference.samplesPerPixel = 256;  // standard error <= 0.031 per pixel, ~0.0005 on the RMSE over ~3500 pixels
  reference.radius = *frame.settings.ssgi.radius;
  const ReferenceImages truth = traceReference(renderer.scene(), frame, reference);
  REQUIRE(truth.ao.channels == std::vector<std::string>{"ao.Y", "sky.Y", "specular.Y"});
  const ErrorStats sky = maskedError(frame.ssgi, 4, truth.ao, 1, frame.position);
  const ErrorStats ao = maskedError(frame.ssgi, 0, truth.ao, 0, frame.position);
  const ErrorStats skyFromAo = maskedError(frame.ssgi, 0, truth.ao, 1, frame.position);
  CAPTURE(sky.rmse);
  CAPTURE(ao.rmse);
  CAPTURE(skyFromAo.rmse);
  CAPTURE(sky.referenceMean);
  // The truth itself: the box is open at the front only.
  CHECK(sky.referenceMean < ao.referenceMean - 0.3);
  // Measured 0.172 at 8 sky steps before issue 16's per-tile offsets (4 steps:
  // 0.27); 0.22 leaves room for another
  // rasteriser's silhouettes; the reference's own noise adds ~0.001 at 256 rays.
  CHECK(sky.rmse < 0.22);
  // Far better than taking AO within R for the sky, as the composite did.
  CHECK(sky.rmse < 0.5 * skyFromAo.rmse);

  // The light from beyond R (indirectFar) against the reference's
  // unlimited less its within-R indirect, summed over geometry pixels:
  // from the virtual lights (the default), and from the marches alone.
  RenderSettings marchesOnly = settings;
  marchesOnly.ssgi.virtualLightCount = 0;
  const Frame marched = renderer.render(marchesOnly);
  const auto farRatio = [&](const Frame& ours) {
    double farSsgi = 0.0, farTruth = 0.0;
    for (int y = 0; y < ours.ssgi.height; ++y)
      for (int x = 0; x < ours.ssgi.width; ++x)
        if (ours.position.at(x, y, 3) > 0.0f)
          for (int c = 0; c < 3; ++c) {
            farSsgi += ours.ssgi.at(x, y, 5 + c);
            farTruth += truth.indirect.at(x, y, 3 + c) - truth.indirect.at(x, y, c);
          }
    return farSsgi / farTruth;
  };
  const double farFromLights = farRatio(frame), farFromMarches = farRatio(marched);
  CAPTURE(farFromLights);
  CAPTURE(farFromMarches);
  // Measured 0.82 from the marches: off-screen and hidden surfaces send
  // nothing there, so it stays below 1; 0.6..1.1 fails a lost or doubled
  // term. From the virtual lights 1.05: they see what the screen hides (1.14
  // before the lights' shadows hid them too: what lies beyond R on screen
  // does not; docs/ACCURACY.md §3.3); 0.9..1.2.
  CHECK(farFromMarches > 0.6);
  CHECK(farFromMarches < 1.1);
  CHECK(farFromLights > 0.9);
  CHECK(farFromLights < 1.2);
  // Lit: sky visibility and light beyond R bring it closer to lit_ref than
  // the AO within R alone did, the virtual lights closer still.
  RenderSettings withinR = marchesOnly;
  withinR.ssgi.skyStepCount = 0;
  const Frame before = renderer.render(withinR);
  const double litError = maskedColorError(frame.lit, 0, truth.lit, 0, frame.position).relativeRmse;
  const double litErrorMarches = maskedColorError(marched.lit, 0, truth.lit, 0, marched.position).relativeRmse;
  const double litErrorBefore = maskedColorError(before.lit, 0, truth.lit, 0, before.position).relativeRmse;
  CAPTURE(litError);
  CAPTURE(litErrorMarches);
  CAPTURE(litErrorBefore);
  CHECK(litErrorMarches < 0.9 * litErrorBefore);  // measured 0.265 against 0.392
  CHECK(litError < litErrorMarches);  // measured 0.198 against 0.265

  // --ssgi-frames carries it: 4 accumulated frames without the blur land
  // as close (measured 0.171).
  RenderSettings accumulated = settings;
  accumulated.ssgi.frames = 4;
  accumulated.ssgi.blur = false;
  const Frame frames = renderer.render(accumulated);
  const ErrorStats framesSky = maskedError(frames.ssgi, 4, truth.ao, 1, frames.position);
  CAPTURE(framesSky.rmse);
  CHECK(framesSky.rmse < 0.22);
}

TEST_CASE("The kernel methods write their AO within R as the sky visibility, and no light from beyond R") {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:cornell"));
  RenderSettings settings = smallSettings(48, 48);
  for (const SsgiMethod method : {SsgiMethod::Hemisphere, SsgiMethod::Radiance}) {
    settings.ssgi.method = method;
    for (const bool blur : {false, true}) {
      CAPTURE(blur);
      settings.ssgi.blur = blur;
      const Frame frame = renderer.render(settings);
      REQUIRE(frame.ssgi.channels.size() == 9);
      // Exact without the blur; 1e-3 with it (as above).
      const float tolerance = blur ? 1e-3f : 0.0f;
      for (int y = 0; y < frame.ssgi.height; ++y)
        for (int x = 0; x < frame.ssgi.width; ++x)
          REQUIRE(std::abs(frame.ssgi.at(x, y, 4) - frame.ssgi.at(x, y, 0)) <= tolerance);
      // They gather nothing beyond R.
      for (int y = 0; y < frame.ssgi.height; ++y)
        for (int x = 0; x < frame.ssgi.width; ++x)
          for (int c = 5; c < 8; ++c) REQUIRE(frame.ssgi.at(x, y, c) == 0.0f);
    }
  }
}

TEST_CASE("SSGI at half and quarter resolution, upsampled by the blur, stays close to full resolution") {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:cornell"));
  RenderSettings settings = smallSettings(96, 72);
  const Frame full = renderer.render(settings);
  for (int divisor : {2, 4}) {
    CAPTURE(divisor);
    settings.ssgi.resolution = divisor == 2 ? SsgiResolution::Half : SsgiResolution::Quarter;
    const Frame reduced = renderer.render(settings);
    REQUIRE(reduced.ssgi.width == 96);  // upsampled to the image size
    double difference = 0;
    int count = 0;
    for (int y = 0; y < 72; ++y)
      for (int x = 0; x < 96; ++x)
        if (full.position.at(x, y, 3) != 0.0f) {
          difference += std::abs(full.ssgi.at(x, y, 0) - reduced.ssgi.at(x, y, 0));
          ++count;
        }
    // Measured mean AO difference on llvmpipe, the default (bitmask) method:
    // 0.029 (half) and 0.070 (quarter: a 4x4 noise tile then spans 16 pixels
    // and the upsample averages 2 of them across a 4x4 raw footprint); the
    // hemisphere method's were 0.012 and 0.023. The bounds leave room for
    // other rasterisers.
    MESSAGE("mean AO difference " << difference / count);
    CHECK(difference / count < (divisor == 2 ? 0.04 : 0.09));
  }
  settings.ssgi.blur = false;
  CHECK_THROWS_AS(renderer.render(settings), SettingsError);  // the blur is the upsample
}


TEST_CASE("SSGI off: no ssgi target, and the image SSGI would give with no occlusion and no bounce") {
  RenderSettings settings = smallSettings(64, 64);
  settings.ssgi.intensity = 0.0f;         // AO 1 everywhere
  settings.ssgi.indirectStrength = 0.0f;  // no indirect term
  const Frame neutral = renderFresh(loadScene("builtin:cornell"), settings);
  settings.ssgi.enabled = false;
  const Frame without = renderFresh(loadScene("builtin:cornell"), settings);
  CHECK(without.ssgi.empty());
  REQUIRE(!neutral.ssgi.empty());
  REQUIRE(without.lit.pixels.size() == neutral.lit.pixels.size());
  float worst = 0;
  for (std::size_t i = 0; i < without.lit.pixels.size(); ++i)
    worst = std::max(worst, std::abs(without.lit.pixels[i] - neutral.lit.pixels[i]));
  // The same composite either way: equal to half-float rounding at most.
  CHECK(worst <= 1e-3f);
}

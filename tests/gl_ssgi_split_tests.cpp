// GL tests of the bitmask SSGI's two resolutions (lib/passes/ssgi_bitmask.hpp):
// the near field is exactly what a run without sky steps draws, and the far
// field from its half-resolution pass stays close to the single
// full-resolution pass's.
#include <doctest/doctest.h>

#include <cmath>

#include "headlight/scene_loader.hpp"
#include "support/gl.hpp"

using namespace headlight;
using namespace headlight::test;

namespace {

// Mean over geometry pixels of ssgi.exr's channel `channel` (0..3 the near
// field, 4 the sky visibility, 5..7 the light from beyond R).
double geometryMean(const Frame& frame, int channel) {
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < frame.ssgi.height; ++y)
    for (int x = 0; x < frame.ssgi.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      sum += frame.ssgi.at(x, y, channel);
      ++count;
    }
  REQUIRE(count > 0);
  return sum / count;
}

double geometryRmse(const Frame& a, const Frame& b, int channel) {
  double sum = 0.0;
  int count = 0;
  for (int y = 0; y < a.ssgi.height; ++y)
    for (int x = 0; x < a.ssgi.width; ++x) {
      if (a.position.at(x, y, 3) == 0.0f) continue;
      const double d = double(a.ssgi.at(x, y, channel)) - double(b.ssgi.at(x, y, channel));
      sum += d * d;
      ++count;
    }
  REQUIRE(count > 0);
  return std::sqrt(sum / count);
}

RenderSettings bitmaskSettings() {
  RenderSettings settings = smallSettings(128, 128);
  settings.ssgi.method = SsgiMethod::Bitmask;
  return settings;
}

}  // namespace

TEST_CASE("bitmask SSGI, two resolutions: the near field is exactly a run's without sky steps") {
  RenderSettings split = bitmaskSettings();
  REQUIRE(split.ssgi.farResolution == SsgiResolution::Half);
  REQUIRE(split.ssgi.skyStepCount > 0);
  RenderSettings nearOnly = bitmaskSettings();
  nearOnly.ssgi.skyStepCount = 0;  // one pass, no far field: the sky is the AO within R
  const Scene scene = loadScene("builtin:cornell");
  const Frame withFar = renderFresh(scene, split);
  const Frame without = renderFresh(scene, nearOnly);
  REQUIRE(withFar.ssgi.pixels.size() == without.ssgi.pixels.size());
  for (int channel = 0; channel < 4; ++channel) {
    CAPTURE(channel);
    CHECK(geometryRmse(withFar, without, channel) == 0.0);
  }
  // The far field is there: beyond R the box is closed on five sides.
  CHECK(geometryMean(withFar, 4) < geometryMean(without, 4) - 0.05);
  CHECK(geometryMean(withFar, 5) > 0.01);
}

TEST_CASE("bitmask SSGI, two resolutions: the far field stays close to the single full-resolution pass's") {
  RenderSettings split = bitmaskSettings();
  RenderSettings single = bitmaskSettings();
  single.ssgi.farResolution = SsgiResolution::Full;
  const Scene scene = loadScene("builtin:cornell");
  const Frame half = renderFresh(scene, split);
  const Frame full = renderFresh(scene, single);
  // Measured on cornell at 128x128 (half / full): sky visibility mean 0.379
  // / 0.373, RMSE between them 0.020; light from beyond R, mean R, G, B
  // 0.386 / 0.401, 0.299 / 0.299, 0.188 / 0.187 (per pixel the two differ
  // by the full pass's noise, which its 7x7 blur leaves: RMSE 0.11 to 0.22).
  // Tolerances about twice what was measured.
  const double skyHalf = geometryMean(half, 4), skyFull = geometryMean(full, 4);
  CHECK(std::abs(skyHalf - skyFull) < 0.015);
  CHECK(geometryRmse(half, full, 4) < 0.04);
  for (int channel = 5; channel < 8; ++channel) {
    CAPTURE(channel);
    const double a = geometryMean(half, channel), b = geometryMean(full, channel);
    REQUIRE(b > 0.1);
    CHECK(std::abs(a - b) / b < 0.08);
  }
}

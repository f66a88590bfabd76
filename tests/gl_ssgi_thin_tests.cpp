// GL tests of the bitmask SSGI's slabs (issue 16, item 3): a sample within R
// stands for the stretch of screen up to the next step, and its slab is at
// least as deep as that stretch is wide, so an object thinner on screen than
// the gap between steps still hides the angle it covers.
#include <doctest/doctest.h>

#include "headlight/reference.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "support/gl.hpp"
#include "tooling/bench.hpp"

using namespace headlight;
using namespace headlight::test;

TEST_CASE("bitmask SSGI: thin slats occlude the wall behind them as the reference says" *
          doctest::skip(!HEADLIGHT_HAS_EMBREE)) {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:slats"));  // bars 0.04 wide, 1-2 pixels at 128x128
  RenderSettings settings = smallSettings(128, 128);
  settings.ssgi.radiusFraction = 0.1f;  // issue 16's AO target is at R = 0.1 diag
  const Frame frame = renderer.render(settings);
  ReferenceSettings reference;
  reference.samplesPerPixel = 256;  // AO standard error <= 0.031 per pixel
  reference.radius = *frame.settings.ssgi.radius;
  const ReferenceImages truth = traceReference(renderer.scene(), frame, reference);
  const ErrorStats ao = maskedError(frame.ssgi, 0, truth.ao, 0, frame.position);
  CAPTURE(ao.rmse);
  CAPTURE(ao.referenceMean);
  // Measured 0.058 (`headlight render builtin:slats --width 128 --height 128
  // --ssgi-radius-fraction 0.1` against a 256-ray reference); 0.126 with
  // slabs only the scene's thickness deep (the commit before). 0.08: issue
  // 16's target, which that fails.
  CHECK(ao.rmse < 0.08);
  // The mean over geometry pixels: measured +0.027 (under-occluded), +0.091
  // before. Deeper slabs must not overshoot into over-darkening either.
  double ssgiSum = 0.0, truthSum = 0.0;
  long long pixels = 0;
  for (int y = 0; y < frame.ssgi.height; ++y)
    for (int x = 0; x < frame.ssgi.width; ++x)
      if (frame.position.at(x, y, 3) > 0.0f) {
        ssgiSum += frame.ssgi.at(x, y, 0);
        truthSum += truth.ao.at(x, y, 0);
        ++pixels;
      }
  REQUIRE(pixels > 5000);
  const double meanSigned = (ssgiSum - truthSum) / double(pixels);
  CAPTURE(meanSigned);
  CHECK(meanSigned < 0.05);
  CHECK(meanSigned > -0.03);
}

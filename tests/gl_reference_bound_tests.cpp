// The reference's screen-space bound (ReferenceSettings::screenBound): within
// R only the surfaces the frame shows occlude and send light. It casts the
// same rays as the truth, so per pixel it can only open what the truth
// found covered and drop light the truth gathered, never add any.
#include <doctest/doctest.h>

#include "headlight/reference.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "support/gl.hpp"

using namespace headlight;
using namespace headlight::test;

TEST_CASE("reference screen bound: within R, surfaces hidden from the camera neither occlude nor send light" *
          doctest::skip(!HEADLIGHT_HAS_EMBREE)) {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:spheres"));  // balls on a floor: the floor under a ball is hidden
  const Frame frame = renderer.render(smallSettings(96, 96));
  ReferenceSettings reference;
  reference.samplesPerPixel = 64;
  reference.radius = *frame.settings.ssgi.radius;
  const ReferenceImages truth = traceReference(renderer.scene(), frame, reference);
  reference.screenBound = true;
  const ReferenceImages bound = traceReference(renderer.scene(), frame, reference);

  int opened = 0, geometry = 0;
  double truthWithinR = 0, boundWithinR = 0;
  for (int y = 0; y < frame.position.height; ++y)
    for (int x = 0; x < frame.position.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      ++geometry;
      CAPTURE(x);
      CAPTURE(y);
      // ao.Y: open within R; the same rays, some of them opened.
      REQUIRE(bound.ao.at(x, y, 0) >= truth.ao.at(x, y, 0));
      if (bound.ao.at(x, y, 0) > truth.ao.at(x, y, 0)) ++opened;
      // sky.Y: which rays escape does not change.
      REQUIRE(bound.ao.at(x, y, 1) == truth.ao.at(x, y, 1));
      for (int c = 0; c < 3; ++c) {
        // indirectR: the light from within R, a subset of the truth's rays' light.
        REQUIRE(bound.indirect.at(x, y, c) <= truth.indirect.at(x, y, c) + 1e-6f);
        truthWithinR += truth.indirect.at(x, y, c);
        boundWithinR += bound.indirect.at(x, y, c);
      }
    }
  CAPTURE(opened);
  CAPTURE(geometry);
  CAPTURE(boundWithinR / truthWithinR);
  // The balls' lower halves and the floor round their feet meet surfaces
  // the camera cannot see. Measured at 96x96, 64 rays: 1545 of 5632
  // geometry pixels opened, the within-R light 0.902 of the truth's. A
  // bound that hid nothing, or most things, fails.
  CHECK(opened > geometry / 10);
  CHECK(boundWithinR < 0.97 * truthWithinR);
  CHECK(boundWithinR > 0.5 * truthWithinR);
}

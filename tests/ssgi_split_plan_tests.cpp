// The frame plan's two SSGI resolutions (GL-free): when the bitmask
// method's far field gets its own pass, at which divisor, and which
// attachments that adds.
#include <doctest/doctest.h>

#include <algorithm>

#include "frame/frame_plan.hpp"
#include "support/plan_settings.hpp"

using namespace headlight;

namespace {

FramePlan planWith(const RenderSettings& settings) { return planFrame(SceneSummary{}, settings, {}); }

}  // namespace

TEST_CASE("SSGI plan: by default the far field is its own pass at half resolution, the near field at full") {
  const FramePlan plan = planWith(test::resolvedPlanSettings());
  REQUIRE(plan.ssgi);
  CHECK(plan.ssgi->downsample == 1);
  CHECK(plan.ssgi->farDownsample == 2);
  CHECK(plan.ssgi->splitsFarField());
  CHECK(plan.divisorOf(Attachment::SsgiRaw) == 1);
  CHECK(plan.divisorOf(Attachment::SsgiRawSky) == 2);
  CHECK(plan.divisorOf(Attachment::SsgiFarSky) == 2);
  CHECK(plan.divisorOf(Attachment::Ssgi) == 1);  // what the composite reads and ssgi.exr holds: the image's size
  CHECK(plan.divisorOf(Attachment::SsgiSky) == 1);
  CHECK(plan.allocates(Attachment::SsgiFarSky));
  // The far field's passes are timed with the SSGI pass and its blur.
  CHECK(plan.passNames() == std::vector<std::string_view>{"virtual-lights", "sky", "gbuffer", "direct", "ssgi-surface",
                                                          "ssgi", "ssgi-blur", "composite", "antialias", "readback"});
}

TEST_CASE("SSGI plan: the far field's divisor follows ssgi-far-resolution, never finer than ssgi-resolution") {
  struct Case {
    SsgiResolution near, far;
    int nearDivisor, farDivisor;
  };
  for (const Case c :
       {Case{SsgiResolution::Full, SsgiResolution::Quarter, 1, 4},
        Case{SsgiResolution::Half, SsgiResolution::Quarter, 2, 4},
        Case{SsgiResolution::Half, SsgiResolution::Half, 2, 2}, Case{SsgiResolution::Half, SsgiResolution::Full, 2, 2},
        Case{SsgiResolution::Full, SsgiResolution::Full, 1, 1}}) {
    CAPTURE(int(c.near));
    CAPTURE(int(c.far));
    RenderSettings settings = test::resolvedPlanSettings();
    settings.ssgi.resolution = c.near;
    settings.ssgi.farResolution = c.far;
    const FramePlan plan = planWith(settings);
    REQUIRE(plan.ssgi);
    CHECK(plan.divisorOf(Attachment::SsgiRaw) == c.nearDivisor);
    CHECK(plan.divisorOf(Attachment::SsgiRawSky) == c.farDivisor);
    CHECK(plan.ssgi->splitsFarField() == (c.farDivisor > c.nearDivisor));
    CHECK(plan.allocates(Attachment::SsgiFarSky) == (c.farDivisor > c.nearDivisor));
  }
}

TEST_CASE("SSGI plan: no far-field pass without sky steps, without the blur, or for the kernel methods") {
  RenderSettings noSkySteps = test::resolvedPlanSettings();
  noSkySteps.ssgi.skyStepCount = 0;
  RenderSettings noBlur = test::resolvedPlanSettings();
  noBlur.ssgi.blur = false;
  RenderSettings kernel = test::resolvedPlanSettings();
  kernel.ssgi.method = SsgiMethod::Radiance;
  for (const RenderSettings& settings : {noSkySteps, noBlur, kernel}) {
    const FramePlan plan = planWith(settings);
    REQUIRE(plan.ssgi);
    CHECK(!plan.ssgi->splitsFarField());
    CHECK(plan.ssgi->farDownsample == plan.ssgi->downsample);
    CHECK(!plan.allocates(Attachment::SsgiFarSky));
  }
}

TEST_CASE("SSGI plan: the bitmask method's far field gathers from virtual lights; the kernel methods have none") {
  RenderSettings settings = test::resolvedPlanSettings();
  REQUIRE(settings.ssgi.method == SsgiMethod::Bitmask);
  settings.ssgi.virtualLightCount = 512;
  CHECK(planWith(settings).ssgi->virtualLights == 512);
  settings.ssgi.virtualLightCount = 0;
  CHECK(planWith(settings).ssgi->virtualLights == 0);
  const auto names = planWith(settings).passNames();
  CHECK(std::find(names.begin(), names.end(), "virtual-lights") == names.end());
  settings.ssgi.virtualLightCount = 512;
  for (SsgiMethod kernel : {SsgiMethod::Hemisphere, SsgiMethod::Radiance}) {
    settings.ssgi.method = kernel;
    CHECK(planWith(settings).ssgi->virtualLights == 0);
  }
}

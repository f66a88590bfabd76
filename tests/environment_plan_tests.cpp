// The frame plan with and without an environment map (no GL): the map's
// tables and composite variant exist only when a map is given, and replace
// the sky's.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "support/plan_settings.hpp"
#include "frame/frame_plan.hpp"

namespace headlight {
namespace {

using test::skips;

bool runs(const FramePlan& plan, std::string_view pass) {
  const auto names = plan.passNames();
  return std::find(names.begin(), names.end(), pass) != names.end();
}

}  // namespace

TEST_CASE("frame plan: an environment map's tables and variant exist only with a map, in place of the sky's") {
  SceneSummary withMap;
  withMap.environment = true;
  const FramePlan mapped = planFrame(withMap, test::resolvedPlanSettings(), {});
  CHECK(mapped.environmentTables);
  CHECK(!mapped.skyTables);
  REQUIRE(mapped.composite);
  CHECK(mapped.composite->sky);
  CHECK(mapped.composite->environment);
  CHECK(runs(mapped, "environment"));
  CHECK(!runs(mapped, "sky"));

  const FramePlan plain = planFrame(SceneSummary{}, test::resolvedPlanSettings(), {});
  CHECK(!plain.environmentTables);
  CHECK(plain.skyTables);
  CHECK(!plain.composite->environment);
  CHECK(!runs(plain, "environment"));

  // Intensity 0: no tables and no ambient term, named; the sky's intensity
  // no longer matters.
  RenderSettings dark = test::resolvedPlanSettings();
  dark.lighting.environmentIntensity = 0.0f;
  const FramePlan unlit = planFrame(withMap, dark, {});
  CHECK(!unlit.environmentTables);
  CHECK(!unlit.composite->sky);
  CHECK(skips(unlit, "sky", "environment intensity 0"));
  RenderSettings noSky = test::resolvedPlanSettings();
  noSky.lighting.skyIntensity = 0.0f;
  CHECK(planFrame(withMap, noSky, {}).environmentTables);

  // Only G-buffer targets: no tables either.
  const std::vector<std::string> normalOnly{"normal"};
  CHECK(!planFrame(withMap, test::resolvedPlanSettings(), normalOnly).environmentTables);
}

}  // namespace headlight

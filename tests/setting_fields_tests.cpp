// The block members that carry settings (glsl/shared_layout.h's
// HL_SETTING_FIELDS) are filled from the settings table: every listed member
// gets its row's value, and a row that is still auto is refused by name.
#include <doctest/doctest.h>

#include <string>
#include <type_traits>

#include "headlight/error.hpp"
#include "settings/setting_fields.hpp"

namespace headlight {
namespace {

// Resolved settings with every listed row away from its default, so a
// member left unfilled (0 in a zeroed block) cannot pass.
RenderSettings unusualSettings() {
  RenderSettings settings;
  settings.ssgi.radius = 0.75f;
  settings.ssgi.bias = 0.03f;
  settings.ssgi.thickness = 0.2f;
  settings.ssgi.intensity = 1.5f;
  settings.ssgi.indirectStrength = 0.8f;
  settings.ssgi.sliceCount = 3;
  settings.ssgi.stepCount = 5;
  settings.ssgi.skyStepCount = 7;
  return settings;
}

// The block of type B among the two.
template <class B>
B& blockOf(gpu::SsgiBlock& kernel, gpu::SsgiBitmaskBlock& bitmask) {
  if constexpr (std::is_same_v<B, gpu::SsgiBlock>)
    return kernel;
  else
    return bitmask;
}

}  // namespace

TEST_CASE("setting fields: every HL_SETTING_FIELDS member holds its row's value") {
  const RenderSettings settings = unusualSettings();
  gpu::SsgiBlock kernel{};
  gpu::SsgiBitmaskBlock bitmask{};
  fillSettingFields(kernel, settings);
  fillSettingFields(bitmask, settings);
  int checked = 0;
#define HL_CHECK_SETTING_FIELD(BlockType, member, row)                                       \
  {                                                                                           \
    CAPTURE(#BlockType "." #member);                                                          \
    const double expected = settingNumber(settings, #row);                                    \
    CHECK(double(blockOf<gpu::BlockType>(kernel, bitmask).member) == doctest::Approx(expected)); \
    CHECK(expected != 0.0);                                                                   \
    ++checked;                                                                                \
  }
  HL_SETTING_FIELDS(HL_CHECK_SETTING_FIELD)
#undef HL_CHECK_SETTING_FIELD
  CHECK(checked == 11);
  CHECK(bitmask.sliceCount == 3);
  CHECK(bitmask.thicknessWorld == 0.2f);
  CHECK(kernel.biasWorld == 0.03f);
}

TEST_CASE("setting fields: an auto value, a choice or an unknown row is refused by name") {
  RenderSettings settings = unusualSettings();
  settings.ssgi.radius.reset();
  gpu::SsgiBitmaskBlock block{};
  CHECK_THROWS_WITH_AS(fillSettingFields(block, settings), doctest::Contains("ssgi-radius: still auto"),
                       SettingsError);
  CHECK_THROWS_WITH_AS(settingNumber(settings, "ssgi-method"), doctest::Contains("not a number"), SettingsError);
  CHECK_THROWS_AS(settingNumber(settings, "ssgi-no-such-row"), SettingsError);
  CHECK(settingNumber(settings, "ssgi-blur") == 1.0);  // a Bool row: 0 or 1
}

}  // namespace headlight

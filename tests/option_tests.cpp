// The option system: every row of the setting table round-trips through the
// CLI parser and the EXR metadata, help lists every row with its default,
// and the parser's rules (auto, on/off, ranges) hold for any row.
#include <doctest/doctest.h>

#include <cmath>

#include "bench_command.hpp"
#include "cli_options.hpp"
#include "headlight/output.hpp"
#include "headlight/settings.hpp"
#include "support/images.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;

namespace {

// A value of the row other than the default, as command-line text.
std::string otherValue(const OptionSpec& spec, const OptionValue& defaultValue) {
  const bool isAuto = std::holds_alternative<AutoValue>(defaultValue);
  switch (spec.type) {
    case OptionType::Bool:
      return std::get<bool>(defaultValue) ? "off" : "on";
    case OptionType::Choice:
      for (std::string_view choice : spec.choices)
        if (isAuto || choice != std::get<std::string>(defaultValue)) return std::string(choice);
      break;
    case OptionType::Int: {
      const auto low = std::int64_t(spec.minimum);
      return std::to_string(!isAuto && std::get<std::int64_t>(defaultValue) == low ? low + 1 : low);
    }
    case OptionType::Float: {
      // A value with no short decimal form, inside the range: formatting
      // must keep every bit for it to come back equal.
      const double value = spec.minimum + (spec.maximum - spec.minimum) / 3.0;
      return formatOptionValue(spec, double(float(value)));
    }
    default:
      break;
  }
  FAIL("no other value for --" << spec.name);
  return {};
}

// The command line that sets the row to `text`.
std::vector<std::string> flagFor(const OptionSpec& spec, const std::string& text) {
  if (spec.type == OptionType::Bool)
    return {text == "on" ? "--" + std::string(spec.name) : "--no-" + std::string(spec.name)};
  return {"--" + std::string(spec.name), text};
}

}  // namespace

TEST_CASE("every setting row round-trips through the CLI parser and the EXR metadata") {
  const RenderSettings defaults;
  const test::TempFolder folder("options");
  for (const Option<RenderSettings>& row : settingOptions()) {
    CAPTURE(row.spec.name);
    const OptionValue defaultValue = row.get(defaults);
    std::vector<std::string> texts{otherValue(row.spec, defaultValue)};
    if (!row.spec.autoMeaning.empty()) texts.push_back("auto");
    for (const std::string& text : texts) {
      CAPTURE(text);
      // CLI: the flag sets exactly this row, to exactly this value.
      const cli::RenderCommand command = cli::parseRenderArgs(flagFor(row.spec, text));
      CHECK(formatOptionValue(row.spec, row.get(command.settings)) == text);
      std::map<std::string, std::string> expected = settingsAsText(defaults);
      expected[std::string(row.spec.name)] = text;
      CHECK(settingsAsText(command.settings) == expected);
      if (text != "auto") CHECK(row.get(command.settings) != defaultValue);

      // EXR metadata: what a file records re-creates the same settings.
      Frame frame;
      frame.settings = command.settings;
      const auto path = folder.path() / "settings.exr";
      writeExr(frame, test::makeImage(2, 2, {"R", "G", "B"}), path, true);
      const std::map<std::string, std::string> recorded = readSettingAttributes(path);
      CHECK(recorded == expected);
      RenderSettings restored;
      applySettingsText(restored, recorded);
      CHECK(settingsAsText(restored) == expected);
    }
  }
}

TEST_CASE("help lists every setting row with its default, generated from the table") {
  const std::string renderHelp = cli::renderHelp();
  const std::string benchHelp = cli::benchHelp();
  const RenderSettings defaults;
  for (const Option<RenderSettings>& row : settingOptions()) {
    CAPTURE(row.spec.name);
    const std::string flag = (row.spec.type == OptionType::Bool ? "--[no-]" : "--") + std::string(row.spec.name);
    const auto at = renderHelp.find(flag + " ");
    REQUIRE(at != std::string::npos);
    // A long flag puts its help on the next line: the entry runs to the next flag.
    const std::string line = renderHelp.substr(at, renderHelp.find("\n  --", at) - at);
    CHECK(line.find("[default: " + formatOptionValue(row.spec, row.get(defaults)) + "]") != std::string::npos);
    CHECK(benchHelp.find(flag + " ") != std::string::npos);  // bench starts from any setting
  }
  CHECK(cli::renderHelp(cli::CommandKind::Reference).find("--reference-samples N") != std::string::npos);
  CHECK(renderHelp.find("--reference-samples") == std::string::npos);
}

TEST_CASE("parser rules hold for every row: ranges, auto, on/off, unknown names") {
  RenderSettings settings;
  for (const Option<RenderSettings>& row : settingOptions()) {
    CAPTURE(row.spec.name);
    const OptionSpec& spec = row.spec;
    if (spec.autoMeaning.empty()) CHECK_THROWS_AS(parseOptionValue(spec, "auto"), SettingsError);
    if (spec.type == OptionType::Int || spec.type == OptionType::Float) {
      const std::string below = formatOptionValue(spec, spec.minimum - 1.0);
      const std::string message = "--" + std::string(spec.name) + ": must be in";
      CHECK_THROWS_WITH_AS(row.set(settings, parseOptionValue(spec, below)), doctest::Contains(message.c_str()),
                           SettingsError);
      CHECK_THROWS_AS(parseOptionValue(spec, "nan"), SettingsError);
    }
    if (spec.type == OptionType::Bool) {
      CHECK(std::get<bool>(parseOptionValue(spec, "off")) == false);
      CHECK_THROWS_AS(parseOptionValue(spec, "maybe"), SettingsError);
    }
  }
  CHECK_THROWS_WITH_AS(applySettingsText(settings, {{"ssgi-radios", "1"}}),
                       doctest::Contains("unknown setting 'ssgi-radios'"), SettingsError);
}

TEST_CASE("validate() reads the table's ranges; the rules between settings stay") {
  RenderSettings settings;
  CHECK_NOTHROW(settings.validate());
  settings.ssgi.sampleCount = 65;
  CHECK_THROWS_WITH_AS(settings.validate(), "--ssgi-samples: must be in 1..64, got 65", SettingsError);
  settings = {};
  settings.ssgi.radius = -1.0f;
  CHECK_THROWS_WITH_AS(settings.validate(), doctest::Contains("--ssgi-radius: must be in"), SettingsError);
  settings = {};
  settings.ssgi.resolution = SsgiResolution::Half;
  settings.ssgi.blur = false;
  CHECK_THROWS_WITH_AS(settings.validate(), doctest::Contains("--no-ssgi-blur needs --ssgi-resolution full"),
                       SettingsError);
}

TEST_CASE("bench sweeps any setting row; the product skips what the settings refuse") {
  const cli::BenchCommand command =
      cli::parseBenchArgs({"--sweep", "ssgi-samples=4,8,16", "--sweep", "ssgi-resolution=full,half", "--sweep",
                           "ssgi-blur=on,off", "--ssgi-method", "radiance", "--reference-samples", "256"});
  CHECK(command.reference.samplesPerPixel == 256);
  const auto configs = cli::benchConfigs(command, 64, 48);
  // 3 x 2 x 2 = 12, less the 3 half-resolution configurations without blur, plus the seed.
  REQUIRE(configs.size() == 3 * 2 * 2 - 3 + 1);
  CHECK(configs.front().label == "ssgi-samples=4 ssgi-resolution=full ssgi-blur=on");
  for (std::size_t i = 0; i + 1 < configs.size(); ++i) {
    CAPTURE(configs[i].label);
    CHECK(configs[i].settings.ssgi.method == SsgiMethod::Radiance);  // the base settings
    CHECK(configs[i].settings.width == 64);
    CHECK_NOTHROW(configs[i].settings.validate());
  }
  CHECK(configs.back().seedDefault);
  CHECK(*configs.back().settings.ssgi.radius == 0.5f);

  auto usage = [](std::vector<std::string> args) {
    try {
      cli::parseBenchArgs(args);
    } catch (const SettingsError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  CHECK(usage({"--sweep", "ssgi-samples=4,99"}) == "--ssgi-samples: must be in 1..64, got 99");
  CHECK(usage({"--sweep", "bogus=1"}).find("unknown setting 'bogus'") != std::string::npos);
  CHECK(usage({"--sweep", "ssgi-samples"}).find("expected NAME=V1,V2") != std::string::npos);
  CHECK(usage({"--samples", "4"}).find("unknown option '--samples'") != std::string::npos);
}

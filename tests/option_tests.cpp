// The option system: every row of the setting table round-trips through the
// CLI parser and the EXR metadata, help lists every row with its default,
// and the parser's rules (auto, on/off, ranges) hold for any row.
#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <functional>
#include <map>
#include <set>
#include <stdexcept>

#include "bench_command.hpp"
#include "cli_options.hpp"
#include "headlight/output.hpp"
#include "headlight/reference.hpp"
#include "headlight/settings.hpp"
#include "support/encoding.hpp"
#include "support/images.hpp"
#include "support/process.hpp"
#include "support/temp_folder.hpp"
#include "tune_command.hpp"

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
    case OptionType::Text:
      if (!spec.example.empty()) return std::string(spec.example);
      break;
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
      const std::string message = std::string(spec.name) + ": must be in";
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

// The library's messages name settings, never flags; Error::settings() lists
// them, and the CLI words them as flags (commandLineMessage).
static std::string messageOf(const std::function<void()>& call, std::vector<std::string>* settings = nullptr,
                             std::string* commandLine = nullptr) {
  try {
    call();
  } catch (const Error& error) {
    if (settings) *settings = error.settings();
    if (commandLine) *commandLine = commandLineMessage(error);
    return error.what();
  }
  return "no error";
}

TEST_CASE("validate() reads the table's ranges; the rules between settings stay") {
  RenderSettings settings;
  CHECK_NOTHROW(settings.validate());
  settings.ssgi.sampleCount = 65;
  std::vector<std::string> named;
  std::string flags;
  CHECK(messageOf([&] { settings.validate(); }, &named, &flags) == "ssgi-samples: must be in 1..64, got 65");
  CHECK(named == std::vector<std::string>{"ssgi-samples"});
  CHECK(flags == "--ssgi-samples: must be in 1..64, got 65");
  settings = {};
  settings.ssgi.radius = -1.0f;
  CHECK_THROWS_WITH_AS(settings.validate(), doctest::Contains("ssgi-radius: must be in"), SettingsError);
  settings = {};
  settings.ssgi.resolution = SsgiResolution::Half;
  settings.ssgi.blur = false;
  CHECK(messageOf([&] { settings.validate(); }, &named, &flags).find("ssgi-blur off needs ssgi-resolution full") == 0);
  CHECK(named == std::vector<std::string>{"ssgi-blur", "ssgi-resolution"});
  CHECK(flags.find("--ssgi-blur off needs --ssgi-resolution full") == 0);
  settings = {};
  settings.width = 8193;
  settings.height = 8193;
  CHECK(messageOf([&] { settings.validate(); }, &named, &flags).find("width 8193 x height 8193: at most") == 0);
  CHECK(flags.find("--width 8193 x --height 8193: at most") == 0);
}

TEST_CASE("commandLineMessage words only the settings an error names, and only where they stand alone") {
  CHECK(commandLineMessage(SettingsError("camera 3: a/camera.gltf has 1 camera(s)", {"camera"})) ==
        "--camera 3: a/camera.gltf has 1 camera(s)");
  CHECK(commandLineMessage(
            LimitError("x.gltf: 9 MiB, more than max-memory allows (8 MiB); raise max-memory", {"max-memory"})) ==
        "x.gltf: 9 MiB, more than --max-memory allows (8 MiB); raise --max-memory");
  CHECK(commandLineMessage(SettingsError("width 3: too small")) == "width 3: too small");  // names nothing
  CHECK(commandLineMessage(std::runtime_error("camera 3")) == "camera 3");
  RenderSettings settings;
  applyPreset(settings, "default");
  std::vector<std::string> named;
  CHECK(messageOf([&] { applyPreset(settings, "slow"); }, &named).find("preset: expected one of") == 0);
  CHECK(named == std::vector<std::string>{"preset"});
}

TEST_CASE("bench's default sweep measures every method, the default (bitmask) among them") {
  const auto configs = cli::benchConfigs(cli::parseBenchArgs({}), 64, 48);
  std::map<SsgiMethod, int> perMethod;
  for (const cli::BenchConfig& config : configs)
    if (!config.seedDefault) ++perMethod[config.settings.ssgi.method];
  CHECK(perMethod[SsgiMethod::Hemisphere] > 0);
  CHECK(perMethod[SsgiMethod::Radiance] > 0);
  // Bitmask over slices x steps x radii x resolutions; sample counts do not apply to it.
  CHECK(perMethod[SsgiMethod::Bitmask] == 3 * 2 * 3 * 2);
  for (const cli::BenchConfig& config : configs)
    if (config.settings.ssgi.method == SsgiMethod::Bitmask)
      CHECK(config.label.find("ssgi-samples") == std::string::npos);
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

TEST_CASE("a settings file round-trips every row it holds, and leaves the size and camera alone") {
  RenderSettings tuned;
  tuned.ssgi.sliceCount = 3;
  tuned.ssgi.stepCount = 11;
  tuned.ssgi.thickness = 0.123456789f;
  tuned.ssgi.resolution = SsgiResolution::Half;
  tuned.lighting.skyIntensity = 0.0f;
  tuned.width = 999;
  const std::string comments[] = {"tune: ao-rmse = 0.04"};
  const std::string text = settingsFileText(tuned, comments);
  CHECK(text.rfind("# tune: ao-rmse = 0.04\n", 0) == 0);
  RenderSettings read;
  read.width = 32;
  applySettingsFileText(read, text, "t.settings");
  CHECK(read.width == 32);
  auto expected = settingsAsText(tuned), actual = settingsAsText(read);
  expected.erase("width");
  actual.erase("width");
  CHECK(actual == expected);
  CHECK(*read.ssgi.thickness == tuned.ssgi.thickness);  // 9 significant digits: exact
}

TEST_CASE("settings file lines: spaces, comments and CRLF are accepted; a bad line names file and line") {
  RenderSettings settings;
  applySettingsFileText(settings, "  # note\r\n\r\n ssgi-steps=9 \r\nssgi-blur = off\r\n", "w.settings");
  CHECK(settings.ssgi.stepCount == 9);
  CHECK(!settings.ssgi.blur);
  CHECK_THROWS_WITH_AS(applySettingsFileText(settings, "ssgi-steps = 9\n= 3\n", "w.settings"),
                       doctest::Contains("w.settings:2: expected NAME = VALUE"), SettingsError);
  CHECK_THROWS_WITH_AS(applySettingsFileText(settings, "ssgi-steps = 99\n", "w.settings"),
                       doctest::Contains("w.settings:1: ssgi-steps: must be in"), SettingsError);
}

TEST_CASE("tune chooses the least frame time among the rows within the AO bound") {
  std::vector<BenchRow> rows(4);
  const double ms[] = {10, 20, 5, 40}, rmse[] = {0.08, 0.04, 0.06, 0.02};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i].frameMs.median = ms[i];
    rows[i].ao.rmse = rmse[i];
  }
  CHECK(cli::cheapestWithin(rows, 0.05) == std::optional<std::size_t>(1));
  CHECK(cli::cheapestWithin(rows, 0.06) == std::optional<std::size_t>(2));  // the bound is inclusive
  CHECK(cli::cheapestWithin(rows, 1.0) == std::optional<std::size_t>(2));
  CHECK(!cli::cheapestWithin(rows, 0.01));
}

TEST_CASE("tune --max-flip bounds lit's HDR-FLIP, alone or with the AO bound") {
  std::vector<BenchRow> rows(4);
  const double ms[] = {10, 20, 5, 40}, rmse[] = {0.08, 0.04, 0.06, 0.02}, flip[] = {0.1, 0.3, 0.2, 0.05};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    rows[i].frameMs.median = ms[i];
    rows[i].ao.rmse = rmse[i];
    rows[i].litFlip = flip[i];
  }
  CHECK(cli::cheapestWithin(rows, std::nullopt, 0.15) == std::optional<std::size_t>(0));
  CHECK(cli::cheapestWithin(rows, std::nullopt, 0.2) == std::optional<std::size_t>(2));  // inclusive
  CHECK(cli::cheapestWithin(rows, 0.05, 0.2) == std::optional<std::size_t>(3));          // both must hold
  CHECK(!cli::cheapestWithin(rows, std::nullopt, 0.01));
  CHECK(cli::parseTuneArgs({"--max-flip", "0.1"}).maxFlip == 0.1);
  CHECK_THROWS_WITH_AS(cli::parseTuneArgs({"--max-flip", "2"}), doctest::Contains("--max-flip"), SettingsError);
}

TEST_CASE("tune's default candidates are the bitmask method's, around the scene's auto thickness") {
  const auto sweeps = cli::defaultTuneSweeps(0.4f);
  const auto configs = cli::sweepConfigs(RenderSettings{}, sweeps, 128, 128);
  // 3 slice counts x 4 step counts x 3 thicknesses x 2 resolutions x 2 frame counts.
  CHECK(configs.size() == 3 * 4 * 3 * 2 * 2);
  std::set<float> thicknesses;
  for (const auto& config : configs) {
    CHECK(config.settings.ssgi.method == SsgiMethod::Bitmask);
    CHECK(config.settings.width == 128);
    if (config.settings.ssgi.thickness) thicknesses.insert(*config.settings.ssgi.thickness);
  }
  CHECK(thicknesses == std::set<float>{0.2f, 0.8f});
}

// Every command that loads a scene loads it through loadCommandScene with
// --allow-external-paths and the limits (tools/support: command_setup), so a
// scene render refuses, reference, bench and tune refuse with the same exit
// code and message (bench and tune once called loadScene(name) without them).
TEST_CASE("render, reference, bench and tune refuse a scene over a limit or with an external URI alike") {
  test::TempFolder folder("scene-input");
  // Two triangles; one with its buffer outside the asset folder.
  std::vector<float> positions{0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 2, 1, 0, 1, 2, 0};
  std::vector<unsigned char> bytes(positions.size() * sizeof(float));
  std::memcpy(bytes.data(), positions.data(), bytes.size());
  auto gltf = [&](const std::string& uri) {
    return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
           R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
           R"("accessors":[{"bufferView":0,"componentType":5126,"count":6,"type":"VEC3","min":[0,0,0],"max":[2,2,0]}],)"
           R"("bufferViews":[{"buffer":0,"byteLength":72}],"buffers":[{"byteLength":72,"uri":")" +
           uri + R"("}]})";
  };
  const std::string inside =
      folder.write("assets/two.gltf", gltf("data:application/octet-stream;base64," + test::base64(bytes))).string();
  const std::string outside = folder.write("assets/outside.gltf", gltf("../outside.bin")).string();
  const std::string out = test::shellQuote((folder.path() / "out").string());

  struct Case {
    std::string scene, flags, expected;
  };
  const Case cases[] = {
      {inside, "--max-triangles 1", "(3 x --max-triangles 1) allowed; raise --max-triangles"},
      {outside, "", "outside the asset folder"},
      {outside, "--allow-external-paths", "outside.bin"},  // let through, then not found
  };
  for (const Case& c : cases) {
    CAPTURE(c.flags);
    const std::string args = test::shellQuote(c.scene) + " " + c.flags + " --out " + out;
    const test::ProcessResult render = test::runHeadlight("render " + args);
    INFO(render.output);
    CHECK(render.exitCode == 1);
    CHECK(render.output.find(c.expected) != std::string::npos);
    if (c.flags == "--allow-external-paths") CHECK(render.output.find("outside the asset folder") == std::string::npos);
    if (!referenceAvailable()) {
      MESSAGE("reference, bench and tune need Embree, which this build lacks: their part is not checked");
      continue;
    }
    for (const std::string command : {"reference", "bench", "tune --max-ao-error 1"}) {
      const test::ProcessResult run = test::runHeadlight(command + " " + args);
      CAPTURE(command);
      CHECK(run.exitCode == render.exitCode);
      CHECK(run.output == render.output);  // the same message, word for word
    }
    CHECK(!std::filesystem::exists(folder.path() / "out"));
  }
}

TEST_CASE("--verbose says per command what it prints, and bench prints the header it promises") {
  auto verboseLine = [](const std::string& help) {
    const auto at = help.find("  --verbose ");
    return at == std::string::npos ? std::string() : help.substr(at, help.find('\n', at) - at);
  };
  CHECK(verboseLine(cli::renderHelp()).find("each pass's time") != std::string::npos);
  CHECK(verboseLine(cli::renderHelp(cli::CommandKind::Reference)).find("the scene's size") != std::string::npos);
  CHECK(verboseLine(cli::benchHelp()).find("each scene's size") != std::string::npos);
  CHECK(verboseLine(cli::tuneHelp()).find("every configuration") != std::string::npos);
  for (const std::string& help : {cli::benchHelp(), cli::tuneHelp()})
    CHECK(verboseLine(help).find("each pass's time") == std::string::npos);  // neither prints pass times

  if (!referenceAvailable()) {
    MESSAGE("bench needs Embree, which this build lacks: its --verbose run is not checked");
    return;
  }
  test::TempFolder folder("bench-verbose");
  const test::ProcessResult run = test::runHeadlight(
      "bench builtin:cornell --verbose --resolutions 16x16 --sweep ssgi-samples=4 --repetitions 1 --warmup 0 "
      "--reference-samples 16 --no-chart --out " +
      test::shellQuote((folder.path() / "bench").string()));
  INFO(run.output);
  CHECK(run.exitCode == 0);
  CHECK(run.output.find("GL_RENDERER: ") != std::string::npos);
  CHECK(run.output.find("scene: builtin:cornell: 8 instances") != std::string::npos);
}

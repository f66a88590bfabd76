// `render` option parsing: table-driven flags, presets, "auto". No context
// needed, but the CLI's option table links the context code (GL), so these
// run in the gl executable.
#include <doctest/doctest.h>

#include "cli_options.hpp"
#include "headlight/error.hpp"

using namespace headlight;

TEST_CASE("render options: table-driven flags, presets, and clear errors") {
  using cli::parseRenderArgs;
  const auto command = parseRenderArgs({"scene.glb", "--width", "320", "--height=200", "--ssgi-samples", "16",
                                        "--ssgi-radius", "0.5", "--backend", "osmesa", "--no-shadows", "--out", "o"});
  CHECK(command.scene == "scene.glb");
  CHECK(command.settings.width == 320);
  CHECK(command.settings.height == 200);
  CHECK(command.settings.ssgi.sampleCount == 16);
  CHECK(command.settings.ssgi.radius == 0.5f);
  CHECK(command.context.backend == Backend::OSMesa);
  CHECK_FALSE(command.settings.lighting.shadows);
  CHECK(command.outDir == "o");
  CHECK(parseRenderArgs({}).scene == "builtin:cornell");

  const auto seed = parseRenderArgs({"--preset", "seed"});
  CHECK(seed.settings.ssgi.radius == 0.5f);
  CHECK(seed.settings.ssgi.bias == 0.025f);
  // The seed's method and constants, whatever the default has become.
  CHECK(seed.settings.ssgi.method == SsgiMethod::Hemisphere);
  CHECK(seed.settings.ssgi.sampleCount == 64);
  CHECK(seed.settings.ssgi.intensity == 1.0f);
  CHECK(seed.settings.ssgi.resolution == SsgiResolution::Full);
  CHECK(parseRenderArgs({}).settings.ssgi.method == SsgiMethod::Bitmask);
  CHECK(parseRenderArgs({"--preset", "fast"}).settings.ssgi.sliceCount == 1);
  CHECK(parseRenderArgs({"--preset", "fast", "--ssgi-samples", "8"}).settings.ssgi.sampleCount == 8);

  auto message = [](std::vector<std::string> args) {
    try {
      parseRenderArgs(args);
    } catch (const SettingsError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  CHECK(message({"--width", "0"}) == "--width: must be in 1..16384, got 0");
  CHECK(message({"--width", "abc"}) == "--width: expected an integer in 1..16384, got 'abc'");
  CHECK(message({"--ssgi-samples", "65"}) == "--ssgi-samples: must be in 1..64, got 65");
  CHECK(message({"--ssgi-radius", "x"}) == "--ssgi-radius: expected auto or a number in 1e-09..1e+09, got 'x'");
  CHECK(message({"--bogus"}).find("unknown option '--bogus'") != std::string::npos);
  CHECK(message({"--width"}) == "--width needs a value (N)");
  CHECK(message({"--backend", "vulkan"}).find("expected one of auto, egl, osmesa") != std::string::npos);
  CHECK(message({"--ssgi-method", "horizon"}) ==
        "--ssgi-method: expected one of hemisphere, radiance, bitmask, got 'horizon'");
  CHECK(message({"--reference-samples", "8"}).find("unknown option") != std::string::npos);  // reference only
  CHECK(parseRenderArgs({"a.glb", "b.glb", "jobs.jsonl"}).scenes.size() == 2);  // a batch
  CHECK(parseRenderArgs({"a.glb", "b.glb", "jobs.jsonl"}).jobFiles.size() == 1);
  CHECK_THROWS_WITH(parseRenderArgs({"a.glb", "b.glb"}, cli::CommandKind::Reference),
                    doctest::Contains("more than one scene"));
  CHECK(message({"--views", "4"}).find("needs --orbit") != std::string::npos);
  CHECK(message({"--shard", "3/3"}).find("expected 0 <= I < N") != std::string::npos);
  CHECK(message({"--targets", "lit,glow"}).find("unknown target 'glow'") != std::string::npos);
  // Every target in the list of known ones (it had fallen behind by eight).
  CHECK(message({"--targets", "glow"}).find("specular, clearcoat, ids, preview)") != std::string::npos);
  CHECK(message({"--no-ssgi=1"}) == "--no-ssgi takes no value");
  // A long value is quoted by its start and its size, not echoed whole (issue 32: 100 KB messages).
  const std::string longValue(100000, 'x');
  for (const char* flag : {"--width", "--ssgi-method", "--targets", "--png"}) {
    CAPTURE(flag);
    const std::string text = message({flag, longValue});
    CHECK(text.size() < 400);
    CHECK(text.find("...' (100000 bytes)") != std::string::npos);
  }
}

TEST_CASE("\"auto\" is its own value: 0 is a number like any other") {
  using cli::parseRenderArgs;
  // The old sentinel encoding turned --ssgi-bias 0 into 5% of the radius.
  const auto zeroBias = parseRenderArgs({"--ssgi-bias", "0"});
  REQUIRE(zeroBias.settings.ssgi.bias.has_value());
  CHECK(*zeroBias.settings.ssgi.bias == 0.0f);
  CHECK_FALSE(parseRenderArgs({"--ssgi-bias", "auto"}).settings.ssgi.bias.has_value());
  CHECK_FALSE(RenderSettings{}.ssgi.bias.has_value());
  // A row that cannot be auto refuses it.
  CHECK_THROWS_WITH_AS(parseRenderArgs({"--ssgi-samples", "auto"}),
                       "--ssgi-samples: expected an integer in 1..64, got 'auto'", SettingsError);
}

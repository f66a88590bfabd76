// `headlight tune`, `render --settings FILE` and the skipped passes in
// `--verbose`, as a user runs them.
#include <doctest/doctest.h>

#include <OpenImageIO/imagebuf.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/process.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;

using headlight::test::freshFolder;
using headlight::test::runHeadlight;
using Run = headlight::test::ProcessResult;

namespace {

using headlight::test::quote;

std::string readText(const fs::path& path) {
  std::ifstream file(path);
  std::ostringstream text;
  text << file.rdbuf();
  return text.str();
}

// The number after "# tune: <key> = " in a settings file; -1 when absent.
double recorded(const std::string& text, const std::string& key) {
  const std::string marker = "# tune: " + key + " = ";
  const auto at = text.find(marker);
  return at == std::string::npos ? -1.0 : std::stod(text.substr(at + marker.size()));
}

// The value `name = value` sets in a settings file ("" when absent).
std::string fileValue(const std::string& text, const std::string& name) {
  const auto at = text.find("\n" + name + " = ");
  if (at == std::string::npos) return {};
  const auto start = at + name.size() + 4;
  return text.substr(start, text.find('\n', start) - start);
}

std::string settingIn(const fs::path& exr, const std::string& name) {
  OIIO::ImageBuf image(exr.string());
  REQUIRE(image.init_spec(exr.string(), 0, 0));
  return image.spec().get_string_attribute("headlight:setting:" + name);
}

// A tiny tune: 32 x 32, 4 candidates, 64 reference rays, one timed frame.
const std::string kTinyTune =
    " --width 32 --height 32 --sweep ssgi-slices=1,2 --sweep ssgi-steps=4,8 --reference-samples 64"
    " --repetitions 1 --warmup 0";

}  // namespace

#if HEADLIGHT_HAS_EMBREE
TEST_CASE("tune writes the cheapest configuration within the bound, with its error, and render --settings uses it") {
  const fs::path folder = freshFolder("tune");
  const fs::path file = folder / "cornell.settings";
  // 0.2: above every candidate's AO RMSE (about 0.1 at 32 x 32), so one is
  // chosen whatever the timing noise, and below no SSGI's (about 0.3), which
  // tune measures beside them and would otherwise choose when it times fastest.
  const Run tune =
      runHeadlight("tune builtin:cornell --max-ao-error 0.2" + kTinyTune + " --out " + quote(file.string()));
  INFO(tune.output);
  REQUIRE(tune.exitCode == 0);
  const std::string text = readText(file);
  INFO(text);
  const double error = recorded(text, "ao-rmse");
  CHECK(error > 0.0);  // a measured error: SSGI is never exact against the reference
  CHECK(error <= 0.2);
  CHECK(recorded(text, "max-ao-error") == doctest::Approx(0.2));
  CHECK(recorded(text, "frame-ms") > 0.0);
  CHECK(text.find("\nwidth = ") == std::string::npos);  // a size is each render's own
  // So is antialiasing: tune measures at the pixel centres, as its reference traces them, and the file
  // leaves the sample count to the render that reads it.
  CHECK(text.find("\nantialias") == std::string::npos);
  const std::string slices = fileValue(text, "ssgi-slices"), steps = fileValue(text, "ssgi-steps");
  CHECK((slices == "1" || slices == "2"));
  CHECK((steps == "4" || steps == "8"));
  CHECK(tune.output.find("chosen: ") != std::string::npos);

  const fs::path out = folder / "out";
  const Run render = runHeadlight("render builtin:cornell --width 32 --height 32 --targets ssgi --settings " +
                                  quote(file.string()) + " --out " + quote(out.string()));
  INFO(render.output);
  REQUIRE(render.exitCode == 0);
  CHECK(settingIn(out / "ssgi.exr", "ssgi-slices") == slices);
  CHECK(settingIn(out / "ssgi.exr", "ssgi-steps") == steps);
  fs::remove_all(folder);
}

TEST_CASE("tune measures the settings as given and no SSGI beside its candidates, and reports its pick against both") {
  const fs::path folder = freshFolder("tune-comparisons");
  const fs::path file = folder / "c.settings";
  const Run tune =
      runHeadlight("tune builtin:cornell --max-ao-error 0.2 --verbose" + kTinyTune + " --out " + quote(file.string()));
  INFO(tune.output);
  REQUIRE(tune.exitCode == 0);
  // --verbose lists every configuration: the four candidates and the two comparisons.
  CHECK(tune.output.find("tune: 6 configurations") != std::string::npos);
  CHECK(tune.output.find("  as given") != std::string::npos);
  CHECK(tune.output.find("  ssgi=off") != std::string::npos);
  CHECK(tune.output.find("\n  as given: AO RMSE ") != std::string::npos);
  CHECK(tune.output.find(" its time\n") != std::string::npos);
  CHECK(tune.output.find("\n  no SSGI: AO RMSE ") != std::string::npos);
  const std::string text = readText(file);
  INFO(text);
  const double asGiven = recorded(text, "as-given-ao-rmse"), noSsgi = recorded(text, "no-ssgi-ao-rmse");
  CHECK(recorded(text, "as-given-frame-ms") > 0.0);
  CHECK(recorded(text, "no-ssgi-lit-flip") > recorded(text, "lit-flip"));
  CHECK(asGiven > 0.0);
  // Measured without SSGI: unoccluded ambient is far from the reference's AO
  // (about 0.3 against 0.1 on the Cornell box at 32 x 32).
  CHECK(noSsgi > 1.5 * asGiven);

  // A sweep that varies ssgi itself gets no second no-SSGI row.
  const Run swept = runHeadlight(
      "tune builtin:cornell --max-ao-error 0.5 --width 32 --height 32 --sweep ssgi=on,off "
      "--reference-samples 64 --repetitions 1 --warmup 0 --out " +
      quote(file.string()));
  INFO(swept.output);
  REQUIRE(swept.exitCode == 0);
  CHECK(swept.output.find("tune: 3 configurations") != std::string::npos);  // on, off, as given
  CHECK(swept.output.find("\n  no SSGI: ") == std::string::npos);
  fs::remove_all(folder);
}

TEST_CASE("tune --max-flip chooses within lit's HDR-FLIP and records it; an unreachable one exits 3") {
  const fs::path folder = freshFolder("tune-flip");
  const fs::path file = folder / "flip.settings";
  // 0.9: above every candidate's lit HDR-FLIP against the reference.
  Run tune = runHeadlight("tune builtin:cornell --max-flip 0.9" + kTinyTune + " --out " + quote(file.string()));
  INFO(tune.output);
  REQUIRE(tune.exitCode == 0);
  const std::string text = readText(file);
  INFO(text);
  CHECK(recorded(text, "lit-flip") > 0.0);  // measured: SSGI never matches the path tracer exactly
  CHECK(recorded(text, "lit-flip") <= 0.9);
  CHECK(recorded(text, "max-flip") == doctest::Approx(0.9));
  CHECK(text.find("max-ao-error") == std::string::npos);  // not asked for
  fs::remove(file);
  tune = runHeadlight("tune builtin:cornell --max-flip 1e-6" + kTinyTune + " --out " + quote(file.string()));
  CHECK(tune.exitCode == 3);
  CHECK(tune.output.find("no configuration reaches lit HDR-FLIP <= 1e-06") != std::string::npos);
  CHECK(tune.output.find("the best lit HDR-FLIP reached ") != std::string::npos);
  CHECK(!fs::exists(file));
  fs::remove_all(folder);
}

TEST_CASE("tune with an error no configuration reaches exits 3, names the best error, and writes nothing") {
  const fs::path folder = freshFolder("tune-unmet");
  const fs::path file = folder / "never.settings";
  const Run tune =
      runHeadlight("tune builtin:cornell --max-ao-error 1e-6" + kTinyTune + " --out " + quote(file.string()));
  INFO(tune.output);
  CHECK(tune.exitCode == 3);
  CHECK(tune.output.find("no configuration reaches AO RMSE <= 1e-06") != std::string::npos);
  const auto best = tune.output.find("the best reached ");
  REQUIRE(best != std::string::npos);
  CHECK(std::stod(tune.output.substr(best + 17)) > 1e-6);
  CHECK(!fs::exists(file));
  CHECK(!fs::exists(file.string() + ".tmp"));
  fs::remove_all(folder);
}
#endif

TEST_CASE("tune without --max-ao-error is a usage error") {
  const Run run = runHeadlight("tune builtin:cornell");
  INFO(run.output);
  CHECK(run.exitCode == 2);
  CHECK(run.output.find("--max-ao-error: required") != std::string::npos);
}

TEST_CASE("render --settings: flags after the file override it, flags before it are overridden") {
  const fs::path folder = freshFolder("settings-order");
  const fs::path file = folder / "mine.settings";
  std::ofstream(file) << "# a comment\n\nssgi-slices = 3\nssgi-steps = 5\n";
  const fs::path out = folder / "out";
  const Run run =
      runHeadlight("render builtin:cornell --width 16 --height 16 --targets ssgi --ssgi-slices 2 --settings " +
                   quote(file.string()) + " --ssgi-steps 7 --out " + quote(out.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK(settingIn(out / "ssgi.exr", "ssgi-slices") == "3");  // the file after --ssgi-slices 2
  CHECK(settingIn(out / "ssgi.exr", "ssgi-steps") == "7");   // --ssgi-steps 7 after the file
  fs::remove_all(folder);
}

TEST_CASE("a malformed settings file is a usage error naming the file and the line, and no output") {
  const fs::path folder = freshFolder("settings-bad");
  const fs::path file = folder / "bad.settings";
  struct Case {
    const char* text;
    const char* message;
  };
  const Case cases[] = {
      {"# fine\nssgi-slices = 2\nssgi-steps 5\n", "bad.settings:3: expected NAME = VALUE"},
      {"ssgi-slices = 2\nssgi-slicez = 3\n", "bad.settings:2: unknown setting 'ssgi-slicez'"},
      {"\nssgi-steps = many\n", "bad.settings:2: ssgi-steps: expected"},  // the file's own name for it
      {"ssgi-steps = 4\nssgi-steps = 8\n", "bad.settings:2: 'ssgi-steps' is already set on line 1"},
  };
  for (const Case& c : cases) {
    CAPTURE(c.text);
    std::ofstream(file) << c.text;
    const Run run = runHeadlight("render builtin:cornell --width 16 --height 16 --settings " + quote(file.string()) +
                                 " --out " + quote((folder / "out").string()));
    INFO(run.output);
    CHECK(run.exitCode == 2);
    CHECK(run.output.find(c.message) != std::string::npos);
    CHECK(!fs::exists(folder / "out"));
  }
  const Run missing = runHeadlight("render --settings " + quote((folder / "none.settings").string()));
  INFO(missing.output);
  CHECK(missing.exitCode == 2);
  CHECK(missing.output.find("none.settings: cannot read the settings file") != std::string::npos);
  fs::remove_all(folder);
}

TEST_CASE("--verbose lists the passes a scene does not need, and none for a scene that needs them all") {
  const fs::path folder = freshFolder("skip-rules");
  // builtin:spheres has no emissive material; sky intensity 0 leaves no sky
  // work. Its sun casts shadows, so those stay.
  const Run dark = runHeadlight("render builtin:spheres --width 32 --height 32 --sky-intensity 0 --verbose --out " +
                                quote((folder / "dark").string()));
  INFO(dark.output);
  REQUIRE(dark.exitCode == 0);
  CHECK(dark.output.find("skipped sky        sky intensity 0") != std::string::npos);
  CHECK(dark.output.find("skipped emissive   no material emits") != std::string::npos);
  CHECK(dark.output.find("skipped shadows") == std::string::npos);
  CHECK(dark.output.find("pass shadows") != std::string::npos);
  // Its lit image: the sky's background is 0.
  OIIO::ImageBuf lit((folder / "dark" / "lit.exr").string());
  REQUIRE(lit.read());
  float corner[4] = {};
  lit.getpixel(0, 0, corner);  // the spheres camera sees background in its top corner
  CHECK(corner[0] == 0.0f);
  CHECK(corner[3] == 0.0f);

  // builtin:cornell has a shadow-casting lamp, an emissive lamp quad and sky 0.15.
  const Run full = runHeadlight("render builtin:cornell --width 32 --height 32 --verbose --out " +
                                quote((folder / "full").string()));
  INFO(full.output);
  REQUIRE(full.exitCode == 0);
  // Only the KHR_materials_* lobes it has no material for.
  CHECK(full.output.find("\nskipped lobes") != std::string::npos);
  CHECK(full.output.find("\nskipped ", full.output.find("\nskipped lobes") + 1) == std::string::npos);
  CHECK(full.output.find("\nskipped ") == full.output.find("\nskipped lobes"));
  CHECK(full.output.find("pass shadows") != std::string::npos);
  fs::remove_all(folder);
}

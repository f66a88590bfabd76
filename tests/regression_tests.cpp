// The regression suite: every golden in reference_images/goldens.txt is
// rendered again by the CLI and diffed target by target with headlight
// diff's per-target thresholds (docs/DIFF.md gives each one's reason). A
// failure leaves the actual images, heatmaps and an HTML page in the build
// folder and prints the page's path.
//
// Warn is a pass only across renderers: a golden made by the same GL
// renderer string as this render (the EXRs' headlight:renderer) must match
// within Pass, since nothing but our code can have moved it.
//
// Every golden is compared in both fullscreen forms (--fullscreen-form
// fragment and compute, lib/passes/fullscreen.hpp): the forms must give the
// same pixels, so one golden serves both.
//
// Goldens made from a shared asset (../shared, beside the checkout) are a
// test case of their own, skipped at registration when none of their assets
// is there, so that doctest counts them as skipped and not as passed. Each
// case reports how many goldens it compared and asserts that this is every
// golden listed but those whose asset is absent.
#include <doctest/doctest.h>

#include <OpenImageIO/imagebuf.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>

#include "headlight/diff.hpp"
#include "headlight/output.hpp"
#include "headlight/settings.hpp"
#include "regression_report.hpp"
#include "support/assets.hpp"
#include "support/process.hpp"

namespace fs = std::filesystem;
using namespace headlight;

namespace {

struct Golden {
  std::string name;
  std::string scene;  // builtin:NAME, or a path relative to the source root
  std::string flags;

  bool fromFile() const { return scene.rfind("builtin:", 0) != 0; }
  bool assetPresent() const { return !fromFile() || test::exists(fs::path(HEADLIGHT_SOURCE_DIR) / scene); }
};

std::vector<Golden> goldens() {
  std::ifstream list(fs::path(HEADLIGHT_SOURCE_DIR) / "reference_images" / "goldens.txt");
  std::vector<Golden> result;
  for (std::string line; std::getline(list, line);) {
    line = line.substr(0, line.find('#'));
    std::istringstream words(line);
    Golden golden;
    if (!(words >> golden.name >> golden.scene)) continue;
    std::getline(words, golden.flags);
    result.push_back(golden);
  }
  return result;
}

// Decided before any test runs: doctest's skip is a registration decorator.
const bool kAnySharedAssetPresent = [] {
  for (const Golden& golden : goldens())
    if (golden.fromFile() && golden.assetPresent()) return true;
  return false;
}();

// The GL renderer string an EXR says it was made by ("" if it says none).
std::string rendererOf(const fs::path& exr) {
  OIIO::ImageBuf image(exr.string());
  return image.init_spec(exr.string(), 0, 0) ? image.spec().get_string_attribute("headlight:renderer") : "";
}

// Setting rows that change no EXR pixel (preview.png's tone curve and
// exposure; how the fullscreen passes run): a golden need not agree on them.
const std::set<std::string> kPixelNeutralSettings{"tonemap", "exposure", "fullscreen-form"};

// The golden holds pixels and the settings that made them: a row recorded
// in both must agree (a changed default fails here, naming the row, before
// the pixels are blamed); a row the golden predates must hold its default
// (an "auto" default resolves per scene, so only its pixels are compared).
// A new row at its default therefore needs no re-rendered golden.
void checkSettings(const fs::path& goldenExr, const fs::path& actualExr) {
  const std::map<std::string, std::string> golden = readSettingAttributes(goldenExr);
  const std::map<std::string, std::string> actual = readSettingAttributes(actualExr);
  const std::map<std::string, std::string> defaults = settingsAsText(RenderSettings{});
  CHECK_MESSAGE(!actual.empty(), actualExr.string() << " records no settings");
  for (const auto& [row, value] : actual) {
    if (kPixelNeutralSettings.count(row)) continue;
    const auto recorded = golden.find(row);
    if (recorded != golden.end()) {
      CHECK_MESSAGE(recorded->second == value, "setting " << row << ": golden " << recorded->second << ", render "
                                                          << value << " (re-render with tools/update_goldens.sh "
                                                          << "if the change is meant)");
      continue;
    }
    const auto byDefault = defaults.find(row);
    const bool isDefault = byDefault != defaults.end() && (byDefault->second == value || byDefault->second == "auto");
    CHECK_MESSAGE(isDefault, "setting " << row << " = " << value << " is not its default, and the golden predates it");
  }
}

struct Tally {
  int listed = 0;
  int skippedAbsent = 0;  // the scene file is not in this checkout
  int compared = 0;       // rendered and diffed
};

// Renders and diffs one golden in one fullscreen form; false if the render failed.
bool compareGolden(const Golden& golden, const std::string& form) {
  const fs::path work = fs::path(HEADLIGHT_BUILD_DIR) / ("regression-" + form);
  const fs::path expected = fs::path(HEADLIGHT_SOURCE_DIR) / "reference_images" / golden.name;
  const fs::path actual = work / golden.name / "actual";
  fs::remove_all(work / golden.name);
  // The golden's own command; scene paths are relative to the source root.
  // --strict: a GL error fails the render instead of leaving a warning.
  const std::string command = "cd " + test::shellQuote(HEADLIGHT_SOURCE_DIR) + " && " +
                              test::shellQuote(HEADLIGHT_EXE) + " render " + golden.scene + " " + golden.flags +
                              " --strict --quiet --fullscreen-form " + form + " --out " +
                              test::shellQuote(actual.string()) +
                              // The targets tools/update_goldens.sh writes: every EXR (emissive as
                              // zeros where nothing emits), no preview.
                              " --targets position,normal,albedo,material,depth,emissive,ssgi,lit,ids";
  const test::ProcessResult run = test::runCommand(command);
  INFO(command);
  INFO(run.output);
  CHECK(run.exitCode == 0);
  if (run.exitCode != 0) return false;
  // The same targets as the golden; frame.json makes both checked sets.
  const DirectoryDiff diff = diffDirectories(expected, actual);
  bool failed = diff.status > DiffStatus::Warn || diff.targets.empty();
  if (!diff.targets.empty()) checkSettings(diff.targets.front().a, diff.targets.front().b);
  for (const DiffResult& target : diff.targets) {
    CAPTURE(target.target);
    const std::string goldenRenderer = rendererOf(target.a), actualRenderer = rendererOf(target.b);
    const bool sameRenderer = !goldenRenderer.empty() && goldenRenderer == actualRenderer;
    CAPTURE(goldenRenderer);
    CAPTURE(actualRenderer);
    if (sameRenderer) {
      CHECK_MESSAGE(target.status == DiffStatus::Pass, "same renderer, so Warn fails too: " << target.problem);
      failed |= target.status != DiffStatus::Pass;
    } else {
      CHECK_MESSAGE(target.status <= DiffStatus::Warn, target.problem);
    }
  }
  if (failed) {
    const fs::path page = test::writeRegressionReport(diff, golden.name, work / golden.name);
    std::cerr << "regression " << golden.name << ": " << statusName(diff.status) << "; look at " << page.string()
              << "\n";
    FAIL_CHECK("golden " << golden.name << " differs: see " << page.string());
  }
  return true;
}

Tally compareGoldens(bool fromFile, const std::string& form) {
  Tally tally;
  for (const Golden& golden : goldens()) {
    if (golden.fromFile() != fromFile) continue;
    CAPTURE(golden.name);
    CAPTURE(form);
    ++tally.listed;
    if (!golden.assetPresent()) {
      MESSAGE("golden " << golden.name << " not compared: " << golden.scene << " is absent");
      ++tally.skippedAbsent;
      continue;
    }
    tally.compared += compareGolden(golden, form) ? 1 : 0;
  }
  return tally;
}

const char* const kForms[] = {"fragment", "compute"};

void checkTally(const Tally& tally, const char* kind) {
  MESSAGE("compared " << tally.compared << " of " << tally.listed << " " << std::string(kind) << " goldens ("
                      << tally.skippedAbsent << " skipped: asset absent)");
  CHECK(tally.compared > 0);
  CHECK(tally.compared == tally.listed - tally.skippedAbsent);
}

}  // namespace

TEST_CASE("every built-in golden renders the same, target by target, in both fullscreen forms") {
  REQUIRE(goldens().size() >= 4);
  for (const char* form : kForms) checkTally(compareGoldens(false, form), "built-in");
}

TEST_CASE("every golden of a shared asset renders the same, target by target, in both fullscreen forms" *
          doctest::skip(!kAnySharedAssetPresent)) {
  for (const char* form : kForms) checkTally(compareGoldens(true, form), "shared-asset");
}

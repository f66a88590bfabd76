// The regression suite: every golden in reference_images/goldens.txt is
// rendered again by the CLI and diffed target by target with headlight
// diff's per-target thresholds (docs/DIFF.md gives each one's reason). A
// failure leaves the actual images, heatmaps and an HTML page in the build
// folder and prints the page's path.
#include <doctest/doctest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <sys/wait.h>

#include "headlight/diff.hpp"
#include "regression_report.hpp"

namespace fs = std::filesystem;
using namespace headlight;

namespace {

struct Golden {
  std::string name;
  std::string scene;
  std::string flags;
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

int run(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

}  // namespace

TEST_CASE("every golden in reference_images renders the same, target by target") {
  const auto list = goldens();
  REQUIRE(list.size() >= 4);
  const fs::path work = fs::path(HEADLIGHT_BUILD_DIR) / "regression";
  for (const Golden& golden : list) {
    CAPTURE(golden.name);
    const fs::path expected = fs::path(HEADLIGHT_SOURCE_DIR) / "reference_images" / golden.name;
    const fs::path actual = work / golden.name / "actual";
    fs::remove_all(work / golden.name);
    // The shared Khronos asset lives beside the project (../shared), in CI
    // too; a checkout without it cannot render that golden.
    const bool isFile = golden.scene.rfind("builtin:", 0) != 0;
    if (isFile && !fs::exists(fs::path(HEADLIGHT_SOURCE_DIR) / golden.scene)) {
      MESSAGE("skipped golden " << golden.name << ": " << golden.scene << " is absent");
      continue;
    }
    // The golden's own command; scene paths are relative to the source root.
    const std::string command = "cd '" HEADLIGHT_SOURCE_DIR "' && '" HEADLIGHT_EXE "' render " + golden.scene + " " +
                                golden.flags + " --strict --quiet --out '" + actual.string() + "'";
    // --strict: a GL error fails the render instead of leaving a warning.
    const int exitCode = run(command);
    CHECK(exitCode == 0);
    if (exitCode != 0) continue;
    fs::remove(actual / "preview.png");
    const DirectoryDiff diff = diffDirectories(expected, actual);
    for (const DiffResult& target : diff.targets) {
      CAPTURE(target.target);
      CHECK_MESSAGE(target.status <= DiffStatus::Warn, target.problem);
    }
    if (diff.status > DiffStatus::Warn || diff.targets.empty()) {
      const fs::path page = test::writeRegressionReport(diff, golden.name, work / golden.name);
      std::cerr << "regression " << golden.name << ": " << statusName(diff.status) << "; look at " << page.string()
                << "\n";
      FAIL_CHECK("golden " << golden.name << " differs: see " << page.string());
    }
  }
}

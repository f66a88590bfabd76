#pragma once
// What the hostile suite's CLI cases share (hostile_tests.cpp,
// hostile_round_two_tests.cpp): quoting, the refusal check and writing a
// generated glTF document.
#include <doctest/doctest.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "support/encoding.hpp"
#include "support/process.hpp"
#include "support/temp_folder.hpp"

namespace headlight::test {

// The hostile suite's budget (issue 32): every command it runs finishes, or
// is refused, within kHostileSeconds, and under the address space the
// probes used (`ulimit -v`, kHostileAddressSpaceKb) its peak resident memory
// stays within the automatic --max-memory that limit gives (half of it)
// plus 10 %. A sanitized build's programs run slower and map terabytes of
// shadow memory: there the budget is not checked (said once per case).
inline constexpr double kHostileSeconds = 10.0;
inline constexpr long kHostileAddressSpaceKb = 4L << 20;                      // 4 GiB, as the probes ran
inline constexpr long kHostilePeakKb = kHostileAddressSpaceKb / 2 * 11 / 10;  // max-memory auto + 10 %

// runHeadlight within the budget: `args` as for runHeadlight.
inline ProcessResult runHostile(const std::string& args) {
  if (HEADLIGHT_SANITIZED_BUILD) {
    MESSAGE("hostile budget not checked: a sanitized build");
    return runHeadlight(args);
  }
  const ProcessResult run =
      runCommand("ulimit -v " + std::to_string(kHostileAddressSpaceKb) + "; " + shellQuote(HEADLIGHT_EXE) + " " + args);
  INFO("headlight " << args);
  CHECK_MESSAGE(run.seconds <= kHostileSeconds, "took " << run.seconds << " s");
  CHECK_MESSAGE(run.peakRssKb <= kHostilePeakKb, "peak resident memory " << run.peakRssKb << " kB");
  return run;
}

inline bool folderEmptyOrAbsent(const std::filesystem::path& folder) {
  return !std::filesystem::exists(folder) || std::filesystem::is_empty(folder);
}

// `headlight render` of `scene` at 32 x 24 into `out`, within the budget.
inline ProcessResult renderSmall(const std::filesystem::path& scene, const std::filesystem::path& out,
                                 const std::string& extra = "") {
  return runHostile("render " + quote(scene) + " --width 32 --height 24 --out " + quote(out) + " " + extra);
}

// Runs `render` on the file and checks exit 1, the file named, each
// fragment present and nothing written.
inline void expectRefused(const std::filesystem::path& scene, const std::vector<std::string>& fragments,
                          const std::string& extra = "") {
  const std::filesystem::path out = scene.parent_path() / "out";
  const ProcessResult run = renderSmall(scene, out, extra);
  INFO(run.output);
  CHECK(run.exitCode == 1);
  CHECK(run.output.find(scene.string()) != std::string::npos);
  for (const std::string& fragment : fragments) CHECK(run.output.find(fragment) != std::string::npos);
  CHECK(folderEmptyOrAbsent(out));
}

inline std::filesystem::path writeGltf(const TempFolder& folder, const nlohmann::json& document,
                                       const std::string& name = "scene.gltf") {
  return folder.write(name, document.dump());
}

}  // namespace headlight::test

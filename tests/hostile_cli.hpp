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

inline std::string quote(const std::filesystem::path& path) { return shellQuote(path.string()); }

inline bool folderEmptyOrAbsent(const std::filesystem::path& folder) {
  return !std::filesystem::exists(folder) || std::filesystem::is_empty(folder);
}

// Runs `render` on the file and checks exit 1, the file named, each
// fragment present and nothing written.
inline void expectRefused(const std::filesystem::path& scene, const std::vector<std::string>& fragments,
                          const std::string& extra = "") {
  const std::filesystem::path out = scene.parent_path() / "out";
  const ProcessResult run =
      runHeadlight("render " + quote(scene) + " --width 32 --height 24 --out " + quote(out) + " " + extra);
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

// `headlight render` batches as a user runs them: job files with a bad
// line, --resume, --targets, --json, and `headlight diff` on an incomplete set.
#include <doctest/doctest.h>

#include <filesystem>
#include <fstream>

#include "support/process.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using headlight::test::runHeadlight;
namespace {
constexpr auto& quote = headlight::test::shellQuote;
}  // namespace
using Run = headlight::test::ProcessResult;

TEST_CASE("a job file: a bad line is named and the other jobs still render; --resume skips finished ones") {
  headlight::test::TempFolder folder("batch_cli");
  const fs::path a = folder.path() / "a", b = folder.path() / "b";
  const fs::path jobs = folder.write(
      "jobs.jsonl", R"({"scene": "builtin:cornell", "out": ")" + a.string() + R"(", "size": "64x48"})" + "\n" +
                        R"({"scene": "builtin:cornell", "out": "x", "settings": {"ssgi-sample": 8}})" + "\n" +
                        R"({"scene": "builtin:spheres", "out": ")" + b.string() +
                        R"(", "size": "64x48", "eye": [0, 1, 6], "target": [0, 0.5, 0]})" + "\n");
  Run run = runHeadlight("render --jobs " + quote(jobs.string()) + " --strict");
  INFO(run.output);
  CHECK(run.exitCode == 1);
  CHECK(run.output.find("jobs.jsonl:2") != std::string::npos);
  CHECK(run.output.find("unknown setting 'ssgi-sample'") != std::string::npos);
  CHECK(run.output.find("3 jobs: 2 rendered, 0 skipped, 1 failed") != std::string::npos);
  CHECK(fs::exists(a / "frame.json"));
  CHECK(fs::exists(b / "lit.exr"));

  run = runHeadlight("render --jobs " + quote(jobs.string()) + " --strict --resume --shard 0/3");
  INFO(run.output);
  CHECK(run.exitCode == 0);
  CHECK(run.output.find("1 job (shard 0/3 of 3): 0 rendered, 1 skipped, 0 failed") != std::string::npos);
}

TEST_CASE("--targets writes only the named targets; --json summarises") {
  headlight::test::TempFolder folder("targets_cli");
  const Run run = runHeadlight(
      "render builtin:cornell builtin:spheres --width 64 --height 48 --targets depth,normal "
      "--json --strict --out " +
      quote(folder.path().string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK(run.output.find("\"rendered\": 2") != std::string::npos);
  CHECK(run.output.find("\"gbuffer\"") != std::string::npos);
  CHECK(run.output.find("\"ssgi\"") == std::string::npos);  // the pass was skipped
  for (const char* scene : {"cornell", "spheres"}) {
    CHECK(fs::exists(folder.path() / scene / "depth.exr"));
    CHECK(fs::exists(folder.path() / scene / "normal.exr"));
    CHECK_FALSE(fs::exists(folder.path() / scene / "lit.exr"));
    CHECK_FALSE(fs::exists(folder.path() / scene / "preview.png"));
  }
}

TEST_CASE("headlight diff: an incomplete set is exit 6 and named") {
  headlight::test::TempFolder folder("incomplete_cli");
  const std::string a = (folder.path() / "a").string(), b = (folder.path() / "b").string();
  REQUIRE(runHeadlight("render --width 64 --height 48 --quiet --out " + quote(a)).exitCode == 0);
  REQUIRE(runHeadlight("render --width 64 --height 48 --quiet --out " + quote(b)).exitCode == 0);
  CHECK(runHeadlight("diff " + quote(a) + " " + quote(b)).exitCode == 0);
  std::ofstream(fs::path(b) / "frame.json") << R"({"complete": false, "files": []})";
  const Run run = runHeadlight("diff " + quote(a) + " " + quote(b));
  INFO(run.output);
  CHECK(run.exitCode == 6);
  CHECK(run.output.find("INCOMPLETE SET") != std::string::npos);
}

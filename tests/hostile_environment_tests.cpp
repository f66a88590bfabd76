// Hostile environment map files through the CLI (`render --environment`):
// each refused with exit 1 and a message naming the file and the value,
// before any GL work, and the huge ones before any pixel is decoded.
#include <doctest/doctest.h>

#include <sys/stat.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "hostile_cli.hpp"
#include "support/environment_maps.hpp"
#include "support/process.hpp"
#include "support/temp_folder.hpp"

using namespace headlight::test;
namespace fs = std::filesystem;

namespace {

// A Radiance .hdr header declaring width x height, followed by `texels`
// flat RGBE texels of radiance 1 (fewer than declared: a truncated file).
fs::path hdrDeclaring(const TempFolder& folder, const std::string& name, long width, long height, long texels) {
  std::string bytes =
      "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y " + std::to_string(height) + " +X " + std::to_string(width) + "\n";
  for (long i = 0; i < texels; ++i) bytes += std::string("\x80\x80\x80\x81", 4);
  return folder.write(name, bytes);
}

ProcessResult renderWith(const TempFolder& folder, const fs::path& environment, const std::string& extra = {}) {
  return runHostile("render builtin:cornell --width 32 --height 24 --environment " + shellQuote(environment.string()) +
                    " --out " + shellQuote((folder.path() / "out").string()) + " " + extra);
}

}  // namespace

TEST_CASE("hostile environment maps: huge, truncated, non-finite, not 2:1, a folder, a FIFO: exit 1, named") {
  const TempFolder folder("hostile-environment");
  const fs::path fifo = folder.path() / "fifo.hdr";
  REQUIRE(::mkfifo(fifo.c_str(), 0600) == 0);
  fs::create_directory(folder.path() / "folder.hdr");
  struct Case {
    fs::path file;
    std::string extra;
    std::vector<std::string> words;  // each must be in the message
  };
  const std::vector<Case> cases{
      // 16384 x 8192 declared in a few bytes: refused by its header, not decoded.
      {hdrDeclaring(folder, "huge.hdr", 16384, 8192, 4), "--max-memory 1024", {"16384x8192", "max-memory"}},
      {hdrDeclaring(folder, "wider.hdr", 40000, 20000, 4), "", {"40000x20000", "16384"}},
      {hdrDeclaring(folder, "truncated.hdr", 64, 32, 100), "", {"truncated"}},
      {writeEnvironmentMap(folder.path() / "nan.exr", 8, 4,
                           [](int x, int y) { return x == 3 && y == 1 ? glm::vec3(NAN) : glm::vec3(1.0f); }),
       "",
       {"texel (3, 1) R = nan"}},
      {writeEnvironmentMap(folder.path() / "negative.exr", 8, 4,
                           [](int x, int) { return x == 7 ? glm::vec3(-2.0f) : glm::vec3(1.0f); }),
       "",
       {"texel (7, 0) R = -2", ">= 0"}},
      {writeEnvironmentMap(folder.path() / "wide.exr", 96, 32, uniformRadiance), "", {"96x32", "2:1"}},
      // Finite, but past what the tables' sums hold in float (issue 32: lit came out NaN).
      {writeEnvironmentMap(folder.path() / "blinding.exr", 8, 4,
                           [](int x, int y) { return x == 5 && y == 2 ? glm::vec3(3e38f) : glm::vec3(1.0f); }),
       "",
       {"texel (5, 2) R", "expected 0..", "float rendering stays finite"}},
      {folder.path() / "folder.hdr", "", {"a folder"}},
      {fifo, "", {"a FIFO"}},  // returns: nothing opens it
      {folder.path() / "missing.hdr", "", {"no such file"}},
  };
  for (const Case& c : cases) {
    CAPTURE(c.file);
    const ProcessResult run = renderWith(folder, c.file, c.extra);
    CAPTURE(run.output);
    CHECK(run.exitCode == 1);
    CHECK(run.output.find(c.file.string()) != std::string::npos);
    for (const std::string& word : c.words) CHECK(run.output.find(word) != std::string::npos);
    CHECK(!fs::exists(folder.path() / "out" / "lit.exr"));
  }
}

TEST_CASE("hostile environment maps: a good one renders, and lit's background is the map") {
  const TempFolder folder("hostile-environment");
  const fs::path map = writeEnvironmentMap(folder.path() / "uniform.hdr", 64, 32, uniformRadiance);
  const ProcessResult run = renderWith(folder, map, "--environment-intensity 2 --verbose");
  CAPTURE(run.output);
  CHECK(run.exitCode == 0);
  CHECK(run.output.find("pass environment") != std::string::npos);
  CHECK(fs::exists(folder.path() / "out" / "lit.exr"));
}

TEST_CASE("hostile environment maps: texels brighter than half floats hold light the scene in float (issue 32)") {
  // 100,000 everywhere: past half's 65504, it was inf on the GPU and NaN in lit even with radiance-precision float.
  const TempFolder folder("hostile-environment");
  const fs::path map =
      writeEnvironmentMap(folder.path() / "bright.hdr", 64, 32, [](int, int) { return glm::vec3(100000.0f); });
  const ProcessResult run = runHostile(
      "render builtin:spheres --width 32 --height 24 --radiance-precision float "
      "--environment " +
      shellQuote(map.string()) + " --out " + shellQuote((folder.path() / "out").string()));
  CAPTURE(run.output);
  CHECK(run.exitCode == 0);
  CHECK(run.output.find("non-finite 0") != std::string::npos);
  CHECK(fs::exists(folder.path() / "out" / "lit.exr"));
}

// The headlight binary as a user runs it: exit codes, messages that name
// the problem, and no output left behind on failure.
#include <doctest/doctest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <sys/wait.h>

namespace fs = std::filesystem;

namespace {

struct Run {
  int exitCode = -1;
  std::string output;  // stdout and stderr together
};

std::string quote(const std::string& text) { return "'" + text + "'"; }

Run runHeadlight(const std::string& args) {
  const std::string command = quote(HEADLIGHT_EXE) + " " + args + " 2>&1";
  Run run;
  FILE* pipe = popen(command.c_str(), "r");
  REQUIRE(pipe != nullptr);
  std::array<char, 4096> buffer;
  while (std::size_t n = fread(buffer.data(), 1, buffer.size(), pipe)) run.output.append(buffer.data(), n);
  const int status = pclose(pipe);
  run.exitCode = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  return run;
}

fs::path freshFolder(const char* name) {
  const fs::path path =
      fs::temp_directory_path() / (std::string("headlight_cli_") + name + "_" + std::to_string(std::random_device{}()));
  fs::remove_all(path);
  fs::create_directories(path);
  return path;
}

bool folderEmpty(const fs::path& folder) { return !fs::exists(folder) || fs::is_empty(folder); }

}  // namespace

TEST_CASE("render of the default scene writes every target with real content") {
  const fs::path out = freshFolder("default") / "out";
  const Run run = runHeadlight("render --width 64 --height 48 --out " + quote(out.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  for (const char* name : {"position", "normal", "albedo", "material", "depth", "emissive", "ssgi", "lit"}) {
    CAPTURE(name);
    const fs::path file = out / (std::string(name) + ".exr");
    CHECK(run.output.find(file.string()) != std::string::npos);  // a summary line per file
    OIIO::ImageBuf image(file.string());
    REQUIRE(image.read());
    CHECK(image.spec().width == 64);
    const OIIO::ImageBufAlgo::PixelStats stats = OIIO::ImageBufAlgo::computePixelStats(image);
    REQUIRE(stats.max.size() == std::size_t(image.nchannels()));
    // Not a blank image: some channel varies over the frame.
    float spread = 0;
    for (int c = 0; c < image.nchannels(); ++c) spread = std::max(spread, stats.max[std::size_t(c)] - stats.min[std::size_t(c)]);
    CHECK(spread > 0.01f);
  }
  OIIO::ImageBuf preview((out / "preview.png").string());
  REQUIRE(preview.read());
  CHECK(preview.spec().format == OIIO::TypeDesc::UINT8);
  fs::remove_all(out.parent_path());
}

TEST_CASE("a malformed glTF is exit 1 with a SceneError naming the file, and no output") {
  const fs::path folder = freshFolder("malformed");
  const fs::path scene = folder / "broken.gltf";
  std::ofstream(scene) << R"({"asset": {"version": "2.0"}, "meshes": [ {"primitives": [)";
  const Run run = runHeadlight("render " + quote(scene.string()) + " --out " + quote((folder / "out").string()));
  INFO(run.output);
  CHECK(run.exitCode == 1);
  CHECK(run.output.find("SceneError") != std::string::npos);
  CHECK(run.output.find("broken.gltf") != std::string::npos);
  CHECK(folderEmpty(folder / "out"));
  fs::remove_all(folder);
}

TEST_CASE("a missing scene file is exit 1 naming the file") {
  const fs::path folder = freshFolder("missing");
  const Run run = runHeadlight("render " + quote((folder / "nope.glb").string()) + " --out " +
                               quote((folder / "out").string()));
  INFO(run.output);
  CHECK(run.exitCode == 1);
  CHECK(run.output.find("nope.glb") != std::string::npos);
  CHECK(folderEmpty(folder / "out"));
  fs::remove_all(folder);
}

TEST_CASE("a bad --width is a usage error (exit 2) naming the flag, and no output") {
  const fs::path folder = freshFolder("badwidth");
  for (const char* width : {"0", "-3", "wide", "99999"}) {
    CAPTURE(width);
    const Run run = runHeadlight(std::string("render --width ") + width + " --out " + quote((folder / "out").string()));
    INFO(run.output);
    CHECK(run.exitCode == 2);
    CHECK(run.output.find("--width") != std::string::npos);
    CHECK(folderEmpty(folder / "out"));
  }
  fs::remove_all(folder);
}

TEST_CASE("a context that cannot be made is exit 1 saying what was tried, and no output") {
  const fs::path folder = freshFolder("nocontext");
  const Run run = runHeadlight("render --backend egl --device 99 --out " + quote((folder / "out").string()));
  INFO(run.output);
  CHECK(run.exitCode == 1);
  CHECK(run.output.find("ContextError") != std::string::npos);
  CHECK(run.output.find("EGL device 99") != std::string::npos);
  CHECK(folderEmpty(folder / "out"));
  fs::remove_all(folder);
}

TEST_CASE("--help, --version and unknown commands") {
  const Run help = runHeadlight("render --help");
  CHECK(help.exitCode == 0);
  CHECK(help.output.find("--ssgi-radius") != std::string::npos);  // from the settings table
  CHECK(help.output.find("--backend") != std::string::npos);
  const Run version = runHeadlight("--version");
  CHECK(version.exitCode == 0);
  CHECK(version.output.rfind("headlight ", 0) == 0);
  CHECK(runHeadlight("paint").exitCode == 2);
  CHECK(runHeadlight("").exitCode == 2);
}

// `headlight render` batches as a user runs them: job files with a bad
// line, --resume, --targets, --json, and `headlight diff` on an incomplete set.
#include <doctest/doctest.h>

#include <OpenImageIO/imagebuf.h>

#include <filesystem>
#include <fstream>

#include <cstring>
#include <vector>

#include "support/encoding.hpp"
#include "support/process.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;
using headlight::test::runHeadlight;
namespace {
using headlight::test::quote;
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

namespace {

// One quad facing +Z, lit by a point light whose red is 1e39: finite as a
// double in the file, infinite as the float the shader gets (issue 10).
std::string overbrightGltf() {
  const float positions[] = {-1, -1, 0, 1, -1, 0, 1, 1, 0, -1, 1, 0};
  const unsigned indices[] = {0, 1, 2, 0, 2, 3};
  std::vector<unsigned char> bytes(sizeof positions + sizeof indices);
  std::memcpy(bytes.data(), positions, sizeof positions);
  std::memcpy(bytes.data() + sizeof positions, indices, sizeof indices);
  return R"({"asset": {"version": "2.0"}, "extensionsUsed": ["KHR_lights_punctual"],
    "extensions": {"KHR_lights_punctual": {"lights": [{"type": "point", "color": [1e39, 1, 1], "intensity": 1}]}},
    "scene": 0, "scenes": [{"nodes": [0, 1]}],
    "nodes": [{"mesh": 0}, {"translation": [0, 0, 1], "extensions": {"KHR_lights_punctual": {"light": 0}}}],
    "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
    "accessors": [{"bufferView": 0, "componentType": 5126, "count": 4, "type": "VEC3", "min": [-1, -1, 0], "max": [1, 1, 0]},
                  {"bufferView": 1, "componentType": 5125, "count": 6, "type": "SCALAR"}],
    "bufferViews": [{"buffer": 0, "byteOffset": 0, "byteLength": 48}, {"buffer": 0, "byteOffset": 48, "byteLength": 24}],
    "buffers": [{"byteLength": 72, "uri": "data:application/octet-stream;base64,)" +
         headlight::test::base64(bytes) + R"("}]})";
}

}  // namespace

TEST_CASE("a light colour that would make the frame non-finite is refused before rendering: exit 1, nothing written") {
  // The loader keeps every scene value where float rendering stays finite
  // (docs/RELIABILITY.md); writeFrame's own refusal or clamping of NaN/inf
  // (--clamp-nonfinite) is tested on synthetic frames in batch_tests.cpp.
  headlight::test::TempFolder folder("nonfinite_cli");
  const fs::path scene = folder.write("overbright.gltf", overbrightGltf());
  const fs::path out = folder.path() / "out";
  for (const char* clamp : {"", " --clamp-nonfinite"}) {
    const Run run = runHeadlight("render " + quote(scene.string()) + " --width 32 --height 32" + clamp + " --out " +
                                 quote(out.string()));
    INFO(run.output);
    CHECK(run.exitCode == 1);
    CHECK(run.output.find("overbright.gltf: light 0") != std::string::npos);
    CHECK(run.output.find("so that float rendering stays finite") != std::string::npos);
    CHECK_FALSE(fs::exists(out));
  }
}

namespace {

// A triangle at x in [-1, 1] whose node slides from x + 1 to x + 5 over
// 1 s (animation 0, "Slide"; it starts away from the static pose, so
// unplayed it is named), its data inline.
std::string slidingTriangleGltf() {
  // Positions (-1,-1,0) (1,-1,0) (0,1,0); times 0 and 1; translations (1,0,0) and (5,0,0).
  const float data[] = {-1, -1, 0, 1, -1, 0, 0, 1, 0, 0, 1, 1, 0, 0, 5, 0, 0};
  std::vector<unsigned char> bytes(sizeof data);
  std::memcpy(bytes.data(), data, sizeof data);
  return R"({"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],)"
         R"("meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],)"
         R"("buffers":[{"byteLength":68,"uri":"data:application/octet-stream;base64,)" +
         headlight::test::base64(bytes) +
         R"("}],"bufferViews":[{"buffer":0,"byteLength":36},{"buffer":0,"byteOffset":36,"byteLength":8},)"
         R"({"buffer":0,"byteOffset":44,"byteLength":24}],)"
         R"("accessors":[{"bufferView":0,"componentType":5126,"type":"VEC3","count":3,"min":[-1,-1,0],"max":[1,1,0]},)"
         R"({"bufferView":1,"componentType":5126,"type":"SCALAR","count":2,"min":[0],"max":[1]},)"
         R"({"bufferView":2,"componentType":5126,"type":"VEC3","count":2}],)"
         R"("animations":[{"name":"Slide","channels":[{"sampler":0,"target":{"node":0,"path":"translation"}}],)"
         R"("samplers":[{"input":1,"output":2}]}]})";
}

}  // namespace

TEST_CASE(
    "--animation and --time pose the file; a job file's \"animation\" and \"time\" pose its job; --resume "
    "tells poses apart") {
  headlight::test::TempFolder folder("animation_cli");
  const fs::path scene = folder.write("slide.gltf", slidingTriangleGltf());
  const std::string view = " --width 48 --height 32 --eye 3,0,12 --target 3,0,0 --targets position --strict --out ";
  // The mean world x over the covered pixels of a set's position.exr.
  auto meanX = [](const fs::path& out) {
    OIIO::ImageBuf position((out / "position.exr").string());
    REQUIRE(position.read(0, 0, true, OIIO::TypeDesc::FLOAT));
    const int a = position.spec().channelindex("A"), x = position.spec().channelindex("position.X");
    REQUIRE(a >= 0);
    REQUIRE(x >= 0);
    double sum = 0;
    int count = 0;
    for (int py = 0; py < position.spec().height; ++py)
      for (int px = 0; px < position.spec().width; ++px)
        if (position.getchannel(px, py, 0, a) > 0.5f) {
          sum += position.getchannel(px, py, 0, x);
          ++count;
        }
    REQUIRE(count > 0);
    return sum / count;
  };
  const fs::path still = folder.path() / "still", half = folder.path() / "half";
  Run run = runHeadlight("render " + quote(scene.string()) + view + quote(still.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK(run.output.find("is not played (the static pose is drawn; --animation N|NAME --time SECONDS") !=
        std::string::npos);
  run = runHeadlight("render " + quote(scene.string()) + " --animation Slide --time 0.5" + view + quote(half.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK(run.output.find("warning") == std::string::npos);
  CHECK(meanX(half) - meanX(still) == doctest::Approx(3.0).epsilon(0.02));
  // --resume: the same pose is skipped, another time is rendered.
  run = runHeadlight("render " + quote(scene.string()) + " --animation Slide --time 0.5 --resume" + view +
                     quote(half.string()));
  INFO(run.output);
  CHECK(run.output.find("skipped") != std::string::npos);
  run = runHeadlight("render " + quote(scene.string()) + " --animation Slide --time 1 --resume --force" + view +
                     quote(half.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK(meanX(half) - meanX(still) == doctest::Approx(5.0).epsilon(0.02));
  // Job files: a time alone plays animation 0; an unknown name fails its job, naming the animations.
  const fs::path a = folder.path() / "a", b = folder.path() / "b";
  const fs::path jobs =
      folder.write("jobs.jsonl", R"({"scene": ")" + scene.string() + R"(", "out": ")" + a.string() +
                                     R"(", "size": "48x32", "eye": [3, 0, 12], "target": [3, 0, 0], "time": 0.25})" +
                                     "\n" + R"({"scene": ")" + scene.string() + R"(", "out": ")" + b.string() +
                                     R"(", "size": "48x32", "animation": "Run"})" + "\n");
  run = runHeadlight("render --jobs " + quote(jobs.string()) + " --targets position");
  INFO(run.output);
  CHECK(run.exitCode == 1);
  CHECK(run.output.find("animation 'Run' is not in the file: its animations are 0 'Slide'") != std::string::npos);
  CHECK(meanX(a) - meanX(still) == doctest::Approx(2.0).epsilon(0.02));
}

TEST_CASE("--views N --through-time poses view k at k / N of the animation, each set naming its pose") {
  headlight::test::TempFolder folder("through_time_cli");
  const fs::path scene = folder.write("slide.gltf", slidingTriangleGltf());
  const fs::path out = folder.path() / "views";
  Run run = runHeadlight("render " + quote(scene.string()) +
                         " --views 4 --through-time --width 32 --height 24 --targets position --strict --out " +
                         quote(out.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK(run.output.find("4 jobs: 4 rendered, 0 skipped, 0 failed") != std::string::npos);
  const char* poses[] = {"animation 0 'Slide' at 0 s", "animation 0 'Slide' at 0.25 s", "animation 0 'Slide' at 0.5 s",
                         "animation 0 'Slide' at 0.75 s"};
  for (int v = 0; v < 4; ++v) {
    char name[16];
    std::snprintf(name, sizeof name, "view_%03d", v);
    std::ifstream manifest(out / name / "frame.json");
    const std::string text((std::istreambuf_iterator<char>(manifest)), std::istreambuf_iterator<char>());
    CAPTURE(v);
    CHECK(text.find(std::string("\"pose\": \"") + poses[v] + "\"") != std::string::npos);
  }
  run = runHeadlight("render " + quote(scene.string()) + " --views 2 --through-time --time 1 --out " +
                     quote((folder.path() / "x").string()));
  CHECK(run.exitCode == 2);
  CHECK(run.output.find("--through-time and --time: choose one") != std::string::npos);
  run = runHeadlight("render builtin:cornell --views 2 --through-time --out " + quote((folder.path() / "y").string()));
  CHECK(run.exitCode == 1);
  CHECK(run.output.find("--through-time: the scene has no animations") != std::string::npos);
}

// The headlight binary as a user runs it: exit codes, messages that name
// the problem, and no output left behind on failure.
#include <doctest/doctest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "support/process.hpp"
#include "support/temp_folder.hpp"

namespace fs = std::filesystem;

using headlight::test::freshFolder;
using headlight::test::quote;
using headlight::test::runHeadlight;
using Run = headlight::test::ProcessResult;

namespace {

bool folderEmpty(const fs::path& folder) { return !fs::exists(folder) || fs::is_empty(folder); }

}  // namespace

TEST_CASE("render of the default scene writes every target with real content") {
  const fs::path out = freshFolder("default") / "out";
  const Run run = runHeadlight("render --width 64 --height 48 --strict --out " + quote(out.string()));
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
    for (int c = 0; c < image.nchannels(); ++c)
      spread = std::max(spread, stats.max[std::size_t(c)] - stats.min[std::size_t(c)]);
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
  const Run run =
      runHeadlight("render " + quote((folder / "nope.glb").string()) + " --out " + quote((folder / "out").string()));
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

TEST_CASE("--device takes an EGL device index or name; an unknown name is exit 1 listing the devices") {
  const fs::path folder = freshFolder("device");
  const Run named = runHeadlight(
      "render --backend egl --device EGL_MESA_device_software --width 16 --height 16 "
      "--verbose --out " +
      quote((folder / "named").string()));
  INFO(named.output);
  CHECK(named.exitCode == 0);
  CHECK(named.output.find("backend: egl") != std::string::npos);
  const Run unknown = runHeadlight("render --backend egl --device no-such-gpu --width 16 --height 16 --out " +
                                   quote((folder / "unknown").string()));
  INFO(unknown.output);
  CHECK(unknown.exitCode == 1);
  CHECK(unknown.output.find("no-such-gpu") != std::string::npos);
  CHECK(unknown.output.find("EGL_MESA_device_software") != std::string::npos);  // the devices it has
  CHECK_FALSE(fs::exists(folder / "unknown"));
  fs::remove_all(folder);
}

TEST_CASE("--device N that does not exist is exit 1 naming the devices, even with --backend auto") {
  const fs::path folder = freshFolder("device-missing");
  // Issue 30: it used to fall back to OSMesa in silence, exit 0.
  const Run missing = runHeadlight("render builtin:cornell --device 7 --width 16 --height 16 --out " +
                                   quote((folder / "missing").string()));
  INFO(missing.output);
  CHECK(missing.exitCode == 1);
  CHECK(missing.output.find("EGL device 7") != std::string::npos);
  CHECK(missing.output.find("EGL device 0") != std::string::npos);  // the devices there are
  CHECK(missing.output.find("--device-fallback") != std::string::npos);
  CHECK_FALSE(fs::exists(folder / "missing"));
  const Run fallback = runHeadlight(
      "render builtin:cornell --device 7 --device-fallback --width 16 --height 16 "
      "--verbose --out " +
      quote((folder / "fallback").string()));
  INFO(fallback.output);
  CHECK(fallback.exitCode == 0);
  CHECK(fallback.output.find("only 1 device(s) exist") != std::string::npos);  // --verbose says why
  fs::remove_all(folder);
}

TEST_CASE("render --eye --target --up --fov places the camera; bad combinations are usage errors") {
  const fs::path folder = freshFolder("cli-camera");
  // The Cornell box's back wall is the plane z = -1: from (0, 1, 5) looking along -Z, a pixel above the
  // boxes that sees it has depth 6 scene units (depth.Z is view-space depth, the same for every such pixel).
  const Run run = runHeadlight(
      "render builtin:cornell --eye 0,1,5 --target 0,1,0 --up 0,1,0 --fov 30 --width 33 "
      "--height 33 --targets depth --quiet --out " +
      quote((folder / "out").string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  OIIO::ImageBuf depth((folder / "out" / "depth.exr").string());
  REQUIRE(depth.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  float wall = 0.0f;
  depth.getpixel(16, 8, &wall, 1);  // row 8 of 33 at 30 degrees: the back wall between the box tops and the ceiling
  CHECK(wall == doctest::Approx(6.0f).epsilon(1e-3));
  for (const std::string args : {"--eye 0,1,5", "--target 0,0,0", "--eye 0,1,5 --target 0,1,5", "--fov 30",
                                 "--eye 0,1,5 --target 0,1,0 --up 0,0,-1", "--eye 1,2 --target 0,0,0",
                                 "--eye 0,1,5 --target 0,1,0 --views 4 --orbit", "--orbit-elevation 30"}) {
    const Run bad = runHeadlight("render builtin:cornell " + args + " --out " + quote((folder / "bad").string()));
    INFO(args);
    INFO(bad.output);
    CHECK(bad.exitCode == 2);
  }
  CHECK_FALSE(fs::exists(folder / "bad"));
  fs::remove_all(folder);
}

TEST_CASE("the thumbnailer entry's command writes a SIZE x SIZE PNG of a glTF file" *
          doctest::skip(!fs::exists(fs::path(HEADLIGHT_SOURCE_DIR) / "../shared/gltf-conformance"))) {
  const fs::path folder = freshFolder("thumbnailer");
  // The command exactly as a file manager runs it: the entry's Exec line with %i, %o and %s filled in, the
  // program found on PATH (as TryExec finds it).
  std::ifstream entry(fs::path(HEADLIGHT_SOURCE_DIR) / "tools" / "headlight.thumbnailer");
  std::string line, exec, mimeTypes;
  while (std::getline(entry, line)) {
    if (line.rfind("Exec=", 0) == 0) exec = line.substr(5);
    if (line.rfind("MimeType=", 0) == 0) mimeTypes = line.substr(9);
  }
  REQUIRE(!exec.empty());
  CHECK(mimeTypes.find("model/gltf-binary") != std::string::npos);
  CHECK(mimeTypes.find("model/gltf+json") != std::string::npos);
  const fs::path model =
      fs::path(HEADLIGHT_SOURCE_DIR) / "../shared/gltf-conformance/NormalTangentTest/glTF/NormalTangentTest.gltf";
  const fs::path png = folder / "thumbnail.png";
  for (const auto& [code, value] :
       {std::pair<std::string, std::string>{"%i", quote(model.string())}, {"%o", quote(png.string())}, {"%s", "128"}})
    exec.replace(exec.find(code), 2, value);
  const std::string path = "PATH=" + quote(fs::path(HEADLIGHT_THUMBNAILER_EXE).parent_path().string()) + ":$PATH ";
  const Run run = headlight::test::runCommand(path + exec);
  INFO(exec);
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  OIIO::ImageBuf thumbnail(png.string());
  REQUIRE(thumbnail.read());
  CHECK(thumbnail.spec().width == 128);
  CHECK(thumbnail.spec().height == 128);
  CHECK(thumbnail.spec().nchannels == 3);  // preview.png's 8-bit sRGB, the sky behind the model
  const OIIO::ImageBufAlgo::PixelStats stats = OIIO::ImageBufAlgo::computePixelStats(thumbnail);
  CHECK(stats.max[0] - stats.min[0] > 0.2f);  // a picture, not a flat fill
  // A file it cannot read is exit 1 naming it, and no PNG.
  const Run bad = headlight::test::runCommand(quote(HEADLIGHT_THUMBNAILER_EXE) + " /no/such.glb " +
                                              quote((folder / "bad.png").string()) + " 128");
  CHECK(bad.exitCode == 1);
  CHECK(bad.output.find("/no/such.glb") != std::string::npos);
  CHECK_FALSE(fs::exists(folder / "bad.png"));
  CHECK(headlight::test::runCommand(quote(HEADLIGHT_THUMBNAILER_EXE) + " a b 0").exitCode == 2);
  fs::remove_all(folder);
}

TEST_CASE("F3D's habits are usage errors that name headlight's flag, and nothing is rendered") {
  const fs::path folder = freshFolder("f3d-habits");
  struct Habit {
    std::string args;
    std::string says;
  };
  const Habit habits[] = {
      {"--ssgi off", "--no-ssgi"},  // rendered a scene called "off" with SSGI on, then failed
      {"--out " + quote((folder / "x.png").string()), "--out is a folder"},  // made a folder called x.png
      {"--output x.png", "--out DIR"},
      {"--resolution 64,48", "--width W --height H"},
      {"--hdri studio.hdr", "--environment FILE"},
  };
  for (const Habit& habit : habits) {
    const Run run = runHeadlight("render builtin:cornell " + habit.args);
    INFO(habit.args);
    INFO(run.output);
    CHECK(run.exitCode == 2);
    CHECK(run.output.find(habit.says) != std::string::npos);
  }
  CHECK_FALSE(fs::exists(folder / "x.png"));
  // The forms that are ours still work.
  const Run ours = runHeadlight("render builtin:cornell --ssgi=off --width 16 --height 16 --quiet --out " +
                                quote((folder / "x").string()));
  INFO(ours.output);
  CHECK(ours.exitCode == 0);
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

TEST_CASE(
    "reference writes ao_ref, indirect_ref and lit_ref with their channels and standard error, and says "
    "whether it is the screen-space bound" *
    doctest::skip(!HEADLIGHT_HAS_EMBREE)) {
  for (const bool bound : {false, true}) {
    CAPTURE(bound);
    const fs::path out = freshFolder("reference") / "out";
    const Run run =
        runHeadlight("reference --width 32 --height 24 --reference-samples 64 --strict " +
                     std::string(bound ? "--reference-screen-bound " : "") + "--out " + quote(out.string()));
    INFO(run.output);
    REQUIRE(run.exitCode == 0);
    const std::pair<const char*, const char*> files[] = {
        {"ao_ref.exr", "ao.Y"}, {"ao_ref.exr", "sky.Y"}, {"indirect_ref.exr", "indirectR.R"}, {"lit_ref.exr", "R"}};
    for (const auto& [name, channel] : files) {
      CAPTURE(name);
      OIIO::ImageBuf image((out / name).string());
      REQUIRE(image.read());
      CHECK(image.spec().width == 32);
      CHECK(image.spec().channelindex(channel) >= 0);
      CHECK(image.spec().get_string_attribute("headlight:reference:samplesPerPixel") == "64");
      CHECK(std::stod(image.spec().get_string_attribute("headlight:reference:aoMeanStandardError")) > 0.0);
      CHECK(image.spec().get_string_attribute("headlight:reference:screenBound") == (bound ? "on" : "off"));
    }
    fs::remove_all(out.parent_path());
  }
}

TEST_CASE("reference takes render's explicit camera: --eye, --target, --up and --fov trace render's pixels" *
          doctest::skip(!HEADLIGHT_HAS_EMBREE)) {
  // Looking past the spheres' edge: a third of the view is sky, where the
  // fitted camera sees geometry everywhere.
  const fs::path out = freshFolder("reference-camera") / "out";
  const std::string camera = "builtin:spheres --width 32 --height 24 --eye 3,1.2,3 --target 1.5,0.4,0 --fov 50 ";
  // At the pixel centres, as the reference traces them.
  REQUIRE(runHeadlight("render " + camera + "--antialias 1 --out " + quote(out.string())).exitCode == 0);
  const Run run = runHeadlight("reference " + camera + "--reference-samples 4 --out " + quote(out.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  OIIO::ImageBuf rendered((out / "lit.exr").string()), traced((out / "lit_ref.exr").string());
  REQUIRE(rendered.read());
  REQUIRE(traced.read());
  int sky = 0, differ = 0;
  for (int y = 0; y < 24; ++y)
    for (int x = 0; x < 32; ++x) {
      const int ra = rendered.spec().channelindex("A"), rb = traced.spec().channelindex("A");
      const float a = rendered.getchannel(x, y, 0, ra), b = traced.getchannel(x, y, 0, rb);
      sky += a == 0.0f ? 1 : 0;
      differ += (a > 0.5f) != (b > 0.5f) ? 1 : 0;
    }
  CHECK(sky > 32 * 24 / 10);
  CHECK(differ == 0);
  CHECK(runHeadlight("reference builtin:spheres --eye 1,1,1 --out " + quote(out.string())).exitCode ==
        2);  // no --target
  fs::remove_all(out.parent_path());
}

TEST_CASE("reference on a terminal draws its progress with the time left" *
          doctest::skip(!HEADLIGHT_HAS_EMBREE || !fs::exists("/usr/bin/script"))) {
  const fs::path folder = freshFolder("reference-progress");
  // script(1) gives the command a terminal: the bar is drawn only there (a log gets nothing extra).
  const std::string command = quote(HEADLIGHT_EXE) + " reference builtin:cornell --width 48 --height 36 " +
                              "--reference-samples 256 --out " + quote((folder / "out").string());
  const Run run = headlight::test::runCommand("script -qec " + quote(command) + " /dev/null");
  INFO(run.output);
  CHECK(run.exitCode == 0);
  CHECK(run.output.find("36/36") != std::string::npos);  // every row, counted
  CHECK(run.output.find("ETA") != std::string::npos);
  CHECK(run.output.find("tracing 256 rays/pixel") != std::string::npos);
  CHECK(fs::exists(folder / "out" / "lit_ref.exr"));
  fs::remove_all(folder);
}

TEST_CASE("bench writes a CSV whose every row has a time and an error, and a chart" *
          doctest::skip(!HEADLIGHT_HAS_EMBREE)) {
  const fs::path out = freshFolder("bench") / "out";
  const Run run = runHeadlight(
      "bench builtin:cornell --resolutions 32x24 --sweep ssgi-method=hemisphere,radiance "
      "--sweep ssgi-samples=4,16 --ssgi-blur "
      "--sweep ssgi-resolution=full,half --repetitions 2 --warmup 1 --reference-samples 64 --quiet --out " +
      quote(out.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  std::ifstream csv(out / "bench.csv");
  std::string header, line;
  std::getline(csv, header);
  std::vector<std::string> columns;
  std::stringstream headerStream(header);
  for (std::string column; std::getline(headerStream, column, ',');) columns.push_back(column);
  const auto column = [&](const char* name) {
    return std::size_t(std::find(columns.begin(), columns.end(), name) - columns.begin());
  };
  int rows = 0, onFront = 0, seedRows = 0;
  while (std::getline(csv, line)) {
    std::vector<std::string> fields;
    std::stringstream lineStream(line);
    for (std::string field; std::getline(lineStream, field, ',');) fields.push_back(field);
    REQUIRE(fields.size() >= columns.size());
    CHECK(std::stod(fields[column("frame_ms_median")]) > 0.0);
    CHECK(std::stod(fields[column("ao_rmse")]) >= 0.0);
    CHECK(std::stod(fields[column("indirect_rmse")]) >= 0.0);
    CHECK(std::stod(fields[column("lit_flip")]) > 0.0);  // SSGI against a path tracer: never identical
    CHECK(std::stod(fields[column("lit_flip")]) < 1.0);
    CHECK(fields[column("reference_screen_bound")] == "0");  // the truth, unless asked
    onFront += fields[column("pareto_ao")] == "1";
    seedRows += fields[column("seed_default")] == "1";
    ++rows;
  }
  CHECK(rows == 2 * 2 * 2 + 1);  // methods x sample counts x SSGI resolutions + the seed default
  CHECK(onFront >= 1);
  CHECK(seedRows == 1);
  OIIO::ImageBuf chart((out / "bench.png").string());
  CHECK(chart.read());
  CHECK(fs::file_size(out / "bench.svg") > 1000);
  CHECK_FALSE(fs::exists(out / "frames.png"));  // no ssgi-frames sweep, no error-against-N chart
  fs::remove_all(out.parent_path());
}

// bench's CSV as rows of name -> field (the header's names).
std::vector<std::map<std::string, std::string>> readBenchCsv(const fs::path& path) {
  std::ifstream csv(path);
  std::string header, line;
  std::getline(csv, header);
  std::vector<std::string> columns;
  std::stringstream headerStream(header);
  for (std::string column; std::getline(headerStream, column, ',');) columns.push_back(column);
  std::vector<std::map<std::string, std::string>> rows;
  while (std::getline(csv, line)) {
    std::stringstream lineStream(line);
    std::map<std::string, std::string> row;
    std::size_t i = 0;
    for (std::string field; std::getline(lineStream, field, ',') && i < columns.size(); ++i) row[columns[i]] = field;
    rows.push_back(row);
  }
  return rows;
}

TEST_CASE("bench writes into the folder it locked, even when its name is moved during the run (issue 32)" *
          doctest::skip(!HEADLIGHT_HAS_EMBREE)) {
  // The folder is renamed as soon as bench has made it, and a new one takes
  // the name: the run's CSV, JSON and chart (drawn by a python3 child) land
  // in the renamed folder, nothing in the new one.
  const fs::path parent = freshFolder("bench-moved");
  const fs::path out = parent / "out", moved = parent / "out.old";
  const Run run = headlight::test::runCommand(quote(HEADLIGHT_EXE) +
                                              " bench builtin:cornell --resolutions 32x24 --repetitions 3 --warmup 1 "
                                              "--reference-samples 64 --quiet --out " +
                                              quote(out.string()) + " & pid=$!; while [ ! -d " + quote(out.string()) +
                                              " ]; do sleep 0.02; done; mv " + quote(out.string()) + " " +
                                              quote(moved.string()) + "; mkdir " + quote(out.string()) + "; wait $pid");
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  for (const char* name : {"bench.csv", "bench.json", "bench.png"}) {
    CAPTURE(name);
    CHECK(fs::exists(moved / name));
    CHECK(!fs::exists(out / name));
  }
  fs::remove_all(parent);
}

TEST_CASE("bench --no-reference times both fullscreen forms with GPU columns, and needs no reference") {
  const fs::path out = freshFolder("bench-forms") / "out";
  const Run run = runHeadlight(
      "bench builtin:cornell --resolutions 32x24 --no-reference --sweep fullscreen-form=fragment,compute "
      "--repetitions 2 --warmup 1 --quiet --out " +
      quote(out.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  const auto rows = readBenchCsv(out / "bench.csv");
  REQUIRE(rows.size() == 2 + 1);  // two forms + the seed default
  int compute = 0;
  for (const auto& row : rows) {
    CHECK(std::stod(row.at("frame_ms_median")) > 0.0);
    // Known (a number >= 0), or nan where llvmpipe gave no GPU time for a pass of every frame.
    for (const char* gpu : {"frame_gpu_ms_median", "ssgi_gpu_ms_median"})
      CHECK((row.at(gpu) == "nan" || std::stod(row.at(gpu)) >= 0.0));
    CHECK(row.at("ao_rmse") == "nan");  // no reference, no error
    // lit judged at the pixel centres, as the reference traces them, unless --antialias is given.
    CHECK(row.at("antialias") == "1");
    if (row.at("fullscreen-form") == "compute") {
      ++compute;
      CHECK(row.at("forms").find("ssgi=compute") != std::string::npos);
      CHECK(row.at("forms").find("fragment") == std::string::npos);
    }
  }
  CHECK(compute == 1);
  CHECK_FALSE(fs::exists(out / "bench.png"));  // the chart plots errors: none without a reference
  fs::remove_all(out.parent_path());
}

TEST_CASE("bench sweeping ssgi=on,off measures no SSGI as open and unlit" * doctest::skip(!HEADLIGHT_HAS_EMBREE)) {
  const fs::path out = freshFolder("bench-ssgi-off") / "out";
  const Run run = runHeadlight(
      "bench builtin:cornell --resolutions 32x24 --sweep ssgi=on,off --repetitions 1 "
      "--warmup 0 --reference-samples 16 --no-chart --quiet --out " +
      quote(out.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  const auto rows = readBenchCsv(out / "bench.csv");
  REQUIRE(rows.size() == 2 + 1);
  std::map<std::string, double> aoError;
  for (const auto& row : rows)
    if (row.at("seed_default") == "0") aoError[row.at("ssgi")] = std::stod(row.at("ao_rmse"));
  REQUIRE(aoError.size() == 2);
  // Without SSGI every pixel is taken as open (AO 1): further from cornell's reference AO than the default's.
  CHECK(aoError["off"] > aoError["on"]);
  fs::remove_all(out.parent_path());
}

TEST_CASE("bench sweeping ssgi-frames also charts the AO error against N" * doctest::skip(!HEADLIGHT_HAS_EMBREE)) {
  const fs::path out = freshFolder("bench-frames") / "out";
  const Run run = runHeadlight(
      "bench builtin:spheres --resolutions 32x24 --ssgi-method bitmask --sweep ssgi-frames=1,2,4 "
      "--repetitions 1 --warmup 0 --reference-samples 16 --quiet --out " +
      quote(out.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  OIIO::ImageBuf chart((out / "frames.png").string());
  REQUIRE(chart.read());
  CHECK(chart.spec().width >= 400);  // 7 x 4.5 inches at 110 dpi: 770 x 495
  CHECK(fs::file_size(out / "frames.svg") > 1000);
  fs::remove_all(out.parent_path());
}

TEST_CASE("without Embree, reference says it is not built" * doctest::skip(HEADLIGHT_HAS_EMBREE)) {
  const Run run = runHeadlight("reference --width 8 --height 8 --out /nonexistent");
  CHECK(run.exitCode == 1);
  CHECK(run.output.find("built without Embree") != std::string::npos);
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

// OpenImageIO is loaded on first use (lib/image_io/image_module.hpp): the
// dynamic loader's own log (LD_DEBUG=libs) shows whether a command loaded it.
TEST_CASE("--version, --help and a usage error do not load OpenImageIO; a render does") {
  auto loadsOiio = [](const std::string& args) {
    const Run run = headlight::test::runCommand("LD_DEBUG=libs " + quote(HEADLIGHT_EXE) + " " + args);
    INFO(args);
    REQUIRE(run.output.find("calling init") != std::string::npos);  // LD_DEBUG took effect
    return run.output.find("libOpenImageIO.so") != std::string::npos;
  };
  CHECK_FALSE(loadsOiio("--version"));
  CHECK_FALSE(loadsOiio("render --help"));
  CHECK_FALSE(loadsOiio("render --width 0"));
  const fs::path out = freshFolder("module-loaded") / "out";
  CHECK(loadsOiio("render --width 16 --height 16 --quiet --out " + quote(out.string())));
  CHECK(fs::exists(out / "frame.json"));
  fs::remove_all(out.parent_path());
}

TEST_CASE("a missing image module is exit 1 naming the path and the remedy, and no output") {
  const fs::path folder = freshFolder("no-module");
  const std::string missing = (folder / "nowhere" / "libheadlight-image-io.so").string();
  const Run run =
      headlight::test::runCommand("HEADLIGHT_IMAGE_MODULE=" + quote(missing) + " " + quote(HEADLIGHT_EXE) +
                                  " render --width 16 --height 16 --out " + quote((folder / "out").string()));
  INFO(run.output);
  CHECK(run.exitCode == 1);
  CHECK(run.output.find(missing) != std::string::npos);
  CHECK(run.output.find("HEADLIGHT_IMAGE_MODULE") != std::string::npos);
  CHECK(folderEmpty(folder / "out"));
  fs::remove_all(folder);
}

TEST_CASE(
    "the CLI asks glibc for huge pages where the kernel gives them on request, and leaves a caller's GLIBC_TUNABLES "
    "alone") {
  // The kernel's policy, read here as the kernel writes it ("always [madvise] never").
  std::string policy;
  {
    std::ifstream file("/sys/kernel/mm/transparent_hugepage/enabled");
    std::string line;
    std::getline(file, line);
    if (const auto open = line.find('['), close = line.find(']'); open != std::string::npos && close > open)
      policy = line.substr(open + 1, close - open - 1);
  }
  const fs::path folder = freshFolder("large-pages");
  const std::string render = " render builtin:cornell --width 16 --height 16 --targets depth --verbose --out " +
                             quote((folder / "out").string());
  const Run restarted = headlight::test::runCommand("env -u GLIBC_TUNABLES " + quote(HEADLIGHT_EXE) + render);
  const Run callers =
      headlight::test::runCommand("env GLIBC_TUNABLES=glibc.malloc.arena_max=2 " + quote(HEADLIGHT_EXE) + render);
  INFO(restarted.output);
  INFO(callers.output);
  REQUIRE(restarted.exitCode == 0);
  REQUIRE(callers.exitCode == 0);
  if (policy == "madvise") {
    CHECK(restarted.output.find("memory: transparent huge pages on (policy 'madvise', "
                                "GLIBC_TUNABLES=glibc.malloc.hugetlb=1)") != std::string::npos);
    CHECK(callers.output.find("memory: transparent huge pages off (policy 'madvise', "
                              "GLIBC_TUNABLES=glibc.malloc.arena_max=2)") != std::string::npos);
  } else {
    MESSAGE("skipped the restart: this kernel's huge-page policy is '" << policy << "', not madvise");
    CHECK(restarted.output.find("memory: transparent huge pages ") != std::string::npos);
    CHECK(restarted.output.find("GLIBC_TUNABLES=glibc.malloc.hugetlb=1") == std::string::npos);
  }
  fs::remove_all(folder);
}

TEST_CASE("render --targets ids --png ids: a segmentation mask, its colours and its names, without lighting") {
  const fs::path folder = freshFolder("ids");
  const fs::path out = folder / "out";
  const Run run = runHeadlight(
      "render builtin:cornell --width 48 --height 36 --targets ids --png ids --verbose --out " + quote(out.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK(fs::exists(out / "ids.exr"));
  CHECK_FALSE(fs::exists(out / "lit.exr"));
  CHECK(run.output.find("ids.exr: 48x36 uint32 instance.id [0, ") != std::string::npos);
  CHECK(run.output.find("8-bit PNG of ids (each instance id a colour, background black)") != std::string::npos);
  CHECK(run.output.find("composite") != std::string::npos);  // --verbose names it as skipped: lit not asked for
  std::ifstream manifest(out / "frame.json");
  const nlohmann::json json = nlohmann::json::parse(manifest);
  REQUIRE(json.contains("ids"));
  CHECK(json["ids"]["instance"][0]["name"] == "floor");
  CHECK(json["ids"]["material"].back()["name"] == "glTF default material");
  // diff compares the labels exactly: the set against itself passes, row "ids", metric mismatch.
  const Run diff = runHeadlight("diff " + quote((out / "ids.exr").string()) + " " + quote((out / "ids.exr").string()));
  INFO(diff.output);
  CHECK(diff.exitCode == 0);
  CHECK(diff.output.find("error = 1 where a != b, else 0") != std::string::npos);
  fs::remove_all(folder);
}

TEST_CASE("render --png writes the named targets as PNGs, drawn even when --targets leaves out their EXR") {
  const fs::path folder = freshFolder("png");
  const fs::path out = folder / "out";
  const Run run = runHeadlight(
      "render builtin:cornell --width 32 --height 24 --targets lit,preview --png normal,depth "
      "--preview-background transparent --out " +
      quote(out.string()));
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  CHECK(fs::exists(out / "lit.exr"));
  CHECK_FALSE(fs::exists(out / "normal.exr"));  // not asked for as EXR
  for (const char* png : {"normal.png", "depth.png", "preview.png"}) {
    CAPTURE(png);
    OIIO::ImageBuf image((out / png).string());
    REQUIRE(image.read());
    CHECK(image.spec().width == 32);
    CHECK(image.nchannels() == (std::string(png) == "preview.png" ? 4 : 3));  // the preview's alpha: coverage
  }
  CHECK(run.output.find("8-bit PNG of normal (vectors as (v + 1) / 2)") != std::string::npos);
  // frame.json lists the PNGs: they belong to the set (--resume, ownership).
  std::ifstream manifest(out / "frame.json");
  const std::string json((std::istreambuf_iterator<char>(manifest)), std::istreambuf_iterator<char>());
  CHECK(json.find("\"normal.png\"") != std::string::npos);

  // Another PNG list is another job: --resume renders it again.
  const Run again = runHeadlight(
      "render builtin:cornell --width 32 --height 24 --targets lit,preview --png normal "
      "--preview-background transparent --resume --out " +
      quote(out.string()));
  INFO(again.output);
  CHECK(again.exitCode == 0);
  CHECK(again.output.find("skipped") == std::string::npos);
  CHECK_FALSE(fs::exists(out / "depth.png"));  // the earlier set's, removed

  const Run unknown = runHeadlight("render builtin:cornell --png preview --out " + quote((folder / "x").string()));
  CHECK(unknown.exitCode == 2);
  CHECK(unknown.output.find("--png: unknown target 'preview'") != std::string::npos);
  const Run badBackground =
      runHeadlight("render builtin:cornell --preview-background blue --out " + quote((folder / "x").string()));
  CHECK(badBackground.exitCode == 2);
  CHECK(badBackground.output.find("preview-background 'blue'") != std::string::npos);
  CHECK_FALSE(fs::exists(folder / "x"));
  fs::remove_all(folder);
}

TEST_CASE(
    "bench replaces only its own files in --out: a user's bench.csv is refused, named, and kept; --force replaces it") {
  const fs::path folder = freshFolder("bench-ours");
  const fs::path out = folder / "out";
  const std::string bench =
      "bench builtin:cornell --resolutions 16x16 --sweep ssgi-samples=4 --repetitions 1 "
      "--warmup 0 --no-reference --quiet --out " +
      quote(out.string());
  Run run = runHeadlight(bench);
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  run = runHeadlight(bench);  // an earlier bench's files: replaced
  CHECK(run.exitCode == 0);
  fs::remove(out / "bench.json");
  { std::ofstream(out / "bench.csv") << "my,own\n1,2\n"; }
  run = runHeadlight(bench);
  CHECK(run.exitCode == 1);
  CHECK(run.output.find(out.string() + " holds bench.csv, which no earlier headlight bench wrote; pass --force to "
                                       "replace it") != std::string::npos);
  CHECK_FALSE(fs::exists(out / "bench.json"));  // refused before measuring: nothing written
  std::ifstream kept(out / "bench.csv");
  CHECK(std::string((std::istreambuf_iterator<char>(kept)), std::istreambuf_iterator<char>()) == "my,own\n1,2\n");
  run = runHeadlight(bench + " --force");
  CHECK(run.exitCode == 0);
  CHECK(fs::exists(out / "bench.json"));
  fs::remove_all(folder);
}

#if HEADLIGHT_HAS_EMBREE
TEST_CASE(
    "reference replaces only its own EXRs in --out: a user's lit_ref.exr is refused and kept; --force replaces it") {
  const fs::path folder = freshFolder("reference-ours");
  const fs::path out = folder / "out";
  const std::string reference =
      "reference builtin:cornell --width 16 --height 12 --reference-samples 4 --quiet --out " + quote(out.string());
  Run run = runHeadlight(reference);
  INFO(run.output);
  REQUIRE(run.exitCode == 0);
  run = runHeadlight(reference);  // its own files: replaced
  CHECK(run.exitCode == 0);
  { std::ofstream(out / "lit_ref.exr") << "not an image of Headlight's"; }
  run = runHeadlight(reference);
  CHECK(run.exitCode == 1);
  CHECK(run.output.find("holds lit_ref.exr, which no earlier headlight reference wrote") != std::string::npos);
  CHECK(fs::file_size(out / "lit_ref.exr") == std::string("not an image of Headlight's").size());
  run = runHeadlight(reference + " --force");
  CHECK(run.exitCode == 0);
  CHECK(fs::file_size(out / "lit_ref.exr") > 100);
  fs::remove_all(folder);
}
#endif

// headlight diff: the library (headlight/diff.hpp) and the CLI command
// (runDiffCommand, called directly). Images are small EXRs written here with
// OpenImageIO; each case states which threshold it sits between.
#include <doctest/doctest.h>

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imageio.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <numbers>
#include <sstream>

#include "color/srgb.hpp"
#include "diff/flip.hpp"
#include "diff_command.hpp"
#include "headlight/diff.hpp"
#include "headlight/error.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
namespace fs = std::filesystem;

namespace {

struct TestImage {
  int width = 8, height = 8;
  std::vector<std::string> channels{"R", "G", "B"};
  std::vector<float> pixels;
  float far = 0;  // written as headlight:far when > 0

  float& at(int x, int y, int c) {
    return pixels[(std::size_t(y) * std::size_t(width) + std::size_t(x)) * channels.size() + std::size_t(c)];
  }
};

// A smooth gradient in 0.1..0.9, different per channel.
TestImage gradient(int width, int height, std::vector<std::string> channels) {
  TestImage image;
  image.width = width;
  image.height = height;
  image.channels = std::move(channels);
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x)
      for (std::size_t c = 0; c < image.channels.size(); ++c)
        image.pixels.push_back(0.1f + 0.8f * float((x + 2 * y + 3 * int(c)) % 17) / 16.0f);
  return image;
}

void write(const fs::path& path, const TestImage& image) {
  OIIO::ImageSpec spec(image.width, image.height, int(image.channels.size()), OIIO::TypeDesc::FLOAT);
  spec.channelnames = image.channels;
  if (image.far > 0) spec.attribute("headlight:far", image.far);
  auto output = OIIO::ImageOutput::create(path.string());
  REQUIRE(output);
  REQUIRE(output->open(path.string(), spec));
  REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()));
  REQUIRE(output->close());
}

struct Cli {
  int exitCode = -1;
  std::string out, err;
};

Cli runCli(std::vector<std::string> args) {
  std::ostringstream out, err;
  Cli cli;
  cli.exitCode = cli::runDiffCommand(args, out, err);
  cli.out = out.str();
  cli.err = err.str();
  return cli;
}

bool contains(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

// Unit normals in many directions (none axis-aligned), background (0) in the first row.
TestImage normals() {
  TestImage image;
  image.width = 16;
  image.height = 16;
  image.channels = {"normal.X", "normal.Y", "normal.Z"};
  for (int y = 0; y < image.height; ++y)
    for (int x = 0; x < image.width; ++x) {
      if (y == 0) {
        image.pixels.insert(image.pixels.end(), {0.0f, 0.0f, 0.0f});
        continue;
      }
      const double theta = 0.1 + 2.9 * x / 15.0, phi = 0.3 + 6.0 * y / 15.0;
      image.pixels.insert(image.pixels.end(), {float(std::sin(theta) * std::cos(phi)), float(std::cos(theta)),
                                               float(std::sin(theta) * std::sin(phi))});
    }
  return image;
}

// Rotates every vector by `degrees` about an axis perpendicular to it, so
// each normal moves by exactly that angle.
TestImage rotated(TestImage image, double degrees) {
  const double angle = degrees * std::numbers::pi / 180.0;
  for (std::size_t p = 0; p < image.pixels.size(); p += 3) {
    const double n[3] = {image.pixels[p], image.pixels[p + 1], image.pixels[p + 2]};
    if (n[0] == 0 && n[1] == 0 && n[2] == 0) continue;
    // t = normalize(n x (0.3, 0.5, 0.8)) is perpendicular to n; rotate towards it.
    double t[3] = {n[1] * 0.8 - n[2] * 0.5, n[2] * 0.3 - n[0] * 0.8, n[0] * 0.5 - n[1] * 0.3};
    const double length = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
    for (int i = 0; i < 3; ++i)
      image.pixels[p + std::size_t(i)] = float(std::cos(angle) * n[i] + std::sin(angle) * t[i] / length);
  }
  return image;
}

}  // namespace

TEST_CASE("diff: identical images pass with zero error, library and CLI" * doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_identical");
  const TestImage image = gradient(12, 10, {"R", "G", "B", "A"});
  write(folder / "a.exr", image);
  write(folder / "b.exr", image);
  const DiffResult result = diffImages(folder / "a.exr", folder / "b.exr");
  CHECK(result.status == DiffStatus::Pass);
  CHECK(result.problem.empty());
  CHECK(result.maxError == 0);
  CHECK(result.pixelCount == 120);
  REQUIRE(result.channels.size() == 4);
  for (const ChannelDiff& channel : result.channels) {
    CHECK(channel.meanError == 0);
    CHECK(channel.failingPixels == 0);
    CHECK(std::isinf(channel.psnr));
  }
  const Cli cli = runCli({(folder / "a.exr").string(), (folder / "b.exr").string()});
  INFO(cli.out, cli.err);
  CHECK(cli.exitCode == 0);
  CHECK(contains(cli.out, "PASS"));
  fs::remove_all(folder);
}

TEST_CASE("diff: idiff's levels on an absolute target (albedo: warn 2e-3, fail 1e-2, 0.5 % allowed)" *
          doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_levels");
  const TestImage reference = gradient(20, 20, {"albedo.B", "albedo.G", "albedo.R"});  // 400 pixels
  write(folder / "albedo.exr", reference);
  const fs::path b = folder / "b" / "albedo.exr";
  fs::create_directories(b.parent_path());
  auto diffWith = [&](const TestImage& changed, const DiffOptions& options = {}) {
    write(b, changed);
    return diffImages(folder / "albedo.exr", b, options);
  };

  SUBCASE("a change under warn passes") {
    TestImage changed = reference;
    changed.at(3, 4, 1) += 1e-3f;
    const DiffResult result = diffWith(changed);
    CHECK(result.status == DiffStatus::Pass);
    CHECK(result.maxError == doctest::Approx(1e-3).epsilon(1e-3));
    CHECK(result.warningPixels == 0);
  }
  SUBCASE("over warn, under fail: warn, naming the pixel") {
    TestImage changed = reference;
    for (float& value : changed.pixels) value += 5e-3f;
    const DiffResult result = diffWith(changed);
    CHECK(result.status == DiffStatus::Warn);
    CHECK(result.warningPixels == 400);
    CHECK(result.failingPixels == 0);
    CHECK(contains(result.problem, "> warn 0.002"));
  }
  SUBCASE("over fail in more than failpercent: fail, with count, percent and the max pixel") {
    TestImage changed = reference;
    for (int x = 0; x < 20; ++x) changed.at(x, 7, 2) += 0.05f;  // 20 of 400 pixels: 5 %
    changed.at(11, 7, 2) += 0.05f;                              // the largest: 0.1
    const DiffResult result = diffWith(changed);
    CHECK(result.status == DiffStatus::Fail);
    CHECK(result.failingPixels == 20);
    CHECK(result.failingPercent == doctest::Approx(5.0));
    CHECK(result.maxX == 11);
    CHECK(result.maxY == 7);
    CHECK(result.maxChannel == "albedo.R");
    // Look channels up by name: OpenImageIO's EXR reader puts R, G, B first.
    auto channel = [&](const std::string& name) -> const ChannelDiff& {
      for (const ChannelDiff& c : result.channels)
        if (c.name == name) return c;
      FAIL("no channel " << name);
      return result.channels[0];
    };
    const ChannelDiff& red = channel("albedo.R");
    CHECK(red.failingPixels == 20);
    CHECK(red.maxError == doctest::Approx(0.1).epsilon(1e-4));
    CHECK(red.valuesB[0] - red.valuesA[0] == doctest::Approx(0.1).epsilon(1e-4));
    CHECK(channel("albedo.B").failingPixels == 0);
    CHECK(contains(result.problem, "5% of pixels (20)"));
    // A larger allowance turns it into a warning.
    DiffOptions lenient;
    lenient.failPercent = 10;
    CHECK(diffWith(changed, lenient).status == DiffStatus::Warn);
  }
  SUBCASE("within failpercent but over hardfail: fail") {
    TestImage changed = reference;
    changed.at(5, 5, 0) += 0.5f;  // 1 of 400 pixels = 0.25 % < 0.5 %
    CHECK(diffWith(changed).status == DiffStatus::Warn);
    DiffOptions hard;
    hard.hardFail = 0.3;
    const DiffResult result = diffWith(changed, hard);
    CHECK(result.status == DiffStatus::Fail);
    CHECK(contains(result.problem, "hardfail 0.3"));
  }
  fs::remove_all(folder);
}

TEST_CASE("diff: structural mismatches and file errors are statuses that name the problem" *
          doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_structural");
  write(folder / "a.exr", gradient(8, 8, {"R", "G", "B"}));
  write(folder / "small.exr", gradient(8, 6, {"R", "G", "B"}));
  write(folder / "other.exr", gradient(8, 8, {"R", "G", "Z"}));
  write(folder / "reordered.exr", gradient(8, 8, {"B", "G", "R"}));
  std::ofstream(folder / "garbage.exr") << "not an image";

  const DiffResult size = diffImages(folder / "a.exr", folder / "small.exr");
  CHECK(size.status == DiffStatus::Structural);
  CHECK(contains(size.problem, "A is 8x8, B is 8x6"));
  CHECK(size.difference.empty());

  const DiffResult names = diffImages(folder / "a.exr", folder / "other.exr");
  CHECK(names.status == DiffStatus::Structural);
  CHECK(contains(names.problem, "only in A: B"));
  CHECK(contains(names.problem, "only in B: Z"));

  // Same names in another order are matched by name (the values differ, so
  // it fails, but it is no structural problem).
  CHECK(diffImages(folder / "a.exr", folder / "reordered.exr").status == DiffStatus::Fail);

  DiffOptions pick;
  pick.channels = {"R", "Q"};
  const DiffResult unknown = diffImages(folder / "a.exr", folder / "a.exr", pick);
  CHECK(unknown.status == DiffStatus::Structural);
  CHECK(contains(unknown.problem, "no channel 'Q'"));
  pick.channels = {"G"};
  const DiffResult one = diffImages(folder / "a.exr", folder / "other.exr", pick);
  CHECK(one.status == DiffStatus::Pass);
  CHECK(one.channels.size() == 1);

  const DiffResult missing = diffImages(folder / "a.exr", folder / "nope.exr");
  CHECK(missing.status == DiffStatus::FileError);
  CHECK(contains(missing.problem, "nope.exr: no such file"));
  const DiffResult garbage = diffImages(folder / "garbage.exr", folder / "a.exr");
  CHECK(garbage.status == DiffStatus::FileError);
  CHECK(contains(garbage.problem, "garbage.exr"));

  CHECK(runCli({(folder / "a.exr").string(), (folder / "small.exr").string()}).exitCode == 3);
  CHECK(runCli({(folder / "a.exr").string(), (folder / "other.exr").string()}).exitCode == 3);
  const Cli cli = runCli({(folder / "a.exr").string(), (folder / "nope.exr").string()});
  CHECK(cli.exitCode == 4);
  CHECK(contains(cli.out, "nope.exr"));
  fs::remove_all(folder);
}

TEST_CASE("diff: normals are compared by angle, not per component" * doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_normals");
  const TestImage reference = normals();
  write(folder / "normal.exr", reference);
  fs::create_directories(folder / "b");
  write(folder / "b" / "normal.exr", rotated(reference, 2.0));
  const fs::path a = folder / "normal.exr", b = folder / "b" / "normal.exr";

  const DiffResult result = diffImages(a, b);
  CHECK(result.metric == DiffMetric::AngleDegrees);
  REQUIRE(result.channels.size() == 1);
  const ChannelDiff& angle = result.channels[0];
  CHECK(angle.name == "normal.angle");
  CHECK(angle.sources == std::vector<std::string>{"normal.X", "normal.Y", "normal.Z"});
  CHECK(angle.maxError == doctest::Approx(2.0).epsilon(1e-3));
  CHECK(angle.meanError == doctest::Approx(2.0 * 240 / 256).epsilon(1e-3));  // background row: 0
  CHECK(angle.valuesA.size() == 3);
  // Default: warn 0.1 deg, fail 1 deg, so 2 degrees everywhere fails.
  CHECK(result.status == DiffStatus::Fail);
  CHECK(result.failingPixels == 240);

  DiffOptions loose;
  loose.fail = 3;  // degrees
  CHECK(diffImages(a, b, loose).status == DiffStatus::Warn);
  // The mean bound: every pixel within fail, but the mean of 1.875 degrees
  // over the table's 1 degree fails once the caller asks for that bound.
  DiffOptions meanBound = loose;
  meanBound.failMean = 1.0;
  const DiffResult tooHighOnAverage = diffImages(a, b, meanBound);
  CHECK(tooHighOnAverage.status == DiffStatus::Fail);
  CHECK(tooHighOnAverage.problem.find("mean error 1.875 in normal.angle > failmean 1") != std::string::npos);
  loose.warn = 2.5;
  CHECK(diffImages(a, b, loose).status == DiffStatus::Pass);
  // Components move by at most sin(2 deg) = 0.035: per component, fail 0.05
  // would pass. As an angle, 2 degrees > 0.05 degrees fails.
  DiffOptions componentSized;
  componentSized.fail = 0.05;
  CHECK(diffImages(a, b, componentSized).status == DiffStatus::Fail);

  // A file named otherwise gets idiff's defaults unless the target is named.
  fs::copy_file(a, folder / "golden.exr");
  CHECK(diffImages(folder / "golden.exr", b).metric == DiffMetric::Absolute);
  const Cli named = runCli({(folder / "golden.exr").string(), b.string(), "--target", "normal", "--json"});
  CHECK(named.exitCode == 2);
  CHECK(nlohmann::json::parse(named.out)["metric"] == "angle-degrees");

  // Geometry in one image only (a zero normal against a unit one) is 180 degrees.
  TestImage hole = reference;
  hole.at(4, 4, 0) = hole.at(4, 4, 1) = hole.at(4, 4, 2) = 0;
  write(b, hole);
  const DiffResult holeResult = diffImages(a, b);
  CHECK(holeResult.maxError == doctest::Approx(180.0));
  CHECK(holeResult.maxX == 4);
  CHECK(holeResult.failingPixels == 1);
  CHECK(holeResult.status == DiffStatus::Warn);  // 1 of 256 pixels is within the 0.5 % allowance
  fs::remove_all(folder);
}

TEST_CASE("diff: position and depth are relative to headlight:far, emissive to max(1, |value|)" *
          doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_relative");
  fs::create_directories(folder / "b");
  TestImage position = gradient(10, 10, {"A", "position.X", "position.Y", "position.Z"});
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) position.at(x, y, 0) = 1;
  TestImage moved = position;
  for (std::size_t p = 1; p < moved.pixels.size(); p += 4) moved.pixels[p] += 0.005f;  // X by 5 mm

  position.far = moved.far = 10;  // 5e-4 of the view depth: over warn 1e-5, under fail 1e-3
  write(folder / "position.exr", position);
  write(folder / "b" / "position.exr", moved);
  DiffResult result = diffImages(folder / "position.exr", folder / "b" / "position.exr");
  CHECK(result.metric == DiffMetric::RelativeToScene);
  CHECK(result.scale == 10);
  CHECK(result.scaleSource == "headlight:far of A");
  CHECK(result.maxError == doctest::Approx(5e-4).epsilon(1e-2));
  CHECK(result.status == DiffStatus::Warn);

  position.far = moved.far = 1;  // 5e-3: fails
  write(folder / "position.exr", position);
  write(folder / "b" / "position.exr", moved);
  CHECK(diffImages(folder / "position.exr", folder / "b" / "position.exr").status == DiffStatus::Fail);

  // Coverage stays absolute even with a huge scene: a pixel losing its
  // geometry is an error of 1, not 1 / far.
  position.far = 1e6f;
  TestImage uncovered = position;
  for (int x = 0; x < 10; ++x) uncovered.at(x, 0, 0) = 0;  // 10 % of pixels
  write(folder / "position.exr", position);
  write(folder / "b" / "position.exr", uncovered);
  result = diffImages(folder / "position.exr", folder / "b" / "position.exr");
  CHECK(result.status == DiffStatus::Fail);
  CHECK(result.maxChannel == "A");
  CHECK(result.maxError == 1);

  // emissive (HDR radiance): 1 % of a bright value warns; 0.1 on a value of 0.5 fails.
  TestImage emissive = gradient(10, 10, {"R", "G", "B"});
  emissive.at(2, 2, 0) = 100;
  TestImage brighter = emissive;
  brighter.at(2, 2, 0) = 101;
  write(folder / "emissive.exr", emissive);
  write(folder / "b" / "emissive.exr", brighter);
  result = diffImages(folder / "emissive.exr", folder / "b" / "emissive.exr");
  CHECK(result.metric == DiffMetric::RelativeToValue);
  CHECK(result.maxError == doctest::Approx(0.01).epsilon(1e-3));
  CHECK(result.status == DiffStatus::Warn);
  TestImage darker = emissive;
  for (int x = 0; x < 10; ++x) darker.at(x, 5, 1) -= 0.1f;
  write(folder / "b" / "emissive.exr", darker);
  CHECK(diffImages(folder / "emissive.exr", folder / "b" / "emissive.exr").status == DiffStatus::Fail);
  fs::remove_all(folder);
}

TEST_CASE("diff: any NaN or Inf fails, even in the same pixel of both images" * doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_nan");
  TestImage image = gradient(8, 8, {"R", "G", "B"});
  write(folder / "a.exr", image);
  TestImage broken = image;
  broken.at(2, 3, 1) = std::nanf("");
  write(folder / "b.exr", broken);
  DiffResult result = diffImages(folder / "a.exr", folder / "b.exr");
  CHECK(result.status == DiffStatus::Fail);
  CHECK(result.nonFiniteValues == 1);
  CHECK(result.channels[1].nonFiniteB == 1);
  CHECK(contains(result.problem, "NaN"));
  // OIIO's compare() skips a NaN present in both images; headlight does not.
  write(folder / "a.exr", broken);
  result = diffImages(folder / "a.exr", folder / "b.exr");
  CHECK(result.status == DiffStatus::Fail);
  CHECK(result.nonFiniteValues == 2);
  broken.at(2, 3, 1) = INFINITY;
  write(folder / "b.exr", broken);
  CHECK(runCli({(folder / "a.exr").string(), (folder / "b.exr").string(), "--quiet"}).exitCode == 2);
  fs::remove_all(folder);
}

TEST_CASE("diff: --json prints one object with the numbers and thresholds used" * doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_json");
  const TestImage image = gradient(10, 10, {"ao.Y", "indirect.B", "indirect.G", "indirect.R"});
  write(folder / "ssgi.exr", image);
  TestImage changed = image;
  changed.at(6, 2, 0) += 0.25f;  // one pixel: 1 % of 100, within ssgi's 1 % allowance
  fs::create_directories(folder / "b");
  write(folder / "b" / "ssgi.exr", changed);
  const Cli cli = runCli({(folder / "ssgi.exr").string(), (folder / "b" / "ssgi.exr").string(), "--json", "--warn",
                          "0.3", "--hardfail=inf"});
  INFO(cli.out, cli.err);
  CHECK(cli.exitCode == 0);
  const nlohmann::json j = nlohmann::json::parse(cli.out);
  CHECK(j["status"] == "pass");
  CHECK(j["exit_code"] == 0);
  CHECK(j["target"] == "ssgi");
  CHECK(j["metric"] == "absolute");
  CHECK(j["thresholds"]["fail"].get<double>() == doctest::Approx(0.05));
  CHECK(j["thresholds"]["warn"].get<double>() == doctest::Approx(0.3));  // the flag won over the table
  CHECK(j["thresholds"]["fail_percent"].get<double>() == doctest::Approx(1.0));
  CHECK(j["thresholds"]["hard_fail"].is_null());  // inf
  CHECK(j["failing_pixels"] == 1);
  CHECK(j["max_error"].get<double>() == doctest::Approx(0.25));
  REQUIRE(j["channels"].size() == 4);
  const nlohmann::json& ao = j["channels"][0];
  CHECK(ao["name"] == "ao.Y");
  CHECK(ao["max_x"] == 6);
  CHECK(ao["max_y"] == 2);
  CHECK(ao["max_error"].get<double>() == doctest::Approx(0.25));
  CHECK(ao["value_b"][0].get<double>() - ao["value_a"][0].get<double>() == doctest::Approx(0.25));
  CHECK(ao["mean_error"].get<double>() == doctest::Approx(0.0025));
  CHECK(ao["failing_percent"].get<double>() == doctest::Approx(1.0));
  CHECK(j["channels"][1]["psnr"].is_null());  // identical channel: PSNR inf
  fs::remove_all(folder);
}

TEST_CASE("diff: folder mode reports each target and the worst verdict" * doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_folders");
  const fs::path a = folder / "a", b = folder / "b";
  fs::create_directories(a);
  fs::create_directories(b);
  TestImage depth = gradient(10, 10, {"depth.Z"});
  depth.far = 5;
  const TestImage albedo = gradient(10, 10, {"albedo.B", "albedo.G", "albedo.R"});
  const TestImage lit = gradient(10, 10, {"A", "B", "G", "R"});
  for (const fs::path& dir : {a, b}) {
    write(dir / "depth.exr", depth);
    write(dir / "lit.exr", lit);
  }
  write(a / "albedo.exr", albedo);
  TestImage changed = albedo;
  for (int x = 0; x < 10; ++x) changed.at(x, 4, 2) += 0.2f;
  write(b / "albedo.exr", changed);
  write(a / "notes.exr", albedo);  // not a target: ignored

  const DirectoryDiff result = diffDirectories(a, b);
  CHECK(result.status == DiffStatus::Fail);
  REQUIRE(result.targets.size() == 3);
  CHECK(result.targets[0].target == "albedo");
  CHECK(result.targets[0].status == DiffStatus::Fail);
  CHECK(result.targets[1].target == "depth");
  CHECK(result.targets[1].status == DiffStatus::Pass);
  CHECK(result.targets[2].status == DiffStatus::Pass);

  const fs::path out = folder / "diffs";
  Cli cli = runCli({a.string(), b.string(), "--out", out.string()});
  INFO(cli.out, cli.err);
  CHECK(cli.exitCode == 2);
  CHECK(contains(cli.out, "albedo    FAIL"));
  CHECK(contains(cli.out, "depth     PASS"));
  CHECK(contains(cli.out, "verdict: FAIL (3 targets: 2 pass, 0 warn, 1 fail"));
  CHECK(fs::exists(out / "albedo_diff.exr"));
  CHECK(fs::exists(out / "albedo_diff.png"));
  CHECK(fs::exists(out / "lit_diff.exr"));
  CHECK(fs::exists(out / "lit_diff_a.png"));  // lit is judged by FLIP: its images beside the map
  std::ifstream report(out / "report.html");
  const std::string page((std::istreambuf_iterator<char>(report)), std::istreambuf_iterator<char>());
  CHECK(contains(page, "albedo_diff.png"));
  CHECK(contains(page, "lit_diff_b.png"));
  CHECK(contains(page, "<span class='fail'>FAIL</span>"));

  // A target in one folder only is structural, and the worst status wins.
  write(b / "ssgi.exr", gradient(10, 10, {"ao.Y"}));
  cli = runCli({a.string(), b.string()});
  CHECK(cli.exitCode == 3);
  CHECK(contains(cli.out, "ssgi      STRUCTURAL"));
  CHECK(contains(cli.out, "ssgi.exr is in " + b.string() + " only"));

  // Folders with no target, a missing folder, a folder against a file.
  fs::create_directories(folder / "empty");
  CHECK(runCli({(folder / "empty").string(), (folder / "empty").string()}).exitCode == 4);
  CHECK(runCli({a.string(), (folder / "nowhere").string()}).exitCode == 4);
  CHECK(runCli({a.string(), (a / "lit.exr").string()}).exitCode == 5);
  CHECK(runCli({a.string(), b.string(), "--channels", "R"}).exitCode == 5);
  fs::remove_all(folder);
}

TEST_CASE("diff: --out writes a float diff.exr and a diff.png heatmap, atomically" * doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_out");
  const TestImage image = gradient(16, 16, {"R", "G", "B"});
  TestImage changed = image;
  changed.at(3, 3, 0) += 1.0f;
  write(folder / "lit.exr", image);
  write(folder / "changed.exr", changed);
  const fs::path exr = folder / "report" / "diff.exr";
  fs::create_directories(exr.parent_path());
  // lit's own metric is FLIP (below); --metric gives relative-to-value with
  // the first such row's thresholds (emissive's).
  const Cli cli = runCli({(folder / "lit.exr").string(), (folder / "changed.exr").string(), "--out", exr.string(),
                          "--metric", "relative-to-value"});
  INFO(cli.out, cli.err);
  CHECK(cli.exitCode == 1);  // one pixel of 256 over fail: within 0.5 %, so a warning
  CHECK(contains(cli.out, "wrote " + exr.string()));

  OIIO::ImageBuf diff(exr.string());
  REQUIRE(diff.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  CHECK(diff.spec().width == 16);
  CHECK(diff.spec().format == OIIO::TypeDesc::FLOAT);
  REQUIRE(diff.nchannels() == 4);
  CHECK(diff.spec().channelnames[3] == "error");
  const int red = diff.spec().channelindex("R"), error = diff.spec().channelindex("error");
  CHECK(diff.getchannel(3, 3, 0, red) == doctest::Approx(1.0));
  CHECK(diff.getchannel(3, 3, 0, error) ==
        doctest::Approx(1.0 / std::max(1.0, double(image.pixels[(3 * 16 + 3) * 3]))));
  CHECK(diff.getchannel(4, 3, 0, error) == 0);

  OIIO::ImageBuf png((folder / "report" / "diff.png").string());
  REQUIRE(png.read());
  CHECK(png.spec().format == OIIO::TypeDesc::UINT8);
  CHECK(png.nchannels() == 3);
  CHECK(png.spec().width == 16);
  // The changed pixel saturates the ramp (inferno's top is light); an
  // unchanged one is its dark bottom.
  CHECK(png.getchannel(3, 3, 0, 0) > 0.9f);
  CHECK(png.getchannel(4, 3, 0, 0) < 0.1f);
  // No temporary file left beside them.
  for (const auto& entry : fs::directory_iterator(exr.parent_path())) CHECK(entry.path().filename().string()[0] != '.');

  // Nothing to draw for a structural mismatch: the library says so, the CLI
  // reports the mismatch and writes nothing.
  write(folder / "small.exr", gradient(4, 4, {"R", "G", "B"}));
  const DiffResult mismatch = diffImages(folder / "lit.exr", folder / "small.exr");
  CHECK_THROWS_AS(writeDiffImages(mismatch, folder / "x.exr"), Error);
  CHECK(runCli({(folder / "lit.exr").string(), (folder / "small.exr").string(), "--out", (folder / "y.exr").string()})
            .exitCode == 3);
  CHECK(!fs::exists(folder / "y.exr"));
  // An unwritable destination is a file error (4) naming it.
  const Cli unwritable = runCli({(folder / "lit.exr").string(), (folder / "changed.exr").string(), "--out",
                                 (folder / "no" / "such" / "dir" / "d.exr").string()});
  CHECK(unwritable.exitCode == 4);
  CHECK(contains(unwritable.err, "d.exr"));
  fs::remove_all(folder);
}

TEST_CASE("diff: default thresholds by target, overridden by options" * doctest::test_suite("diff")) {
  CHECK(targetTolerance("normal").metric == DiffMetric::AngleDegrees);
  CHECK(targetTolerance("position").metric == DiffMetric::RelativeToScene);
  CHECK(targetTolerance("depth").metric == DiffMetric::RelativeToScene);
  CHECK(targetTolerance("lit").metric == DiffMetric::Flip);
  CHECK(targetTolerance("preview").metric == DiffMetric::Flip);
  CHECK(targetTolerance("emissive").metric == DiffMetric::RelativeToValue);
  CHECK(targetTolerance("albedo").metric == DiffMetric::Absolute);
  CHECK(targetTolerance("normal").thresholds.fail == 1.0);
  CHECK(targetTolerance("ssgi").thresholds.failPercent == 1.0);
  // Every target has a row with a reason, warn <= fail, and a finite mean
  // bound no looser than what its failPercent allowance could add at full scale.
  for (const FrameTarget& target : frameTargets()) {
    CAPTURE(target.name);
    const FrameTarget& row = targetTolerance(target.name);
    CHECK(row.name == target.name);
    CHECK(!row.reason.empty());
    CHECK(row.thresholds.warn <= row.thresholds.fail);
    CHECK(std::isfinite(row.thresholds.failMean));
  }
  // Anything else gets idiff's defaults.
  const DiffThresholds other = targetTolerance("golden_beauty").thresholds;
  CHECK(other.fail == 1e-6);
  CHECK(other.failPercent == 0);
  CHECK(std::isinf(other.hardFail));
  CHECK(std::isinf(other.failMean));
  CHECK(targetTolerance("golden_beauty").name.empty());

  DiffOptions options;
  options.fail = 0.5;
  options.hardWarn = 2;
  const DiffThresholds resolved = resolveThresholds("lit", options);
  CHECK(resolved.fail == 0.5);
  CHECK(resolved.hardWarn == 2);
  CHECK(resolved.warn == targetTolerance("lit").thresholds.warn);
}

TEST_CASE("diff: the command's usage errors are exit 5, --help is 0 and lists the exit codes" *
          doctest::test_suite("diff")) {
  Cli cli = runCli({});
  CHECK(cli.exitCode == 5);
  CHECK(contains(cli.err, "expected two images"));
  cli = runCli({"a.exr", "b.exr", "--fail"});
  CHECK(cli.exitCode == 5);
  CHECK(contains(cli.err, "--fail needs a value"));
  cli = runCli({"a.exr", "b.exr", "--failpercent", "150"});
  CHECK(cli.exitCode == 5);
  CHECK(contains(cli.err, "--failpercent"));
  CHECK(runCli({"a.exr", "b.exr", "--warn", "-1"}).exitCode == 5);
  CHECK(runCli({"a.exr", "b.exr", "--warn", "nan"}).exitCode == 5);
  CHECK(runCli({"a.exr", "b.exr", "--bogus"}).exitCode == 5);
  CHECK(runCli({"a.exr", "b.exr", "--json=yes"}).exitCode == 5);
  CHECK(runCli({"a.exr", "b.exr", "--channels", "R,,G"}).exitCode == 5);
  CHECK(runCli({"a.exr", "b.exr", "--out", "diff.tif"}).exitCode == 5);
  CHECK(runCli({"a.exr", "b.exr", "c.exr"}).exitCode == 5);
  cli = runCli({"a.exr", "b.exr", "--target", "normals"});
  CHECK(cli.exitCode == 5);
  CHECK(contains(cli.err, "expected one of position, normal,"));
  cli = runCli({"--help"});
  CHECK(cli.exitCode == 0);
  CHECK(contains(cli.out, "usage: headlight diff"));
  CHECK(contains(cli.out, "3 structural mismatch"));
  CHECK(contains(cli.out, "5 usage error"));
  CHECK(contains(cli.out, "angle-degrees"));
  CHECK(contains(cli.out, "preview"));
  cli = runCli({"a.exr", "b.exr", "--metric", "psnr"});
  CHECK(cli.exitCode == 5);
  CHECK(contains(cli.err, "flip"));  // the choices are listed
  // Missing files are a file error, not a usage error.
  CHECK(runCli({"/nonexistent/a.exr", "/nonexistent/b.exr"}).exitCode == 4);
}

TEST_CASE("diff: lit is judged by HDR-FLIP, preview.png by LDR-FLIP, and --metric picks another measure" *
          doctest::test_suite("diff")) {
  const fs::path folder = test::freshFolder("diff_flip");
  fs::create_directories(folder / "b");
  // HDR radiance up to ~3, fully covered.
  TestImage lit = gradient(32, 32, {"R", "G", "B", "A"});
  for (std::size_t i = 0; i < lit.pixels.size(); ++i) lit.pixels[i] = i % 4 == 3 ? 1.0f : 3.0f * lit.pixels[i];
  write(folder / "lit.exr", lit);
  write(folder / "b" / "lit.exr", lit);
  DiffResult result = diffImages(folder / "lit.exr", folder / "b" / "lit.exr");
  CHECK(result.metric == DiffMetric::Flip);
  CHECK(result.status == DiffStatus::Pass);
  REQUIRE(result.channels.size() == 2);  // flip of R, G, B; coverage A on its own
  CHECK(result.channels[0].name == "flip");
  CHECK(result.channels[0].sources == std::vector<std::string>{"R", "G", "B"});
  CHECK(result.channels[1].name == "A");
  CHECK(result.maxError == 0);
  REQUIRE(result.flip);
  CHECK(result.flip->hdr);
  CHECK(result.flip->exposureCount >= 2);

  // A 6x6 block twice as bright: 3.5 % of the pixels, clearly visible: FAIL,
  // with the library's HDR-FLIP mean (A is the reference).
  TestImage brighter = lit;
  for (int y = 10; y < 16; ++y)
    for (int x = 10; x < 16; ++x)
      for (int c = 0; c < 3; ++c) brighter.at(x, y, c) *= 2.0f;
  write(folder / "b" / "lit.exr", brighter);
  result = diffImages(folder / "lit.exr", folder / "b" / "lit.exr");
  CHECK(result.status == DiffStatus::Fail);
  CHECK(result.maxChannel == "flip");
  const flip::FlipResult direct = flip::hdrFlip({lit.pixels.data(), 32, 32, 4}, {brighter.pixels.data(), 32, 32, 4});
  CHECK(result.channels[0].meanError == doctest::Approx(direct.mean).epsilon(1e-5));
  CHECK(result.channels[0].maxError == doctest::Approx(direct.maximum).epsilon(1e-5));
  CHECK(result.maxX >= 8);
  CHECK(result.maxX <= 17);
  CHECK(result.channels[1].maxError == 0);

  // --out: the FLIP map itself in diff.exr's error channel, magma in the PNG
  // (0 is magma's black bottom, whatever the fail threshold).
  const fs::path exr = folder / "flip_diff.exr";
  const Cli written =
      runCli({(folder / "lit.exr").string(), (folder / "b" / "lit.exr").string(), "--out", exr.string(), "--json"});
  CHECK(written.exitCode == 2);
  const nlohmann::json j = nlohmann::json::parse(written.out);
  CHECK(j["metric"] == "flip");
  CHECK(j["flip"]["variant"] == "hdr");
  CHECK(j["flip"]["pixels_per_degree"].get<double>() == doctest::Approx(67.02).epsilon(1e-3));
  CHECK(j["flip"]["exposures"].get<int>() == direct.exposureCount);
  OIIO::ImageBuf diff(exr.string());
  REQUIRE(diff.read(0, 0, true, OIIO::TypeDesc::FLOAT));
  const int error = diff.spec().channelindex("error");
  CHECK(diff.getchannel(result.maxX, result.maxY, 0, error) == doctest::Approx(direct.maximum).epsilon(1e-5));
  OIIO::ImageBuf png((folder / "flip_diff.png").string());
  REQUIRE(png.read());
  CHECK(png.getchannel(31, 31, 0, 0) < 0.02f);  // FLIP 0 there: magma's near-black
  CHECK(png.getchannel(31, 31, 0, 2) < 0.05f);
  // Beside the map: A and B as FLIP saw them (tone mapped, 8-bit), and the
  // HTML report showing the three with the numbers.
  for (const char* name : {"flip_diff_a.png", "flip_diff_b.png"}) {
    OIIO::ImageBuf view((folder / name).string());
    REQUIRE(view.read());
    CHECK(view.spec().width == 32);
    CHECK(view.nchannels() == 3);
  }
  OIIO::ImageBuf viewA((folder / "flip_diff_a.png").string()), viewB((folder / "flip_diff_b.png").string());
  REQUIRE(viewA.read());
  REQUIRE(viewB.read());
  CHECK(viewB.getchannel(12, 12, 0, 0) > viewA.getchannel(12, 12, 0, 0));  // the brighter block
  CHECK(viewB.getchannel(30, 30, 0, 0) == viewA.getchannel(30, 30, 0, 0));
  std::ifstream html(folder / "flip_diff.html");
  const std::string page((std::istreambuf_iterator<char>(html)), std::istreambuf_iterator<char>());
  for (const char* part : {"flip_diff_a.png", "flip_diff_b.png", "flip_diff.png", "HDR-FLIP", "FAIL"})
    CHECK_MESSAGE(contains(page, part), part);

  // Coverage is compared absolutely beside the FLIP.
  TestImage uncovered = lit;
  for (int x = 0; x < 32; ++x) uncovered.at(x, 0, 3) = 0;  // 3 % of the pixels
  write(folder / "b" / "lit.exr", uncovered);
  result = diffImages(folder / "lit.exr", folder / "b" / "lit.exr");
  CHECK(result.status == DiffStatus::Fail);
  CHECK(result.maxChannel == "A");

  // Without R, G, B (--channels) FLIP cannot apply: absolute per channel.
  DiffOptions someChannels;
  someChannels.channels = {"R", "A"};
  CHECK(diffImages(folder / "lit.exr", folder / "b" / "lit.exr", someChannels).metric == DiffMetric::Absolute);

  // --metric flip on a file that is no target: lit's thresholds; and the
  // other way, lit judged by relative-to-value gets emissive's.
  write(folder / "golden.exr", lit);
  write(folder / "b" / "golden.exr", brighter);
  DiffOptions asFlip;
  asFlip.metric = DiffMetric::Flip;
  result = diffImages(folder / "golden.exr", folder / "b" / "golden.exr", asFlip);
  CHECK(result.metric == DiffMetric::Flip);
  CHECK(result.thresholds.fail == targetTolerance("lit").thresholds.fail);
  CHECK(result.thresholds.failMean == targetTolerance("lit").thresholds.failMean);
  DiffOptions asRelative;
  asRelative.metric = DiffMetric::RelativeToValue;
  CHECK(resolveThresholds("lit", asRelative).fail == targetTolerance("emissive").thresholds.fail);

  // preview.png: 8-bit sRGB, LDR-FLIP of the decoded values.
  auto writePng = [](const fs::path& path, const TestImage& image) {
    OIIO::ImageSpec spec(image.width, image.height, int(image.channels.size()), OIIO::TypeDesc::UINT8);
    auto output = OIIO::ImageOutput::create(path.string());
    REQUIRE(output);
    REQUIRE(output->open(path.string(), spec));
    REQUIRE(output->write_image(OIIO::TypeDesc::FLOAT, image.pixels.data()));
    REQUIRE(output->close());
  };
  TestImage preview = gradient(32, 32, {"R", "G", "B"});
  TestImage tinted = preview;
  for (int y = 0; y < 32; ++y)
    for (int x = 20; x < 32; ++x) tinted.at(x, y, 2) = 0.1f;  // 37 % of the picture loses its blue
  writePng(folder / "preview.png", preview);
  writePng(folder / "b" / "preview.png", tinted);
  result = diffImages(folder / "preview.png", folder / "b" / "preview.png");
  CHECK(result.metric == DiffMetric::Flip);
  REQUIRE(result.flip);
  CHECK_FALSE(result.flip->hdr);
  CHECK(result.status == DiffStatus::Fail);
  // The same as LDR-FLIP of the decoded 8-bit values.
  std::vector<float> decodedA, decodedB;
  for (std::size_t i = 0; i < preview.pixels.size(); ++i) {
    decodedA.push_back(srgbToLinear(std::round(preview.pixels[i] * 255.0f) / 255.0f));
    decodedB.push_back(srgbToLinear(std::round(tinted.pixels[i] * 255.0f) / 255.0f));
  }
  const double ldrMean = flip::ldrFlip({decodedA.data(), 32, 32, 3}, {decodedB.data(), 32, 32, 3}).mean;
  CHECK(result.channels[0].meanError == doctest::Approx(ldrMean).epsilon(1e-4));
  writePng(folder / "b" / "preview.png", preview);
  CHECK(diffImages(folder / "preview.png", folder / "b" / "preview.png").status == DiffStatus::Pass);
  fs::remove_all(folder);
}

// headlight diff's verdicts: the library (headlight/diff.hpp) and the CLI
// command (runDiffCommand, called directly) on small EXRs written here with
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
#include "diff_test_images.hpp"
#include "headlight/diff.hpp"
#include "headlight/error.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
namespace fs = std::filesystem;
using namespace headlight::test;

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

TEST_CASE("diff: HDR-FLIP's exposures are counted before the first, and a pair needing more than allowed is refused" *
          doctest::test_suite("diff")) {
  // Issue 32: a denormal median under one pixel at 1e38 asked for ~260 whole FLIPs (~95 s at its size).
  const fs::path folder = test::freshFolder("diff_flip_exposures");
  TestImage extreme = gradient(16, 16, {"R", "G", "B"});
  for (float& value : extreme.pixels) value = 1e-40f;  // a denormal: the median
  extreme.at(3, 4, 0) = extreme.at(3, 4, 1) = extreme.at(3, 4, 2) = 1e38f;
  write(folder / "lit.exr", extreme);
  const DiffResult refused = diffImages(folder / "lit.exr", folder / "lit.exr");
  CHECK(refused.status == DiffStatus::FileError);
  CHECK(contains(refused.problem, "more than --max-flip-exposures 64 allows"));
  CHECK(contains(refused.problem, "HDR-FLIP would evaluate 2"));  // 259 or so
  const Cli cli = runCli({(folder / "lit.exr").string(), (folder / "lit.exr").string()});
  CHECK(cli.exitCode == 4);
  CHECK(contains(cli.out, "--max-flip-exposures"));
  // An ordinary HDR image is far inside the bound; raised, the extreme pair is compared.
  write(folder / "ordinary.exr", gradient(16, 16, {"R", "G", "B"}));
  const DiffResult ordinary = diffImages(folder / "ordinary.exr", folder / "ordinary.exr", [] {
    DiffOptions options;
    options.metric = DiffMetric::Flip;
    return options;
  }());
  CHECK(ordinary.status == DiffStatus::Pass);
  REQUIRE(ordinary.flip.has_value());
  CHECK(ordinary.flip->exposureCount <= 8);
  DiffOptions raised;
  raised.maxFlipExposures = 1000;
  CHECK(diffImages(folder / "lit.exr", folder / "lit.exr", raised).status == DiffStatus::Pass);
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

// The bench's own correctness: its metrics, its Pareto front and its files.
// (Its speed is measured by `headlight bench`, never asserted.)
#include <doctest/doctest.h>

#include <cmath>
#include <limits>

#include <filesystem>
#include <fstream>
#include <random>

#include <nlohmann/json.hpp>

#include "diff/flip.hpp"
#include "headlight/error.hpp"
#include "support/images.hpp"
#include "support/temp_folder.hpp"
#include "tooling/bench.hpp"

using namespace headlight;

using test::makeImage;

TEST_CASE("maskedError counts only geometry pixels" * doctest::test_suite("bench")) {
  ImageF mask = makeImage(4, 1, {"position.X", "position.Y", "position.Z", "A"}, 0.0f);
  ImageF a = makeImage(4, 1, {"ao.Y"}, 0.0f), b = makeImage(4, 1, {"ao.Y"}, 0.0f);
  a.pixels = {1.0f, 0.5f, 0.0f, 100.0f};
  b.pixels = {0.0f, 0.5f, 0.0f, 0.0f};
  for (int x : {0, 1, 2}) mask.pixels[std::size_t(x) * 4 + 3] = 1.0f;  // pixel 3 is background
  const ErrorStats stats = maskedError(a, 0, b, 0, mask);
  CHECK(stats.pixels == 3);
  CHECK(stats.rmse == doctest::Approx(std::sqrt(1.0 / 3.0)));
  CHECK(stats.meanAbsolute == doctest::Approx(1.0 / 3.0));
  CHECK(stats.referenceMean == doctest::Approx(0.5 / 3.0));
}

TEST_CASE("maskedSsim is 1 for identical images and lower for noise" * doctest::test_suite("bench")) {
  ImageF mask = makeImage(32, 32, {"position.X", "position.Y", "position.Z", "A"}, 1.0f);
  ImageF a = makeImage(32, 32, {"R", "G", "B", "A"}, 0.0f);
  std::mt19937 rng(3);
  for (float& v : a.pixels) v = float(rng() % 1000) / 500.0f;
  CHECK(maskedSsim(a, a, mask) == doctest::Approx(1.0));
  ImageF b = a;
  for (float& v : b.pixels) v += float(rng() % 1000) / 1000.0f;
  CHECK(maskedSsim(a, b, mask) < 0.95);
}

TEST_CASE("hdrFlipMean is HDR-FLIP's mean with the reference's exposures, over every pixel" *
          doctest::test_suite("bench")) {
  ImageF reference = makeImage(40, 32, {"R", "G", "B", "A"}, 1.0f), lit = reference;
  std::mt19937 rng(5);
  for (std::size_t i = 0; i < reference.pixels.size(); ++i)
    if (i % 4 != 3) reference.pixels[i] = float(rng() % 1000) / 250.0f;  // radiance 0..4
  CHECK(hdrFlipMean(reference, reference) == 0.0);
  lit = reference;
  for (std::size_t i = 0; i < lit.pixels.size(); i += 4) lit.pixels[i] *= 1.5f;  // redder
  const double mean = hdrFlipMean(lit, reference);
  CHECK(mean > 0.01);
  CHECK(mean < 1.0);
  // The second argument is FLIP's reference (its exposures), the first the test.
  CHECK(mean ==
        doctest::Approx(flip::hdrFlip({reference.pixels.data(), 40, 32, 4}, {lit.pixels.data(), 40, 32, 4}).mean));
  ImageF small = makeImage(8, 8, {"R", "G", "B"}, 0.5f);
  CHECK_THROWS_WITH_AS(hdrFlipMean(small, reference), doctest::Contains("8x8"), Error);
}

TEST_CASE("paretoFront keeps exactly the non-dominated points" * doctest::test_suite("bench")) {
  const std::vector<std::pair<double, double>> points{{1, 5}, {2, 3}, {3, 3}, {4, 1}, {2, 4}, {5, 5}, {1, 5}};
  const std::vector<bool> front = paretoFront(points);
  CHECK(front == std::vector<bool>{true, true, false, true, false, false, true});
  // The definition, checked directly on random sets: no front point is
  // dominated, and every other point is.
  std::mt19937 rng(11);
  for (int trial = 0; trial < 20; ++trial) {
    std::vector<std::pair<double, double>> random(30);
    for (auto& p : random) p = {double(rng() % 50), double(rng() % 50)};
    const auto onFront = paretoFront(random);
    for (std::size_t i = 0; i < random.size(); ++i) {
      bool dominated = false;
      for (std::size_t j = 0; j < random.size(); ++j)
        dominated |= random[j].first <= random[i].first && random[j].second <= random[i].second &&
                     (random[j].first < random[i].first || random[j].second < random[i].second);
      CHECK(onFront[i] == !dominated);
    }
  }
}

TEST_CASE("summarize gives median and spread" * doctest::test_suite("bench")) {
  const Summary odd = summarize({5, 1, 3});
  CHECK(odd.median == 3);
  CHECK(odd.minimum == 1);
  CHECK(odd.maximum == 5);
  CHECK(summarize({4, 1, 3, 2}).median == 2.5);
  // An unknown GPU time (nan) is left out, not sorted among the numbers; none known: nan.
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Summary partly = summarize({nan, 4, 2});
  CHECK(partly.median == 3);
  CHECK(partly.minimum == 2);
  CHECK(std::isnan(summarize({nan, nan}).median));
}

TEST_CASE("bench.csv and bench.json hold every row with its time and error" * doctest::test_suite("bench")) {
  std::vector<BenchRow> rows(2);
  rows[0].scene = "builtin:cornell";
  rows[0].label = "ssgi-method=hemisphere";
  rows[0].settings = {{"ssgi-method", "hemisphere"}, {"ssgi-samples", "64"}};
  rows[0].frameMs = {12.5, 12, 13};
  rows[0].ao.rmse = 0.1;
  rows[0].sky.rmse = 0.375;
  rows[0].litFlip = 0.125;
  rows[1].scene = "a, \"quoted\" scene";
  rows[1].label = "ssgi-method=radiance";
  rows[1].settings = {{"ssgi-method", "radiance"}};
  rows[1].frameMs = {7.25, 7, 8};
  rows[1].ao.rmse = 0.2;
  const auto folder = test::freshFolder("bench");
  writeBenchCsv(rows, folder / "bench.csv");
  writeBenchJson(rows, "headlight bench test", folder / "bench.json");
  std::ifstream csv(folder / "bench.csv");
  std::string header, line;
  std::getline(csv, header);
  CHECK(header.find("frame_ms_median") != std::string::npos);
  CHECK(header.find("ao_rmse") != std::string::npos);
  CHECK(header.find(",sky_rmse,sky_mae,") != std::string::npos);
  CHECK(header.find(",lit_ssim,lit_flip,") != std::string::npos);
  // One column per setting row, so a new setting reaches the CSV by itself.
  for (const Option<RenderSettings>& option : settingOptions())
    CHECK(header.find("," + std::string(option.spec.name) + ",") != std::string::npos);
  int lines = 0;
  while (std::getline(csv, line)) ++lines;
  CHECK(lines == 2);
  std::ifstream jsonFile(folder / "bench.json");
  const auto json = nlohmann::json::parse(jsonFile);
  REQUIRE(json["rows"].size() == 2);
  CHECK(json["rows"][1]["scene"] == "a, \"quoted\" scene");
  CHECK(json["rows"][1]["frame_ms"]["median"] == 7.25);
  CHECK(json["rows"][0]["ao"]["rmse"] == 0.1);
  CHECK(json["rows"][0]["sky"]["rmse"] == 0.375);
  CHECK(json["rows"][0]["lit"]["flip"] == 0.125);
  CHECK(json["rows"][0]["settings"]["ssgi-samples"] == "64");
  CHECK(json["rows"][1]["label"] == "ssgi-method=radiance");
  std::filesystem::remove_all(folder);
}

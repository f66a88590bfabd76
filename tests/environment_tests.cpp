// The environment map's CPU side (no GL): its loader's refusals, its
// prefiltered irradiance against closed forms on generated maps, and the
// reference's importance sampler.
#include <doctest/doctest.h>

#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <numbers>
#include <string>

#include "environment/environment_prefilter.hpp"
#include "environment/environment_sampler.hpp"
#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "support/environment_maps.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
using namespace headlight::test;

namespace {

// E / pi from one texel (x0, y0) of a 64 x 32 map of radiance `radiance`,
// exactly: the integral of n . w over the texel, every point of which must
// face the normal. Over phi0..phi1 and theta0..theta1, with w = (sin t sin p,
// cos t, -sin t cos p) and dw = sin t dt dp.
double texelIrradianceOverPi(const glm::dvec3& n, int x0, int y0, double radiance) {
  const double phi0 = 2.0 * std::numbers::pi * (x0 / 64.0 - 0.5),
               phi1 = 2.0 * std::numbers::pi * ((x0 + 1) / 64.0 - 0.5);
  const double theta0 = std::numbers::pi * y0 / 32.0, theta1 = std::numbers::pi * (y0 + 1) / 32.0;
  auto sinSquared = [](double t) { return t / 2.0 - std::sin(2.0 * t) / 4.0; };  // antiderivative of sin^2
  auto sinCos = [](double t) { return std::sin(t) * std::sin(t) / 2.0; };         // of sin cos
  const double a = sinSquared(theta1) - sinSquared(theta0), b = sinCos(theta1) - sinCos(theta0);
  const double integral = n.x * a * (std::cos(phi0) - std::cos(phi1)) + n.y * b * (phi1 - phi0) -
                          n.z * a * (std::sin(phi1) - std::sin(phi0));
  return radiance * integral / std::numbers::pi;
}

std::shared_ptr<const EnvironmentMap> generated(const TempFolder& folder, const std::string& name,
                                                glm::vec3 (*radiance)(int, int)) {
  return loadEnvironmentMap(writeEnvironmentMap(folder.path() / name, 64, 32, radiance));
}

const glm::vec3 kNormals[] = {{0, 1, 0},    {0, -1, 0},         {1, 0, 0},          {0, 0, -1},
                              {0.6f, 0.8f, 0}, {-0.48f, 0.6f, 0.64f}, {0.36f, -0.48f, 0.8f}};

// The texel's centre direction (the map's layout, scene.hpp).
glm::vec3 brightTexelDirection() {
  return environment::uvToDirection((kBrightTexelX + 0.5f) / 64.0f, (kBrightTexelY + 0.5f) / 32.0f);
}

}  // namespace

TEST_CASE("environment irradiance equals the closed form on a uniform map, within 1%") {
  const TempFolder folder("environment");
  const auto map = generated(folder, "uniform.exr", uniformRadiance);
  const auto tables = environment::prefilterEnvironment(*map);
  for (const glm::vec3& n : kNormals) {
    const glm::vec3 value = environment::irradianceOverPiAt(tables, glm::normalize(n));
    CAPTURE(n.x);
    CAPTURE(n.y);
    CAPTURE(n.z);
    CHECK(value.r == doctest::Approx(0.5).epsilon(0.01));
    CHECK(value.b == doctest::Approx(0.5).epsilon(0.01));
  }
  // Every roughness level of a uniform map is that radiance.
  for (const auto& level : tables.specular)
    CHECK(level.lookup(glm::normalize(glm::vec3(0.3f, 0.2f, -0.9f))).g == doctest::Approx(0.5).epsilon(0.01));
}

TEST_CASE("environment irradiance equals the closed form on a horizon split, within 1%") {
  // Radiance 1 above the horizon, 0 below: E / pi = (1 + n.y) / 2.
  const TempFolder folder("environment");
  const auto map = generated(folder, "split.exr", horizonSplitRadiance);
  const auto tables = environment::prefilterEnvironment(*map);
  for (const glm::vec3& n : kNormals) {
    const glm::vec3 normal = glm::normalize(n);
    const double expected = (1.0 + normal.y) / 2.0;
    CAPTURE(normal.x);
    CAPTURE(normal.y);
    CAPTURE(normal.z);
    // Relative 1% where the closed form is at least a quarter of its
    // maximum; below (normals facing the dark half) 1% of the maximum.
    const double value = environment::irradianceOverPiAt(tables, normal).g;
    if (expected >= 0.25)
      CHECK(value == doctest::Approx(expected).epsilon(0.01));
    else
      CHECK(std::abs(value - expected) <= 0.01);
  }
}

TEST_CASE("environment irradiance equals the closed form for a single bright texel, within 1%") {
  const TempFolder folder("environment");
  const auto map = generated(folder, "bright.exr", brightTexelRadiance);
  const auto tables = environment::prefilterEnvironment(*map);
  const glm::vec3 toTexel = brightTexelDirection();
  const glm::vec3 normals[] = {toTexel, glm::vec3(0, 1, 0), glm::normalize(toTexel + glm::vec3(0, 0, 0.8f)),
                               glm::normalize(toTexel + glm::vec3(-0.5f, 0.3f, 0.0f))};
  for (const glm::vec3& normal : normals) {
    // Normals that face the whole texel well (cos >= 0.3 at its centre),
    // where the bilinear table's error is a small share of the value.
    REQUIRE(glm::dot(normal, toTexel) >= 0.3f);
    const double expected = texelIrradianceOverPi(glm::dvec3(normal), kBrightTexelX, kBrightTexelY, 1000.0);
    CAPTURE(normal.x);
    CAPTURE(normal.y);
    CAPTURE(normal.z);
    CHECK(environment::irradianceOverPiAt(tables, normal).r == doctest::Approx(expected).epsilon(0.01));
  }
  // Facing away, nothing.
  CHECK(environment::irradianceOverPiAt(tables, -toTexel).r == doctest::Approx(0.0).epsilon(1e-6));
}

TEST_CASE("environment importance sampling: its density integrates to 1 and estimates a bright texel's irradiance") {
  const TempFolder folder("environment");
  const auto map = generated(folder, "bright.exr", brightTexelRadiance);
  const environment::EquirectImage image = environment::equirectOf(*map);
  const environment::EnvironmentSampler sampler(image);
  // The density over a 256 x 128 grid of the sphere, midpoint rule.
  double total = 0.0;
  for (int y = 0; y < 128; ++y)
    for (int x = 0; x < 256; ++x)
      total += sampler.pdf(environment::uvToDirection((x + 0.5f) / 256.0f, (y + 0.5f) / 128.0f)) *
               environment::texelSolidAngle(y, 256, 128);
  CHECK(total == doctest::Approx(1.0).epsilon(0.01));
  // E / pi at the texel's direction: mean of L cos / (pi pdf) over 4096
  // stratified samples (most land in the texel).
  const glm::vec3 normal = brightTexelDirection();
  double sum = 0.0;
  const int count = 64;
  for (int i = 0; i < count; ++i)
    for (int j = 0; j < count; ++j) {
      float pdf = 0.0f;
      const glm::vec3 d = sampler.sample((i + 0.5f) / count, (j + 0.5f) / count, pdf);
      const float cosine = glm::dot(normal, d);
      if (cosine > 0.0f) sum += image.lookup(d).r * cosine / (std::numbers::pi * pdf);
    }
  // The sampler reads the bilinear map, as the reference does: its integral
  // over the sphere equals the texel's to within the lookup's spread.
  const double expected = texelIrradianceOverPi(glm::dvec3(normal), kBrightTexelX, kBrightTexelY, 1000.0);
  CHECK(sum / (count * count) == doctest::Approx(expected).epsilon(0.03));
}

TEST_CASE("loadEnvironmentMap refuses bad files, naming the file and the value") {
  const TempFolder folder("environment");
  auto messageOf = [](const std::filesystem::path& path, const ResourceLimits& limits = {}) -> std::string {
    try {
      loadEnvironmentMap(path, limits);
    } catch (const Error& error) {
      return error.what();
    }
    return "(loaded)";
  };
  const auto wide = writeEnvironmentMap(folder.path() / "wide.exr", 96, 32, uniformRadiance);
  const std::string notEquirect = messageOf(wide);
  CHECK(notEquirect.find(wide.string()) != std::string::npos);
  CHECK(notEquirect.find("96x32") != std::string::npos);
  CHECK(notEquirect.find("2:1") != std::string::npos);

  const auto nan = writeEnvironmentMap(folder.path() / "nan.exr", 8, 4, [](int x, int y) {
    return x == 5 && y == 2 ? glm::vec3(0.0f, std::nanf(""), 0.0f) : glm::vec3(1.0f);
  });
  const std::string notFinite = messageOf(nan);
  CHECK(notFinite.find(nan.string()) != std::string::npos);
  CHECK(notFinite.find("texel (5, 2) G = nan") != std::string::npos);

  // The header's size is checked against max-memory before any pixel is
  // decoded: 2048 x 1024 texels at 36 bytes each is 72 MiB, over 64.
  const auto big = writeEnvironmentMap(folder.path() / "big.exr", 2048, 1024, uniformRadiance);
  ResourceLimits small;
  small.maxMemoryMiB = 64;
  CHECK_THROWS_AS(loadEnvironmentMap(big, small), LimitError);
  const std::string tooBig = messageOf(big, small);
  CHECK(tooBig.find(big.string()) != std::string::npos);
  CHECK(tooBig.find("2048x1024") != std::string::npos);
  CHECK(tooBig.find("max-memory") != std::string::npos);
  CHECK(loadEnvironmentMap(big)->width == 2048);  // within the default

  CHECK(messageOf(folder.path()).find("a folder") != std::string::npos);
  CHECK(messageOf(folder.path() / "missing.hdr").find("no such file") != std::string::npos);
}

TEST_CASE("a map whose header declares more than its data holds fails before the map's memory is taken (issue 32)") {
  const TempFolder folder("environment-truncated");
  // 16384 x 8192 declared in 52 bytes (1.7 GB as float): within the default
  // max-memory, so refused only when its pixels run out, at the first band.
  const auto huge = folder.write("huge.hdr", "#?RADIANCE\nFORMAT=32-bit_rle_rgbe\n\n-Y 8192 +X 16384\n");
  CHECK_THROWS_WITH_AS(loadEnvironmentMap(huge), doctest::Contains("truncated"), SceneError);
  // The CLI's whole peak (a child process: wait4's rusage), refusing it:
  // it reached 1.7 GB when the map was allocated whole before reading.
  const std::string out = (folder.path() / "out").string();
  const char* const argv[] = {HEADLIGHT_EXE, "render",    "builtin:cornell", "--environment", huge.c_str(),
                              "--out",       out.c_str(), "--quiet",         nullptr};
  pid_t child = -1;
  REQUIRE(posix_spawn(&child, HEADLIGHT_EXE, nullptr, nullptr, const_cast<char* const*>(argv), environ) == 0);
  int status = 0;
  rusage usage{};
  REQUIRE(wait4(child, &status, 0, &usage) == child);
  REQUIRE(WIFEXITED(status));
  CHECK(WEXITSTATUS(status) == 1);
  CHECK_MESSAGE(usage.ru_maxrss < 1024 * 1024, "peak resident memory " << usage.ru_maxrss << " kB");
  const auto small = writeEnvironmentMap(folder.path() / "small.exr", 8, 4, uniformRadiance);
  CHECK(loadEnvironmentMap(small)->height == 4);  // and a whole map still loads
}

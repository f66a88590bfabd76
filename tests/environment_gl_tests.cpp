// Environment maps through the renderer (gl suite): a white diffuse sphere
// under a uniform map reflects exactly the map's radiance (any split of the
// split sum's diffuse and specular parts sums to it for albedo 1); the
// background shows the map; the rotation turns where a bright texel lights;
// the tables are made once per map.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"
#include "job_file.hpp"
#include "support/environment_maps.hpp"
#include "support/gl.hpp"
#include "support/temp_folder.hpp"

using namespace headlight;
using namespace headlight::test;

namespace {

// A white diffuse sphere, seen from +Z by the fitted camera, with one light
// of intensity 0 (no default key light): only the ambient term lights it.
Scene whiteSphere(std::shared_ptr<const EnvironmentMap> environment) {
  Scene scene;
  scene.source = "test:environment-sphere";
  addInstance(scene, makeUvSphere(1.0f, 96, 48), addMaterial(scene, makeMaterial(glm::vec3(1.0f), 1.0f, 0.0f)));
  scene.lights.push_back(darkLight());
  scene.environment = std::move(environment);
  return scene;
}

// SSGI off: the ambient term is then unoccluded (sky visibility 1).
RenderSettings ambientOnly(float intensity = 1.0f) {
  RenderSettings settings = smallSettings(64, 64);
  settings.ssgi.enabled = false;
  settings.lighting.environmentIntensity = intensity;
  return settings;
}

}  // namespace

TEST_CASE("environment: a white diffuse sphere under a uniform map is lit by the map's radiance within 1%, and the "
          "background shows it") {
  const TempFolder folder("environment-gl");
  const auto map = loadEnvironmentMap(writeEnvironmentMap(folder.path() / "uniform.exr", 64, 32, uniformRadiance));
  Renderer renderer(sharedContext());
  renderer.setScene(whiteSphere(map));
  const float intensity = 2.0f;  // L = 0.5 x 2
  const Frame frame = renderer.render(ambientOnly(intensity));
  int geometry = 0, background = 0;
  double worstGeometry = 0.0, worstBackground = 0.0;
  for (int y = 0; y < frame.lit.height; ++y)
    for (int x = 0; x < frame.lit.width; ++x) {
      const bool covered = frame.position.at(x, y, 3) != 0.0f;
      for (int c = 0; c < 3; ++c) {
        const double error = std::abs(frame.lit.at(x, y, c) - 1.0);
        (covered ? worstGeometry : worstBackground) = std::max(covered ? worstGeometry : worstBackground, error);
      }
      if (covered) ++geometry;
      else {
        ++background;
        CHECK(frame.lit.at(x, y, 3) == 0.0f);  // the background is never covered
      }
    }
  REQUIRE(geometry > 500);
  REQUIRE(background > 500);
  CHECK(worstGeometry <= 0.01);
  CHECK(worstBackground <= 0.002);  // the map itself (half float: 1 ulp at 1 is 0.001)

  SUBCASE("environment-background off: black behind the sphere, the sphere unchanged") {
    RenderSettings settings = ambientOnly(intensity);
    settings.lighting.environmentBackground = false;
    const Frame dark = renderer.render(settings);
    for (int y = 0; y < dark.lit.height; ++y)
      for (int x = 0; x < dark.lit.width; ++x)
        if (dark.position.at(x, y, 3) == 0.0f)
          CHECK(dark.lit.at(x, y, 0) == 0.0f);
        else
          CHECK(dark.lit.at(x, y, 0) == frame.lit.at(x, y, 0));
  }
}

TEST_CASE("environment: the rotation turns the side a bright texel lights") {
  // A bright 2 x 2 block centred on the horizon toward +X (u = 0.75): the sphere's
  // right side (+X, seen from +Z) is lit, its left side is not. Turned by
  // 180 degrees about +Y it lies toward -X; by 90, toward -Z (behind).
  const TempFolder folder("environment-gl");
  const auto map = loadEnvironmentMap(writeEnvironmentMap(folder.path() / "bright.exr", 64, 32, [](int x, int y) {
    return (x == 47 || x == 48) && (y == 15 || y == 16) ? glm::vec3(500.0f) : glm::vec3(0.0f);
  }));
  Renderer renderer(sharedContext());
  renderer.setScene(whiteSphere(map));
  auto sides = [&](float degrees) {
    RenderSettings settings = ambientOnly();
    settings.lighting.environmentRotation = degrees;
    const Frame frame = renderer.render(settings);
    int count = 0;
    const double right = meanWhere(frame, frame.lit, 0, [](glm::vec3, glm::vec3 n) { return n.x > 0.5f; }, count);
    const double left = meanWhere(frame, frame.lit, 0, [](glm::vec3, glm::vec3 n) { return n.x < -0.5f; }, count);
    return std::pair{right, left};
  };
  const auto [right0, left0] = sides(0.0f);
  const auto [right180, left180] = sides(180.0f);
  const auto [right90, left90] = sides(90.0f);
  CHECK(right0 > 0.1);
  CHECK(left0 < 0.01 * right0);
  CHECK(left180 == doctest::Approx(right0).epsilon(0.05));  // mirrored
  CHECK(right180 < 0.01 * left180);
  CHECK(right90 == doctest::Approx(left90).epsilon(0.05));  // symmetric: the light is behind
}

TEST_CASE("environment: the tables are made once per map, and only with a map") {
  const TempFolder folder("environment-gl");
  const auto map = loadEnvironmentMap(writeEnvironmentMap(folder.path() / "split.exr", 64, 32, horizonSplitRadiance));
  Renderer renderer(sharedContext());
  renderer.setScene(whiteSphere(map));
  const Frame first = renderer.render(ambientOnly());
  CHECK(timed(first, "environment"));
  CHECK(!timed(first, "sky"));
  CHECK(!timed(renderer.render(ambientOnly()), "environment"));
  // A new scene with the same map (a batch) keeps its tables.
  renderer.setScene(whiteSphere(map));
  CHECK(!timed(renderer.render(ambientOnly()), "environment"));
  // Horizon split, white sphere: its top reflects about 1, its bottom about 0.
  int count = 0;
  CHECK(meanWhere(first, first.lit, 1, [](glm::vec3, glm::vec3 n) { return n.y > 0.95f; }, count) ==
        doctest::Approx(1.0).epsilon(0.02));
  CHECK(meanWhere(first, first.lit, 1, [](glm::vec3, glm::vec3 n) { return n.y < -0.95f; }, count) < 0.02);
  // Intensity 0: no tables, no ambient term.
  renderer.setScene(whiteSphere(map));
  const Frame off = renderer.render(ambientOnly(0.0f));
  CHECK(std::any_of(off.skipped.begin(), off.skipped.end(), [](const SkippedWork& s) {
    return s.reason.find("environment intensity 0") != std::string::npos;
  }));
  // Without a map: the sky, as before.
  renderer.setScene(whiteSphere(nullptr));
  const Frame sky = renderer.render(ambientOnly());
  CHECK(timed(sky, "sky"));
  CHECK(!timed(sky, "environment"));
}

TEST_CASE("environment: SSGI's sky visibility occludes the map's light") {
  // A white floor under a uniform map with a box standing on it: with SSGI
  // on, the floor right beside the box sees less of the map than the floor
  // far from it; with SSGI off, both reflect the map's radiance.
  const TempFolder folder("environment-gl");
  Scene scene;
  scene.source = "test:environment-occlusion";
  const int white = addMaterial(scene, makeMaterial(glm::vec3(1.0f), 1.0f, 0.0f));
  addInstance(scene, makeFloor(4.0f), white);
  addInstance(scene, makeBox(glm::vec3(1.0f, 2.0f, 1.0f)), white, glm::translate(glm::mat4(1.0f), {0.0f, 1.0f, 0.0f}));
  scene.lights.push_back(darkLight());
  scene.cameras.push_back(makeLookAtCamera({0.0f, 4.0f, 5.0f}, {0.0f, 0.0f, 0.0f}, 0.9f));
  scene.environment =
      loadEnvironmentMap(writeEnvironmentMap(folder.path() / "uniform.exr", 64, 32, uniformRadiance));
  Renderer renderer(sharedContext());
  renderer.setScene(std::move(scene));
  auto floorMean = [](const Frame& frame, float nearest, float farthest) {
    int count = 0;
    const double mean = meanWhere(frame, frame.lit, 1, [&](glm::vec3 p, glm::vec3 n) {
      const float distance = std::max(std::abs(p.x), std::abs(p.z));
      return n.y > 0.9f && p.y < 0.01f && distance > nearest && distance < farthest;
    }, count);
    REQUIRE(count > 20);
    return mean;
  };
  RenderSettings settings = smallSettings(96, 96);
  settings.ssgi.enabled = false;
  const Frame open = renderer.render(settings);
  CHECK(floorMean(open, 0.52f, 0.7f) == doctest::Approx(0.5).epsilon(0.01));
  settings.ssgi.enabled = true;
  const Frame occluded = renderer.render(settings);
  const double beside = floorMean(occluded, 0.52f, 0.7f), far = floorMean(occluded, 2.5f, 3.5f);
  CHECK(beside < 0.85 * far);
  CHECK(far > 0.45);
}

TEST_CASE("environment: a batch job's hash covers the environment map's bytes, and no map adds nothing") {
  // --resume skips a set whose job hash matches: a set rendered with another
  // map (or none) must not match.
  const TempFolder folder("environment-gl");
  cli::Job job;
  job.scene = "builtin:cornell";
  job.outDir = "x";
  const std::string none = cli::jobHash(job, {});
  CHECK(cli::jobHash(job, {}, {}) == none);
  const auto a = writeEnvironmentMap(folder.path() / "a.exr", 8, 4, uniformRadiance);
  const auto b = writeEnvironmentMap(folder.path() / "b.exr", 8, 4, horizonSplitRadiance);
  const std::string withA = cli::jobHash(job, {}, a.string());
  CHECK(withA != none);
  CHECK(cli::jobHash(job, {}, b.string()) != withA);
  CHECK(cli::jobHash(job, {}, a.string()) == withA);
}

// Tests that need no GL context: the SSGI kernel and noise, camera fitting,
// the shared std140 layouts, settings and option parsing, tone curves.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "cli_options.hpp"
#include "headlight/camera.hpp"
#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "output/tonemap.hpp"
#include "passes/ssgi.hpp"
#include "shared_layout.h"

using namespace headlight;

TEST_CASE("SSGI kernel: 64 samples in the upper unit hemisphere, deterministic, denser near the centre") {
  const auto kernel = makeSsgiKernel(64, 1);
  REQUIRE(kernel.size() == 64);
  int inner = 0;
  for (const glm::vec3& k : kernel) {
    CHECK(k.z >= 0.0f);
    CHECK(glm::length(k) <= 1.0f);
    if (glm::length(k) < 0.5f) ++inner;
  }
  // Lengths are uniform times lerp(0.1, 1, t^2): a uniform ball would put
  // 1/8 of its volume inside radius 0.5; this kernel puts most samples there.
  CHECK(inner > 40);
  // The scale grows with the index: the first quarter is shorter than the last.
  auto meanLength = [&](int begin, int end) {
    float sum = 0;
    for (int i = begin; i < end; ++i) sum += glm::length(kernel[std::size_t(i)]);
    return sum / float(end - begin);
  };
  CHECK(meanLength(0, 16) < 0.5f * meanLength(48, 64));
  CHECK(makeSsgiKernel(64, 1) == kernel);
  CHECK(makeSsgiKernel(64, 2) != kernel);
  // Cosine weighting: mean cos(theta) of the directions is 2/3 (uniform: 1/2).
  float meanCos = 0;
  for (const glm::vec3& k : makeSsgiKernel(4096, 7)) meanCos += k.z / std::max(glm::length(k), 1e-12f);
  CHECK(meanCos / 4096.0f == doctest::Approx(2.0 / 3.0).epsilon(0.03));
}

TEST_CASE("SSGI noise: 16 unit vectors in the xy plane, deterministic") {
  const auto noise = makeSsgiNoise(1);
  for (const glm::vec2& v : noise) CHECK(glm::length(v) == doctest::Approx(1.0f).epsilon(1e-6));
  CHECK(makeSsgiNoise(1) == noise);
  // Not all the same direction: the rotations must actually vary.
  float spread = 0;
  for (const glm::vec2& v : noise) spread = std::max(spread, glm::length(v - noise[0]));
  CHECK(spread > 1.0f);
}

TEST_CASE("fitted camera frames the bounds and its depth range hugs them") {
  for (float scale : {0.008f, 1.0f, 2000.0f}) {
    CAPTURE(scale);
    Bounds bounds;
    bounds.extend(glm::vec3(-1, -0.5f, -2) * scale);
    bounds.extend(glm::vec3(3, 1, 0.5f) * scale);
    const Camera camera = fitCamera(bounds, 4.0f / 3.0f);
    const CameraView view = makeCameraView(camera, bounds, 640, 480);
    // Every corner projects inside the image and between the planes.
    for (int corner = 0; corner < 8; ++corner) {
      const glm::vec3 p((corner & 1) ? bounds.max.x : bounds.min.x, (corner & 2) ? bounds.max.y : bounds.min.y,
                        (corner & 4) ? bounds.max.z : bounds.min.z);
      const glm::vec4 clip = view.projection * view.view * glm::vec4(p, 1.0f);
      CHECK(std::abs(clip.x / clip.w) <= 1.0f);
      CHECK(std::abs(clip.y / clip.w) <= 1.0f);
      CHECK(std::abs(clip.z / clip.w) <= 1.0f);
    }
    // Near and far within a few radii: depth precision scales with the scene.
    CHECK(view.nearPlane > 0.0f);
    CHECK(view.farPlane / view.nearPlane < 20.0f);
    CHECK(view.farPlane - view.nearPlane <= 2.1f * bounds.radius());
  }
}

TEST_CASE("depth range honours the file's znear/zfar and survives a camera inside the bounds") {
  Bounds bounds;
  bounds.extend(glm::vec3(-10.0f));
  bounds.extend(glm::vec3(10.0f));
  Camera camera;  // at the origin, inside the box
  camera.znear = 0.05f;
  float nearPlane = 0, farPlane = 0;
  fitDepthRange(camera, bounds, nearPlane, farPlane);
  CHECK(nearPlane == doctest::Approx(0.05f));
  CHECK(farPlane > 10.0f);
  camera.zfar = 8.0f;  // nearer than the box's far side: the file wins
  fitDepthRange(camera, bounds, nearPlane, farPlane);
  CHECK(farPlane == doctest::Approx(8.0f));
}

TEST_CASE("render options: table-driven flags, presets, and clear errors") {
  using cli::parseRenderArgs;
  const auto command = parseRenderArgs({"scene.glb", "--width", "320", "--height=200", "--ssgi-samples", "16",
                                        "--ssgi-radius", "0.5", "--backend", "osmesa", "--no-shadows", "--out", "o"});
  CHECK(command.scene == "scene.glb");
  CHECK(command.settings.width == 320);
  CHECK(command.settings.height == 200);
  CHECK(command.settings.ssgi.sampleCount == 16);
  CHECK(command.settings.ssgi.radius == 0.5f);
  CHECK(command.context.backend == Backend::OSMesa);
  CHECK_FALSE(command.settings.lighting.shadows);
  CHECK(command.outDir == "o");
  CHECK(parseRenderArgs({}).scene == "builtin:cornell");

  const auto seed = parseRenderArgs({"--preset", "seed"});
  CHECK(seed.settings.ssgi.radius == 0.5f);
  CHECK(seed.settings.ssgi.bias == 0.025f);
  // The seed's method and constants, whatever the default has become.
  CHECK(seed.settings.ssgi.method == SsgiMethod::Hemisphere);
  CHECK(seed.settings.ssgi.sampleCount == 64);
  CHECK(seed.settings.ssgi.intensity == 1.0f);
  CHECK(seed.settings.ssgi.resolution == SsgiResolution::Full);
  CHECK(parseRenderArgs({}).settings.ssgi.method == SsgiMethod::Bitmask);
  CHECK(parseRenderArgs({"--preset", "fast"}).settings.ssgi.sliceCount == 1);
  CHECK(parseRenderArgs({"--preset", "fast", "--ssgi-samples", "8"}).settings.ssgi.sampleCount == 8);

  auto message = [](std::vector<std::string> args) {
    try {
      parseRenderArgs(args);
    } catch (const SettingsError& error) {
      return std::string(error.what());
    }
    return std::string("no error");
  };
  CHECK(message({"--width", "0"}) == "--width: must be in 1..16384, got 0");
  CHECK(message({"--width", "abc"}) == "--width: expected an integer in 1..16384, got 'abc'");
  CHECK(message({"--ssgi-samples", "65"}) == "--ssgi-samples: must be in 1..64, got 65");
  CHECK(message({"--ssgi-radius", "x"}) == "--ssgi-radius: expected auto or a number in 1e-09..1e+09, got 'x'");
  CHECK(message({"--bogus"}).find("unknown option '--bogus'") != std::string::npos);
  CHECK(message({"--width"}) == "--width needs a value (N)");
  CHECK(message({"--backend", "vulkan"}).find("expected one of auto, egl, osmesa") != std::string::npos);
  CHECK(message({"--ssgi-method", "horizon"}) ==
        "--ssgi-method: expected one of hemisphere, radiance, bitmask, got 'horizon'");
  CHECK(message({"--reference-samples", "8"}).find("unknown option") != std::string::npos);  // reference only
  CHECK(parseRenderArgs({"a.glb", "b.glb", "jobs.jsonl"}).scenes.size() == 2);  // a batch
  CHECK(parseRenderArgs({"a.glb", "b.glb", "jobs.jsonl"}).jobFiles.size() == 1);
  CHECK_THROWS_WITH(parseRenderArgs({"a.glb", "b.glb"}, cli::CommandKind::Reference),
                    doctest::Contains("more than one scene"));
  CHECK(message({"--views", "4"}).find("needs --orbit") != std::string::npos);
  CHECK(message({"--shard", "3/3"}).find("expected 0 <= I < N") != std::string::npos);
  CHECK(message({"--targets", "lit,glow"}).find("unknown target 'glow'") != std::string::npos);
  CHECK(message({"--no-ssgi=1"}) == "--no-ssgi takes no value");
}

TEST_CASE("\"auto\" is its own value: 0 is a number like any other") {
  using cli::parseRenderArgs;
  // The old sentinel encoding turned --ssgi-bias 0 into 5% of the radius.
  const auto zeroBias = parseRenderArgs({"--ssgi-bias", "0"});
  REQUIRE(zeroBias.settings.ssgi.bias.has_value());
  CHECK(*zeroBias.settings.ssgi.bias == 0.0f);
  CHECK_FALSE(parseRenderArgs({"--ssgi-bias", "auto"}).settings.ssgi.bias.has_value());
  CHECK_FALSE(RenderSettings{}.ssgi.bias.has_value());
  // A row that cannot be auto refuses it.
  CHECK_THROWS_WITH_AS(parseRenderArgs({"--ssgi-samples", "auto"}),
                       "--ssgi-samples: expected an integer in 1..64, got 'auto'", SettingsError);
}

TEST_CASE("tone curves map 0 to 0, rise monotonically and stay below 1") {
  float previousAces = -1, previousReinhard = -1;
  for (float x = 0; x < 100; x = x * 1.5f + 0.01f) {
    CHECK(tonemapAces(x) >= previousAces);
    CHECK(tonemapReinhard(x) > previousReinhard);
    CHECK(tonemapAces(x) <= 1.0f);
    CHECK(tonemapReinhard(x) < 1.0f);
    previousAces = tonemapAces(x);
    previousReinhard = tonemapReinhard(x);
  }
  CHECK(tonemapAces(0) == doctest::Approx(0.0f));
  CHECK(tonemapReinhard(1) == doctest::Approx(0.5f));
}

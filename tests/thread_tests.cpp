// Threads and contexts: one renderer per thread, each with its own context,
// EGL and OSMesa at the same time; a renderer used where its context is not
// current; EGL devices chosen by index and by name. The cases in the test
// suite "backends" need both EGL and OSMesa; gl_main.cpp skips them (visibly)
// where either is missing.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "headlight/context.hpp"
#include "headlight/error.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "support/gl.hpp"

using namespace headlight;
using namespace headlight::test;

namespace {

RenderSettings tinySettings() {
  RenderSettings settings;
  settings.width = 48;
  settings.height = 32;
  settings.ssgi.sampleCount = 8;
  return settings;
}

ContextOptions optionsFor(Backend backend) {
  ContextOptions options;
  options.backend = backend;
  options.errorPolicy = GlErrorPolicy::Throw;
  return options;
}

}  // namespace

TEST_CASE("two EGL and two OSMesa renderers on four threads at once render correct frames" *
          doctest::test_suite("backends")) {
  constexpr int kCycles = 25;
  std::mutex mutex;
  std::vector<std::string> failures;
  std::vector<float> firstLit[4];
  auto work = [&](int index, Backend backend) {
    try {
      Context context(optionsFor(backend));
      Renderer renderer(context);
      renderer.setScene(loadScene("builtin:cornell"));
      const RenderSettings settings = tinySettings();
      const std::vector<float> first = renderer.render(settings).lit.pixels;
      for (int cycle = 0; cycle < kCycles; ++cycle) {
        const Frame frame = renderer.render(settings);
        if (frame.lit.pixels != first || frame.backend.rfind(std::string(backendName(backend)), 0) != 0) {
          std::lock_guard lock(mutex);
          failures.push_back(std::string(backendName(backend)) + " frame " + std::to_string(cycle) +
                             " differs from its first frame");
        }
      }
      std::lock_guard lock(mutex);
      firstLit[index] = first;
    } catch (const std::exception& error) {
      std::lock_guard lock(mutex);
      failures.push_back(std::string(backendName(backend)) + ": " + error.what());
    }
  };
  // Same-backend renderers take turns (detail::ContextAccess::lockBackend); EGL and OSMesa
  // run at the same time.
  std::thread threads[] = {std::thread(work, 0, Backend::Egl), std::thread(work, 1, Backend::OSMesa),
                           std::thread(work, 2, Backend::Egl), std::thread(work, 3, Backend::OSMesa)};
  for (std::thread& thread : threads) thread.join();
  for (const std::string& failure : failures) FAIL_CHECK(failure);
  REQUIRE(failures.empty());
  // Both are llvmpipe: the same picture (the cross-backend test's bound), and
  // a lit one: the middle of the Cornell box is not black.
  REQUIRE(firstLit[0].size() == 48u * 32u * 4u);
  REQUIRE(firstLit[0].size() == firstLit[1].size());
  CHECK(firstLit[0] == firstLit[2]);  // EGL threads agree exactly
  CHECK(firstLit[1] == firstLit[3]);  // OSMesa threads agree exactly
  float worst = 0;
  for (std::size_t i = 0; i < firstLit[0].size(); ++i)
    worst = std::max(worst, std::abs(firstLit[0][i] - firstLit[1][i]) / std::max(1.0f, std::abs(firstLit[0][i])));
  CHECK(worst <= 1e-3f);
  const std::size_t middle = (16u * 48u + 24u) * 4u;
  CHECK(firstLit[0][middle] > 0.05f);
  CHECK(firstLit[0][middle + 3] == 1.0f);
}

TEST_CASE("a renderer used on a thread where its context is not current throws ContextError") {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:cornell"));
  std::string message;
  std::thread([&] {
    try {
      renderer.render(tinySettings());
    } catch (const ContextError& error) {
      message = error.what();
    }
  }).join();
  CHECK(message.find("not current on this thread") != std::string::npos);
  CHECK(message.find("Renderer::render") != std::string::npos);
  // Still usable on its own thread.
  CHECK(renderer.render(tinySettings()).lit.width == 48);
}

TEST_CASE("EGL devices by index and by name; a missing one is a ContextError" * doctest::test_suite("backends")) {
  std::thread([] {
    ContextOptions options = optionsFor(Backend::Egl);
    options.eglDevice = 99;
    CHECK_THROWS_WITH_AS(Context{options}, doctest::Contains("EGL device 99"), ContextError);
    options.eglDevice = -1;
    options.eglDeviceName = "no-such-device";
    CHECK_THROWS_WITH_AS(Context{options}, doctest::Contains("no device has that name"), ContextError);
    options.eglDeviceName = "EGL_MESA_device_software";  // llvmpipe's device, where EGL_EXT_platform_device exists
    try {
      Context context(options);
      CHECK(context.description().find("EGL device") == 0);
      Renderer renderer(context);
      renderer.setScene(loadScene("builtin:cornell"));
      CHECK(renderer.render(tinySettings()).lit.width == 48);
    } catch (const ContextError& error) {
      MESSAGE("no software EGL device here: " << error.what());
    }
  }).join();
  sharedContext().makeCurrent();
}

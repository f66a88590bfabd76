#pragma once
// What GL tests share: one context per process for the backend under test,
// small render settings, and pixel lookups by world position. Scenes are
// built with headlight/scene_builder.hpp.
#include <algorithm>
#include <cstdlib>
#include <functional>
#include <string>
#include <string_view>

#include "headlight/context.hpp"
#include "headlight/frame.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene.hpp"

namespace headlight::test {

inline Backend backendUnderTest() {
  const char* name = std::getenv("HEADLIGHT_TEST_BACKEND");
  return parseBackend(name ? name : "auto");
}

// Errors throw (GlErrorPolicy::Throw): a GL error fails the test.
inline Context& sharedContext() {
  static Context context(
      ContextOptions{.backend = backendUnderTest(), .errorPolicy = GlErrorPolicy::Throw, .eglDeviceName = {}});
  return context;
}

// Whether a context of `backend` can be made here; tried on a thread of its
// own, so the calling thread's current context is untouched.
bool canMakeContext(Backend backend);

// The GL errors pending on `context` (glGetError and KHR_debug messages of
// type ERROR), reported and cleared: empty when there were none. `context`
// must have GlErrorPolicy::Throw; it is made current on this thread first.
// gl_main.cpp calls it after every test case on sharedContext().
std::string takeGlErrors(Context& context);

// Mean of `channel` of `image` over the pixels whose G-buffer position and
// normal pass `select`; sets `count` to how many there were.
double meanWhere(const Frame& frame, const ImageF& image, int channel,
                 const std::function<bool(glm::vec3 position, glm::vec3 normal)>& select, int& count);

// A 1x1 quad at the origin facing +Z (albedo 0.5, 0.25, 0.125; roughness
// 0.6, metallic 0.3) seen by an orthographic camera from +Z, 3 units tall:
// the quad fills the middle 2/3 of the image.
Scene orthoQuadScene();
// A 100x100 open plane (albedo 0.8) seen from above at a slant.
Scene openPlaneScene();
// True when the frame timed `pass` (it ran).
inline bool timed(const Frame& frame, std::string_view pass) {
  return std::any_of(frame.timings.begin(), frame.timings.end(), [&](const PassTime& t) { return t.pass == pass; });
}

// `scene` rendered by a fresh renderer on sharedContext().
Frame renderFresh(Scene scene, const RenderSettings& settings);

// Settings for a small test render, lit sampled at the pixel centres (no
// antialiasing): the per-pixel checks compare lit with the G-buffer's
// surface at the same pixel and with CPU ports evaluated there; the
// antialiased lit has its own tests (antialias_tests.cpp).
inline RenderSettings smallSettings(int width = 96, int height = 96) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.antialiasSamples = 1;
  return settings;
}

}  // namespace headlight::test

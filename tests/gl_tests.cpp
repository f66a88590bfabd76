// GL tests: small renders on the backend under test (gl_main.cpp), checked
// against analytic values with stated tolerances. Every render goes through
// Context::checkErrors under GlErrorPolicy::Throw, so a GL error fails the
// test that caused it.
#include <doctest/doctest.h>

#include <glad/gl.h>
#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

#include "context/context_access.hpp"
#include "gl/shader_library.hpp"
#include "headlight/error.hpp"
#include "headlight/reference.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"
#include "shared_layout.h"
#include "support/assets.hpp"
#include "support/gl.hpp"
#include "tooling/bench.hpp"

using namespace headlight;
using namespace headlight::test;

TEST_CASE("G-buffer of a known quad holds the analytic position, normal, albedo, material and depth") {
  const int size = 64;
  const Frame frame = renderFresh(orthoQuadScene(), smallSettings(size, size));
  int inside = 0, outside = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      // Pixel centre in world units: orthographic, 1.5 half height, square.
      const float worldX = ((x + 0.5f) / size * 2.0f - 1.0f) * 1.5f;
      const float worldY = (1.0f - (y + 0.5f) / size * 2.0f) * 1.5f;  // rows top first
      if (std::max(std::abs(worldX), std::abs(worldY)) > 1.05f) {
        CHECK(frame.position.at(x, y, 3) == 0.0f);  // background mark
        ++outside;
        continue;
      }
      if (std::max(std::abs(worldX), std::abs(worldY)) > 0.95f) continue;  // edge pixels may go either way
      ++inside;
      CHECK(frame.position.at(x, y, 3) == 1.0f);
      // float32 interpolation at pixel centres: exact to rounding.
      CHECK(std::abs(frame.position.at(x, y, 0) - worldX) < 1e-4f);
      CHECK(std::abs(frame.position.at(x, y, 1) - worldY) < 1e-4f);
      CHECK(std::abs(frame.position.at(x, y, 2)) < 1e-5f);
      // RGBA16F normal: half precision, 1e-3.
      CHECK(std::abs(frame.normal.at(x, y, 2) - 1.0f) < 1e-3f);
      CHECK(std::abs(frame.normal.at(x, y, 0)) < 1e-3f);
      // sRGB8 albedo: half a code step at 0.5 linear is 0.003.
      CHECK(std::abs(frame.albedo.at(x, y, 0) - 0.5f) < 0.004f);
      CHECK(std::abs(frame.albedo.at(x, y, 1) - 0.25f) < 0.004f);
      CHECK(std::abs(frame.albedo.at(x, y, 2) - 0.125f) < 0.004f);
      // RGBA8 material: half a code step is 0.002.
      CHECK(std::abs(frame.material.at(x, y, 0) - 0.3f) < 0.003f);
      CHECK(std::abs(frame.material.at(x, y, 1) - 0.6f) < 0.003f);
      CHECK(std::abs(frame.material.at(x, y, 2) - 1.0f) < 0.003f);
      // The camera is 2 units in front of the quad; float32 depth.
      CHECK(std::abs(frame.depth.at(x, y, 0) - 2.0f) < 1e-4f);
    }
  CHECK(inside > 1000);
  CHECK(outside > 500);
}

TEST_CASE("background pixels are left as cleared by every pass") {
  const Frame frame = renderFresh(loadScene("builtin:spheres"), smallSettings(96, 72));
  int background = 0;
  for (int y = 0; y < frame.position.height; ++y)
    for (int x = 0; x < frame.position.width; ++x) {
      if (frame.position.at(x, y, 3) != 0.0f) continue;
      ++background;
      for (int c = 0; c < 3; ++c) {
        CHECK(frame.normal.at(x, y, c) == 0.0f);
        CHECK(frame.albedo.at(x, y, c) == 0.0f);
        CHECK(frame.material.at(x, y, c) == 0.0f);
      }
      CHECK(frame.ssgi.at(x, y, 0) == 1.0f);
      CHECK(frame.ssgi.at(x, y, 1) == 0.0f);
      CHECK(frame.depth.at(x, y, 0) == doctest::Approx(frame.view.farPlane).epsilon(1e-4));
      CHECK(frame.lit.at(x, y, 3) == 0.0f);
      CHECK(frame.lit.at(x, y, 2) > 0.0f);  // the sky shows through
    }
  CHECK(background > 100);
}

TEST_CASE("one renderer renders many sizes and views; a repeated render is bit-identical") {
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:cornell"));
  const Frame first = renderer.render(smallSettings(80, 60));
  const Frame other = renderer.render(smallSettings(33, 17));
  CHECK(other.lit.width == 33);
  CHECK(other.lit.height == 17);
  Camera side = makeLookAtCamera({1.5f, 1.0f, 3.0f}, {0, 1, 0}, 0.9f);
  const Frame moved = renderer.render(smallSettings(80, 60), &side);
  const Frame again = renderer.render(smallSettings(80, 60));
  CHECK(moved.lit.pixels != first.lit.pixels);
  for (const auto& [name, image] : first.targets()) {
    CAPTURE(name);
    const auto& againTargets = again.targets();
    const auto match =
        std::find_if(againTargets.begin(), againTargets.end(), [&](const auto& t) { return t.first == name; });
    REQUIRE(match != againTargets.end());
    CHECK(image->pixels == match->second->pixels);
  }
}

TEST_CASE("a GL error is reported as GlError naming the operation") {
  Context& context = sharedContext();
  // Core profile: binding a name that glGen*/glCreate* never returned is
  // GL_INVALID_OPERATION.
  glBindTexture(GL_TEXTURE_2D, 987654);
  CHECK(headlight::detail::ContextAccess::pendingErrorCount(context) >= 1);  // the KHR_debug callback saw it
  try {
    context.checkErrors("deliberate bad bind");
    FAIL("checkErrors did not throw");
  } catch (const GlError& error) {
    CHECK(std::string(error.what()).find("deliberate bad bind") != std::string::npos);
    CHECK(std::string(error.what()).find("GL_INVALID_OPERATION") != std::string::npos);
  }
  CHECK_NOTHROW(context.checkErrors("after the error was reported"));
}

// gl_main.cpp runs takeGlErrors on the shared context after every case and
// fails the case when it reports anything. These two cases show that the
// check sees a provoked error, and that a case which leaves one is failed.
TEST_CASE("the end-of-case check reports a provoked GL error once, then nothing") {
  Context& context = sharedContext();
  glBindTexture(GL_TEXTURE_2D, 987654);  // GL_INVALID_OPERATION, as above
  const std::string errors = takeGlErrors(context);
  CHECK(errors.find("GL_INVALID_OPERATION") != std::string::npos);
  CHECK(errors.find("the end of the test case") != std::string::npos);
  CHECK(takeGlErrors(context).empty());
}

TEST_CASE("a case that leaves a GL error pending is failed by the end-of-case check" * doctest::should_fail()) {
  // No assertion here fails: only gl_main.cpp's check can fail this case,
  // and should_fail turns that failure into a pass (and its absence into a
  // failure). The check clears the error, so the next case starts clean.
  glBindTexture(GL_TEXTURE_2D, 987654);
  CHECK(detail::ContextAccess::pendingErrorCount(sharedContext()) >= 1);
}

TEST_CASE("EGL and OSMesa render the same images" * doctest::test_suite("backends")) {
  RenderSettings settings = smallSettings(64, 48);
  auto renderWith = [&](Backend backend) {
    Context context(ContextOptions{.backend = backend, .errorPolicy = GlErrorPolicy::Throw, .eglDeviceName = {}});
    Renderer renderer(context);
    renderer.setScene(loadScene("builtin:cornell"));
    return renderer.render(settings);
  };
  const Frame egl = renderWith(Backend::Egl);
  const Frame osmesa = renderWith(Backend::OSMesa);
  sharedContext().makeCurrent();
  CHECK(egl.backend.rfind("egl", 0) == 0);
  CHECK(osmesa.backend.rfind("osmesa", 0) == 0);
  // Both run the same rasteriser on llvmpipe; on other drivers a few ULPs of
  // half-float difference are allowed: 1e-3 of the lit value, max.
  for (const auto& [name, image] : egl.targets()) {
    CAPTURE(name);
    const auto other = osmesa.targets();
    const auto match = std::find_if(other.begin(), other.end(), [&](const auto& t) { return t.first == name; });
    REQUIRE(match != other.end());
    REQUIRE(image->pixels.size() == match->second->pixels.size());
    float worst = 0;
    for (std::size_t i = 0; i < image->pixels.size(); ++i)
      worst = std::max(
          worst, std::abs(image->pixels[i] - match->second->pixels[i]) / std::max(1.0f, std::abs(image->pixels[i])));
    CHECK(worst <= 1e-3f);
  }
}

TEST_CASE("a mirrored instance (negative determinant) is drawn, facing the way it faces") {
  Scene scene = orthoQuadScene();
  // glTF: a mirroring transform makes clockwise triangles the front faces.
  scene.instances[0].worldFromLocal = glm::scale(glm::mat4(1.0f), glm::vec3(-1.0f, 1.0f, 1.0f));
  const Frame frame = renderFresh(scene, smallSettings(64, 64));
  int covered = 0;
  for (int y = 0; y < 64; ++y)
    for (int x = 0; x < 64; ++x)
      if (frame.position.at(x, y, 3) == 1.0f) {
        ++covered;
        CHECK(frame.normal.at(x, y, 2) > 0.999f);  // still toward the camera at +Z
      }
  CHECK(covered > 1000);  // culled away entirely before glFrontFace followed the transform
}

TEST_CASE("one renderer across setting and scene changes renders what a fresh one does") {
  const RenderSettings defaults = smallSettings(48, 36);
  auto freshRender = [&](const char* scene, const RenderSettings& settings) {
    return renderFresh(loadScene(scene), settings);
  };
  Renderer renderer(sharedContext());
  renderer.setScene(loadScene("builtin:cornell"));
  renderer.render(defaults);
  RenderSettings changed = defaults;
  changed.ssgi.enabled = false;
  renderer.render(changed);
  changed = defaults;
  changed.ssgi.method = SsgiMethod::Radiance;
  changed.ssgi.resolution = SsgiResolution::Half;
  renderer.render(changed);
  changed = defaults;
  changed.lighting.shadows = false;
  renderer.render(changed);
  changed.width = 40;
  renderer.render(changed);
  CHECK(renderer.render(defaults).lit.pixels == freshRender("builtin:cornell", defaults).lit.pixels);

  // Scene changes: emissive (Cornell) -> none (spheres) -> emissive again.
  renderer.setScene(loadScene("builtin:spheres"));
  const Frame spheres = renderer.render(defaults);
  CHECK(spheres.emissive.empty());
  CHECK(spheres.lit.pixels == freshRender("builtin:spheres", defaults).lit.pixels);
  renderer.setScene(loadScene("builtin:cornell"));
  const Frame cornell = renderer.render(defaults);
  CHECK(!cornell.emissive.empty());
  CHECK(cornell.lit.pixels == freshRender("builtin:cornell", defaults).lit.pixels);
}

TEST_CASE("a spot light lights its cone and not beyond, with inverse-square falloff") {
  Scene scene;
  scene.source = "test:spot";
  addInstance(scene, makeSquare({0, 0, 0}, {0, 1, 0}, 5.0f), addMaterial(scene, makeMaterial(glm::vec3(0.8f), 1.0f)));
  scene.cameras.push_back(makeOrthographicCamera({0, 6, 0.01f}, {0, 0, 0}, 4.0f));  // from above
  Light spot;
  spot.type = Light::Type::Spot;
  spot.position = {0, 2, 0};
  spot.direction = {0, -1, 0};
  spot.intensity = 10.0f;
  spot.innerConeAngle = 0.3f;
  spot.outerConeAngle = 0.4f;  // a disc of radius 2 tan(0.4) = 0.85 on the floor
  scene.lights.push_back(spot);
  scene.sky.intensity = 0.0f;
  RenderSettings settings = smallSettings(64, 64);
  settings.ssgi.enabled = false;
  const Frame frame = renderFresh(scene, settings);
  auto litAt = [&](float worldX) {  // along the image's middle row
    const int x = int((worldX / 4.0f * 0.5f + 0.5f) * 64);
    return frame.lit.at(x, 32, 0);
  };
  const float centre = litAt(0.0f), inside = litAt(0.5f), outside = litAt(1.5f);
  CHECK(centre > 0.1f);
  CHECK(outside == 0.0f);  // beyond the outer cone: no light, no sky
  // Inside the inner cone only distance and angle differ: the centre gets
  // E = I / d^2 at normal incidence, x = 0.5 gets I cos / (d^2 + x^2).
  const float expectedRatio = (2.0f / std::pow(4.25f, 1.5f)) / (1.0f / 4.0f);
  CHECK(inside / centre == doctest::Approx(expectedRatio).epsilon(0.1));
}


// Tests that need no GL context and link no GL: camera fitting and tone
// curves. (The unit executable links only the library's GL-free objects;
// tests/meson.build.)
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

#include "headlight/camera.hpp"
#include "headlight/output.hpp"
#include "output/tonemap.hpp"

using namespace headlight;

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

// A directional light's shadow map covers what the camera sees of the scene
// (lib/passes/shadow.cpp, directionalCoverage) where that is much less than
// the scene: a view of a small part of a large floor gets the map's texels
// there, and its shadow edges stay about a pixel wide.
#include <doctest/doctest.h>

#include <glm/gtc/matrix_transform.hpp>

#include "headlight/renderer.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/shapes.hpp"
#include "passes/shadow.hpp"
#include "headlight/camera.hpp"
#include "support/gl.hpp"

using namespace headlight;
using namespace headlight::test;

namespace {

// A 1 m box on a 60 m floor under a sun from the upper left, nothing else:
// no sky, so the floor is lit by the sun alone (or not at all).
Scene largeFloorScene() {
  Scene scene;
  scene.source = "test:large-floor";
  addInstance(scene, makeFloor(30.0f), addMaterial(scene, makeMaterial({1.0f, 1.0f, 1.0f}, 1.0f)));
  addInstance(scene, makeBox(glm::vec3(1.0f)), addMaterial(scene, makeMaterial({1.0f, 1.0f, 1.0f}, 1.0f)),
              glm::translate(glm::mat4(1.0f), glm::vec3(0.0f, 0.5f, 0.0f)));
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(glm::vec3(1.0f, -1.0f, 0.0f));
  sun.intensity = 3.0f;
  sun.castsShadows = true;
  scene.lights.push_back(sun);
  scene.sky.intensity = 0.0f;
  return scene;
}

// Looking down at the box and the shadow it throws along +x.
Camera closeCamera() { return makeLookAtCamera({1.5f, 4.0f, 2.0f}, {1.5f, 0.0f, 0.0f}, 0.9f); }

CameraView viewOf(const Scene& scene, const Camera& camera) {
  return makeCameraView(camera, scene.worldBounds(), 128, 128);
}

}  // namespace

TEST_CASE("a directional map covers the part of a large scene the camera sees, and all of a framed one") {
  const Scene scene = largeFloorScene();
  const float radius = scene.worldBounds().radius();
  const float squareArea = 4.0f * radius * radius;
  const CameraView close = viewOf(scene, closeCamera());
  const std::vector<glm::vec4> fitted = directionalCoverage(scene.lights, scene.worldBounds(), &close);
  REQUIRE(fitted.size() == 1);
  const glm::vec4 rectangle = fitted[0];
  const float area = (rectangle.z - rectangle.x) * (rectangle.w - rectangle.y);
  CAPTURE(area / squareArea);
  // The close view sees a few metres of a 60 m floor.
  CHECK(area < 0.05f * squareArea);
  CHECK(area > 0.0f);
  // A camera framing the whole scene, and no camera, cover the square.
  const Camera framing = fitCamera(scene.worldBounds(), 1.0f);
  const CameraView whole = viewOf(scene, framing);
  const glm::vec4 square(-radius, -radius, radius, radius);
  CHECK(directionalCoverage(scene.lights, scene.worldBounds(), &whole)[0] == square);
  CHECK(directionalCoverage(scene.lights, scene.worldBounds(), nullptr)[0] == square);
  // Spot and point lights are not fitted; a sun without shadows has no map.
  Scene others = scene;
  others.lights[0].castsShadows = false;
  CHECK(directionalCoverage(others.lights, others.worldBounds(), &close).empty());
}

TEST_CASE("a close view of a large floor gets a shadow edge about a pixel wide, and a new view new maps") {
  Renderer renderer(sharedContext());
  renderer.setScene(largeFloorScene());
  RenderSettings settings = smallSettings(128, 128);
  settings.ssgi.enabled = false;
  const Camera close = closeCamera();
  const Frame frame = renderer.render(settings, &close);
  // Along each row, the floor goes from the box's shadow (0) to sunlit; the
  // pixels in between (more than 5 % and less than 95 % of the row's lit
  // level) are the edges' width, two edges a row.
  int rows = 0, edgePixels = 0;
  for (int y = 0; y < frame.lit.height; ++y) {
    float brightest = 0.0f, darkest = 1e30f;
    for (int x = 0; x < frame.lit.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f || frame.position.at(x, y, 1) > 1e-3f) continue;  // floor only
      brightest = std::max(brightest, frame.lit.at(x, y, 0));
      darkest = std::min(darkest, frame.lit.at(x, y, 0));
    }
    if (brightest <= 0.0f || darkest > 0.05f * brightest) continue;  // no shadow on this row
    ++rows;
    for (int x = 0; x < frame.lit.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f || frame.position.at(x, y, 1) > 1e-3f) continue;
      const float level = frame.lit.at(x, y, 0) / brightest;
      edgePixels += level > 0.05f && level < 0.95f;
    }
  }
  CAPTURE(rows);
  CAPTURE(edgePixels);
  REQUIRE(rows > 10);
  // Measured 3.0 a row (75 pixels over 25 rows); with the map over the whole
  // scene's square (85 m across at 1024 texels: 8 cm a texel, where a pixel
  // here is ~3 cm) 9.4 (187 over 20).
  CHECK(double(edgePixels) / rows < 5.0);

  // The same view reuses the maps; another one is fitted anew.
  const auto shadowPasses = [](const Frame& f) {
    return std::count_if(f.timings.begin(), f.timings.end(), [](const PassTime& t) { return t.pass == "shadows"; });
  };
  CHECK(shadowPasses(frame) == 1);
  CHECK(shadowPasses(renderer.render(settings, &close)) == 0);
  const Camera other = makeLookAtCamera({-1.5f, 4.0f, 2.0f}, {-1.5f, 0.0f, 0.0f}, 0.9f);
  CHECK(shadowPasses(renderer.render(settings, &other)) == 1);
}

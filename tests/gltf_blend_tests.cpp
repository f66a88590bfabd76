// alphaMode BLEND: the blend pass (lib/passes/blend.hpp) draws blended
// surfaces back to front over lit, with a coverage target, and keeps them
// out of the G-buffer and the shadow maps.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "headlight/reference.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"
#include "passes/blend.hpp"
#include "support/assets.hpp"
#include "support/gl.hpp"

using namespace headlight;
using namespace headlight::test;

namespace {

// Black, fully rough metal that only emits: its radiance is its emission
// exactly when no light reaches its front (the sun below shines on its back).
Material emitter(const glm::vec3& emission, float alpha, AlphaMode mode) {
  Material material = makeMaterial(glm::vec3(0.0f), 1.0f, 1.0f);
  material.emissiveFactor = emission;
  material.baseColorFactor.a = alpha;
  material.alphaMode = mode;
  return material;
}

// Seen from +Z, orthographic, 3 units tall: an opaque wall at z = -1 on
// the left half (x < 0), and two blended squares over the middle, the
// nearer (z = 0.5, green, alpha 0.25) listed first so that only the sort
// draws it last.
constexpr glm::vec3 kWall{0.2f, 0.4f, 0.8f}, kFar{1.0f, 0.0f, 0.0f}, kNear{0.0f, 1.0f, 0.0f};
constexpr float kFarAlpha = 0.5f, kNearAlpha = 0.25f;

Scene twoLayerScene() {
  Scene scene;
  scene.source = "test:two-layers";
  addInstance(scene, makeSquare({0, 0, 0.5f}, {0, 0, 1}, 1.0f), addMaterial(scene, emitter(kNear, kNearAlpha, AlphaMode::Blend)));
  addInstance(scene, makeSquare({0, 0, 0}, {0, 0, 1}, 1.0f), addMaterial(scene, emitter(kFar, kFarAlpha, AlphaMode::Blend)));
  addInstance(scene, makeSquare({-1.5f, 0, -1}, {0, 0, 1}, 1.5f), addMaterial(scene, emitter(kWall, 1.0f, AlphaMode::Opaque)));
  scene.cameras.push_back(makeOrthographicCamera({0, 0, 3}, {0, 0, 0}, 1.5f));
  Light light;
  light.type = Light::Type::Directional;
  light.direction = {0, 0, 1};  // travels away from the camera: lights only the backs
  light.intensity = 3.0f;
  scene.lights.push_back(light);
  scene.sky.intensity = 0.0f;
  return scene;
}

RenderSettings exactSettings(int size) {
  RenderSettings settings = smallSettings(size, size);
  settings.ssgi.enabled = false;  // blended surfaces get no SSGI; the wall then gets none either
  return settings;
}

}  // namespace

TEST_CASE("blend: two layers over an opaque wall and over background give the over operator's answer") {
  constexpr int size = 64;
  const Frame frame = renderFresh(twoLayerScene(), exactSettings(size));
  REQUIRE(!frame.coverage.empty());
  const float coverage = 1.0f - (1.0f - kFarAlpha) * (1.0f - kNearAlpha);  // 0.625
  // World x = -0.5 (over the wall) and +0.5 (over background), y = 0.
  const int overWall = size * 1 / 3, overBackground = size * 2 / 3, row = size / 2;
  for (int c = 0; c < 3; ++c) {
    CAPTURE(c);
    const float overBlack = kNearAlpha * kNear[c] + (1.0f - kNearAlpha) * kFarAlpha * kFar[c];
    const float overWallExpected = overBlack + (1.0f - coverage) * kWall[c];
    // Half-float lit: 1e-3 relative and absolute covers its rounding.
    CHECK(frame.lit.at(overWall, row, c) == doctest::Approx(overWallExpected).epsilon(2e-3).scale(1.0));
    CHECK(frame.lit.at(overBackground, row, c) == doctest::Approx(overBlack).epsilon(2e-3).scale(1.0));
  }
  CHECK(frame.lit.at(overWall, row, 3) == doctest::Approx(1.0f));
  CHECK(frame.lit.at(overBackground, row, 3) == doctest::Approx(coverage).epsilon(2e-3));
  CHECK(frame.coverage.at(overWall, row, 0) == doctest::Approx(coverage).epsilon(2e-3));
  CHECK(frame.coverage.at(overBackground, row, 0) == doctest::Approx(coverage).epsilon(2e-3));
  // One layer alone: coverage is its alpha. Nothing blended: 0.
  Scene single = twoLayerScene();
  single.instances.erase(single.instances.begin());
  const Frame one = renderFresh(single, exactSettings(size));
  CHECK(one.coverage.at(overBackground, row, 0) == doctest::Approx(kFarAlpha).epsilon(2e-3));
  CHECK(one.lit.at(overBackground, row, 3) == doctest::Approx(kFarAlpha).epsilon(2e-3));
  CHECK(frame.coverage.at(2, row, 0) == 0.0f);  // x = -1.45: the wall, no layer
  // The G-buffer holds what is under the layers: the wall, or background.
  CHECK(frame.position.at(overWall, row, 2) == doctest::Approx(-1.0f));
  CHECK(frame.position.at(overBackground, row, 3) == 0.0f);
}

TEST_CASE("blend: the sort draws the farthest centre first, whatever the file's order") {
  std::vector<GpuBlendDraw> draws(3);
  draws[0].worldCenter = {0, 0, 0.5f};
  draws[1].worldCenter = {0, 0, -2.0f};
  draws[2].worldCenter = {5, 0, 0.0f};
  CameraView view;
  view.view = glm::mat4(1.0f);
  view.view[3] = glm::vec4(0, 0, -3, 1);  // camera at z = 3 looking down -Z
  CHECK(blendOrder(draws, view) == std::vector<std::size_t>{1, 2, 0});
  draws[0].worldCenter = draws[1].worldCenter;  // a tie keeps the file's order
  CHECK(blendOrder(draws, view) == std::vector<std::size_t>{0, 1, 2});
}

TEST_CASE("blend: a blended surface casts no shadow and leaves unblended pixels as they were") {
  constexpr int size = 64;
  Scene scene;
  scene.source = "test:blend-shadow";
  addInstance(scene, makeSquare({0, 0, 0}, {0, 0, 1}, 1.5f), addMaterial(scene, makeMaterial(glm::vec3(0.8f), 0.8f)));
  Material glass = makeMaterial(glm::vec3(0.9f), 0.5f);
  glass.baseColorFactor.a = 0.5f;
  glass.alphaMode = AlphaMode::Blend;
  // A small pane at z = 1 over the wall's right part; the sun travels toward
  // -x and -z, so an opaque pane's shadow would fall 1 unit to its left.
  addInstance(scene, makeSquare({0.75f, 0, 1}, {0, 0, 1}, 0.4f), addMaterial(scene, glass));
  scene.cameras.push_back(makeOrthographicCamera({0, 0, 3}, {0, 0, 0}, 1.5f));
  Light sun;
  sun.type = Light::Type::Directional;
  sun.direction = glm::normalize(glm::vec3(-1, 0, -1));
  sun.intensity = 3.0f;
  scene.lights.push_back(sun);
  const Frame blended = renderFresh(scene, exactSettings(size));
  // Alpha 0 draws nothing, and keeps the bounds (camera, shadow maps) as they were.
  Scene without = scene;
  without.materials[1].baseColorFactor.a = 0.0f;
  const Frame reference = renderFresh(without, exactSettings(size));
  int covered = 0, same = 0, other = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (blended.coverage.at(x, y, 0) > 0.0f) {
        ++covered;
        continue;
      }
      ++other;
      bool equal = true;
      for (int c = 0; c < 4; ++c) equal = equal && blended.lit.at(x, y, c) == reference.lit.at(x, y, c);
      same += equal ? 1 : 0;
    }
  CHECK(covered > 0);
  CHECK(same == other);  // the would-be shadow, left of the pane, is as lit as without the pane
  // An opaque pane does shadow it: the test can fail.
  Scene opaque = scene;
  opaque.materials[1].alphaMode = AlphaMode::Opaque;
  const Frame shadowed = renderFresh(opaque, exactSettings(size));
  const int shadowX = int((0.75f - 1.0f + 1.5f) / 3.0f * size), shadowY = size / 2;
  CHECK(shadowed.lit.at(shadowX, shadowY, 0) < 0.5f * reference.lit.at(shadowX, shadowY, 0));
  CHECK(blended.lit.at(shadowX, shadowY, 0) == reference.lit.at(shadowX, shadowY, 0));
}

TEST_CASE("conformance: AlphaBlendModeTest's blend panel lies between what is behind it and the panel made opaque" *
          doctest::skip(!test::exists(test::sharedFolder() / "gltf-conformance" / "AlphaBlendModeTest"))) {
  const Scene scene = loadScene(
      (test::sharedFolder() / "gltf-conformance" / "AlphaBlendModeTest" / "glTF" / "AlphaBlendModeTest.gltf").string());
  CHECK(std::none_of(scene.ignored.begin(), scene.ignored.end(),
                     [](const IgnoredFeature& f) { return f.feature == "alphaMode BLEND"; }));
  // What is behind the blended surfaces (their alpha 0: nothing drawn, and
  // the same bounds, fitted camera and shadow maps), and the blended
  // surfaces made opaque.
  Scene behind = scene, opaque = scene;
  for (Material& material : behind.materials)
    if (material.blended()) material.baseColorFactor.a = 0.0f;
  for (Material& material : opaque.materials)
    if (material.blended()) material.alphaMode = AlphaMode::Opaque;
  constexpr int width = 192, height = 96;
  RenderSettings settings = exactSettings(width);
  settings.height = height;
  const Frame frame = renderFresh(scene, settings), under = renderFresh(behind, settings),
              layer = renderFresh(opaque, settings);
  int blendedPixels = 0, between = 0, proportional = 0, unblended = 0, unchanged = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const float a = frame.coverage.at(x, y, 0);
      if (a == 0.0f) {
        ++unblended;
        bool equal = true;
        for (int c = 0; c < 4; ++c) equal = equal && frame.lit.at(x, y, c) == under.lit.at(x, y, c);
        unchanged += equal ? 1 : 0;
        continue;
      }
      if (a < 0.05f || a > 0.95f) continue;
      ++blendedPixels;
      bool inside = true, matches = true;
      for (int c = 0; c < 3; ++c) {
        const float back = under.lit.at(x, y, c), front = layer.lit.at(x, y, c), got = frame.lit.at(x, y, c);
        // 0.01 + 2 %: half-float storage and one layer's silhouette.
        const float tolerance = 0.01f + 0.02f * std::max(back, front);
        inside = inside && got >= std::min(back, front) - tolerance && got <= std::max(back, front) + tolerance;
        matches = matches && std::abs(got - (a * front + (1.0f - a) * back)) <= tolerance;
      }
      between += inside ? 1 : 0;
      proportional += matches ? 1 : 0;
    }
  CAPTURE(blendedPixels);
  CAPTURE(between);
  CAPTURE(proportional);
  CHECK(blendedPixels > width * height / 100);  // the panel and its label: several percent of the image
  // Edges (the opaque render's silhouette moves the layer by a pixel) and
  // the label drawn over the panel (two layers) are allowed 5 %.
  CHECK(between >= blendedPixels * 95 / 100);
  CHECK(proportional >= blendedPixels * 95 / 100);
  // The opaque panel and everything else no blended surface covers: exactly
  // as with the blended surfaces invisible (they cast no shadow).
  CHECK(unchanged == unblended);
}

TEST_CASE("blend: the Embree reference composites the same two layers along its primary rays" *
          doctest::skip(!referenceAvailable())) {
  constexpr int size = 32;
  const Scene scene = twoLayerScene();
  const Frame frame = renderFresh(scene, exactSettings(size));
  ReferenceSettings settings;
  settings.samplesPerPixel = 4;
  settings.radius = 1.0f;
  const ReferenceImages reference = traceReference(scene, frame, settings);
  // Emission only (black metal lit from behind, sky 0): the rasteriser's
  // answer exactly, up to lit's half-float storage.
  int compared = 0;
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (frame.coverage.at(x, y, 0) == 0.0f) continue;
      ++compared;
      for (int c = 0; c < 4; ++c) {
        CAPTURE(x);
        CAPTURE(y);
        CAPTURE(c);
        CHECK(reference.lit.at(x, y, c) == doctest::Approx(frame.lit.at(x, y, c)).epsilon(2e-3).scale(1.0));
      }
    }
  CHECK(compared > size * size / 4);
}

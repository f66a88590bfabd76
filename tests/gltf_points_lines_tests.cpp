// Points and lines in the G-buffer: 1-pixel points and lines, lit like
// surfaces, with a normal toward the camera where the file gives none.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "headlight/scene_builder.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/shapes.hpp"
#include "support/assets.hpp"
#include "support/gl.hpp"

using namespace headlight;
using namespace headlight::test;

namespace {

// 60 pixels over 3 units (orthographic from +Z): pixel centres at
// -1.475 + 0.05 i, so 0.025 is the centre of pixel 30.
constexpr int kSize = 60;

Primitive listOf(PrimitiveMode mode, std::vector<glm::vec3> positions, std::vector<std::uint32_t> indices) {
  Primitive primitive;
  primitive.mode = mode;
  primitive.normals.assign(positions.size(), glm::vec3(0.0f));  // as the loader leaves them without NORMAL
  primitive.positions = std::move(positions);
  primitive.indices = std::move(indices);
  for (const glm::vec3& p : primitive.positions) primitive.bounds.extend(p);
  return primitive;
}

Scene pointsAndLines(bool withLine) {
  Scene scene;
  scene.source = "test:points-lines";
  const int white = addMaterial(scene, makeMaterial(glm::vec3(0.8f), 0.5f));
  addInstance(scene, listOf(PrimitiveMode::Points, {{0.025f, 0.525f, 0.0f}}, {0}), white);
  if (withLine) addInstance(scene, listOf(PrimitiveMode::Lines, {{-1.0f, -0.475f, 0}, {1.0f, -0.475f, 0}}, {0, 1}), white);
  scene.cameras.push_back(makeOrthographicCamera({0, 0, 2}, {0, 0, 0}, 1.5f));
  return scene;
}

}  // namespace

TEST_CASE("points and lines: a point covers one pixel and a line one pixel per pixel of length, facing the camera") {
  const Frame frame = renderFresh(pointsAndLines(true), smallSettings(kSize, kSize));
  int pointPixels = 0, linePixels = 0, lineRows = 0;
  std::vector<int> rowsWithLine;
  for (int y = 0; y < kSize; ++y) {
    int inRow = 0;
    for (int x = 0; x < kSize; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      const float worldY = frame.position.at(x, y, 1);
      (worldY > 0.0f ? pointPixels : linePixels)++;
      if (worldY < 0.0f) ++inRow;
      // The normal faces the camera (+Z), the albedo is the material's, and
      // it is lit.
      CHECK(frame.normal.at(x, y, 2) == doctest::Approx(1.0f).epsilon(1e-3));
      CHECK(frame.albedo.at(x, y, 0) == doctest::Approx(0.8f).epsilon(0.01));
      CHECK(frame.lit.at(x, y, 0) > 0.05f);
    }
    lineRows += inRow > 0 ? 1 : 0;
  }
  CHECK(pointPixels == 1);  // 1-pixel point at a pixel centre
  const int pointX = 30, pointY = kSize - 1 - 40;  // world (0.025, 0.525), rows top first
  CHECK(frame.position.at(pointX, pointY, 3) == 1.0f);
  CHECK(frame.position.at(pointX, pointY, 0) == doctest::Approx(0.025f));
  CHECK(lineRows == 1);  // a 1-pixel line along a row of pixel centres
  // 2 units at 0.05 per pixel: 40 pixels, give or take an end (diamond-exit rule).
  CHECK(linePixels >= 39);
  CHECK(linePixels <= 41);
}

TEST_CASE("points and lines cast no shadow") {
  // A sun straight down, a floor at y = -1; a horizontal line above it would
  // shade one row if it cast a shadow: the floor is lit the same with and
  // without it.
  Scene with = pointsAndLines(true), without = pointsAndLines(false);
  for (Scene* scene : {&with, &without}) {
    addInstance(*scene, makeSquare({0, -1, -0.5f}, glm::normalize(glm::vec3(0, 1, 1)), 2.0f),
                addMaterial(*scene, makeMaterial(glm::vec3(0.5f), 0.9f)));
    Light sun;
    sun.type = Light::Type::Directional;
    sun.direction = {0, -1, 0};
    scene->lights.push_back(sun);
  }
  RenderSettings settings = smallSettings(kSize, kSize);
  settings.ssgi.enabled = false;
  const Frame a = renderFresh(with, settings), b = renderFresh(without, settings);
  int floorPixels = 0, differ = 0;
  for (int y = 0; y < kSize; ++y)
    for (int x = 0; x < kSize; ++x) {
      if (b.position.at(x, y, 3) == 0.0f || a.position.at(x, y, 1) > -0.45f) continue;  // the floor only
      if (std::abs(a.position.at(x, y, 2) - b.position.at(x, y, 2)) > 1e-4f) continue;   // the line, not the floor
      ++floorPixels;
      differ += a.lit.at(x, y, 0) != b.lit.at(x, y, 0) ? 1 : 0;
    }
  CHECK(floorPixels > 100);
  CHECK(differ == 0);
}

TEST_CASE("conformance: MeshPrimitiveModes draws something in every cell, points sparsest" *
          doctest::skip(!test::exists(test::sharedFolder() / "gltf-conformance" / "MeshPrimitiveModes"))) {
  const Scene scene = loadScene(
      (test::sharedFolder() / "gltf-conformance" / "MeshPrimitiveModes" / "glTF" / "MeshPrimitiveModes.gltf").string());
  REQUIRE(scene.instances.size() == 7);
  constexpr int size = 128;
  const Frame frame = renderFresh(scene, smallSettings(size, size));
  // The screenshot's layout: POINTS on top at (0, 3); LINES, LINE_LOOP,
  // LINE_STRIP at y = 0 and x = -2, 0, 2; TRIANGLES, STRIP, FAN at y = -3.
  // A covered pixel belongs to the cell whose node origin is nearest.
  const glm::vec2 origins[7] = {{0, 3}, {-2, 0}, {0, 0}, {2, 0}, {-2, -3}, {0, -3}, {2, -3}};
  int counts[7] = {};
  for (int y = 0; y < size; ++y)
    for (int x = 0; x < size; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      const glm::vec2 p(frame.position.at(x, y, 0), frame.position.at(x, y, 1));
      int nearest = 0;
      for (int cell = 1; cell < 7; ++cell)
        if (glm::length(p - origins[cell]) < glm::length(p - origins[nearest])) nearest = cell;
      ++counts[nearest];
    }
  for (int cell = 0; cell < 7; ++cell) {
    CAPTURE(cell);
    CHECK(counts[cell] > 0);
  }
  CHECK(counts[0] <= 7);  // 7 vertices as 1-pixel points
  for (int line = 1; line <= 3; ++line)
    for (int triangle = 4; triangle <= 6; ++triangle) CHECK(counts[line] < counts[triangle]);
  MESSAGE("covered pixels per cell (points, lines, loop, strip, triangles, strip, fan): " << counts[0] << " "
          << counts[1] << " " << counts[2] << " " << counts[3] << " " << counts[4] << " " << counts[5] << " "
          << counts[6]);
}

// The Khronos conformance models of KHR_materials_specular and
// KHR_materials_clearcoat (issue 18 item 3), rendered small: what each
// extension must change, in numbers. Pixels are told apart by their world
// position (the G-buffer's), so the tests do not depend on the framing. A
// missing model is a visible skip.
#include <doctest/doctest.h>

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "headlight/scene_loader.hpp"
#include "support/assets.hpp"
#include "support/gl.hpp"
#include "support/scene_checks.hpp"

using namespace headlight;
using namespace headlight::test;

namespace {

float luminance(const Frame& frame, int x, int y) {
  return 0.2126f * frame.lit.at(x, y, 0) + 0.7152f * frame.lit.at(x, y, 1) + 0.0722f * frame.lit.at(x, y, 2);
}

// The covered pixels whose world position passes `inside`.
struct Region {
  std::vector<std::pair<int, int>> pixels;
  float maxLuminance = 0.0f;
  double meanLuminance = 0.0;
};
Region region(const Frame& frame, const std::function<bool(glm::vec3)>& inside) {
  Region r;
  for (int y = 0; y < frame.lit.height; ++y)
    for (int x = 0; x < frame.lit.width; ++x) {
      if (frame.position.at(x, y, 3) == 0.0f) continue;
      if (!inside({frame.position.at(x, y, 0), frame.position.at(x, y, 1), frame.position.at(x, y, 2)})) continue;
      r.pixels.emplace_back(x, y);
      const float l = luminance(frame, x, y);
      r.maxLuminance = std::max(r.maxLuminance, l);
      r.meanLuminance += l;
    }
  if (!r.pixels.empty()) r.meanLuminance /= double(r.pixels.size());
  return r;
}

// The pixels within `radius` of `center` (world).
Region near(const Frame& frame, glm::vec3 center, float radius) {
  return region(frame, [=](glm::vec3 p) { return glm::length(p - center) < radius; });
}

// Mean of `channel` of `image` over a region's pixels.
double meanOf(const ImageF& image, const Region& r, int channel) {
  double sum = 0.0;
  for (const auto& [x, y] : r.pixels) sum += image.at(x, y, channel);
  return r.pixels.empty() ? 0.0 : sum / double(r.pixels.size());
}

}  // namespace

TEST_CASE("conformance: SpecularTest's highlight grows with the specular factor" *
          doctest::skip(!haveConformanceModel("SpecularTest"))) {
  const Scene scene = loadScene(conformanceGltf("SpecularTest"));
  CHECK(!ignores(scene, "KHR_materials_specular"));
  constexpr int kSize = 160;
  const Frame frame = renderFresh(scene, smallSettings(kSize, kSize));
  REQUIRE(!frame.specular.empty());
  // Row 1: black dielectric spheres (radius 0.05, roughness 0) with
  // specularFactor 0, 0.05, 0.21, 0.52, 1, at x = -0.44 .. 0 (+ 0.325, the
  // root's offset), y = 0.33.
  const float factors[] = {0.0f, 0.051269f, 0.212231f, 0.520996f, 1.0f};
  double previousMean = -1.0;
  float previousMax = -1.0f;
  for (int i = 0; i < 5; ++i) {
    CAPTURE(i);
    const Region sphere = near(frame, {0.325f - 0.44f + 0.11f * float(i), 0.33f, 0.0f}, 0.06f);
    REQUIRE(sphere.pixels.size() > 20);
    // The specular target holds the weight as the file gives it (half float).
    CHECK(meanOf(frame.specular, sphere, 3) == doctest::Approx(factors[i]).epsilon(2e-3).scale(1.0));
    CAPTURE(sphere.meanLuminance);
    CAPTURE(sphere.maxLuminance);
    // Black base colour and weight 0: nothing is reflected at all.
    if (i == 0) CHECK(sphere.maxLuminance < 1e-4f);
    // Each step up in the factor brightens the sphere, in its mean and in its highlight.
    CHECK(sphere.meanLuminance > previousMean * 1.5);
    CHECK(sphere.maxLuminance > previousMax * 1.5f);
    previousMean = sphere.meanLuminance;
    previousMax = sphere.maxLuminance;
  }
  // Row 7: specularColorFactor 0, 1.184, 5.441, 13.276, 25 times F0 0.04 is
  // clamped to 1 (the last two spheres: 0.53 and 1).
  const float f0[] = {0.0f, 0.04736f, 0.21764f, 0.53104f, 1.0f};
  for (int i = 0; i < 5; ++i) {
    CAPTURE(i);
    const Region sphere = near(frame, {0.325f - 0.44f + 0.11f * float(i), -0.33f, 0.0f}, 0.06f);
    REQUIRE(sphere.pixels.size() > 20);
    CHECK(meanOf(frame.specular, sphere, 0) == doctest::Approx(f0[i]).epsilon(2e-3).scale(1.0));
  }
  // Rows 3 and 5 at factor 1: a yellow specular colour (1, 1, 0) against a
  // white one reflects the same red and less blue. Not none: Schlick's
  // grazing term (F90 = 1) is the same for every channel (specification).
  const Region white = near(frame, {0.325f, 0.11f, 0.0f}, 0.06f), yellow = near(frame, {0.325f, -0.11f, 0.0f}, 0.06f);
  REQUIRE(white.pixels.size() > 20);
  REQUIRE(yellow.pixels.size() > 20);
  CAPTURE(meanOf(frame.lit, white, 2));
  CAPTURE(meanOf(frame.lit, yellow, 2));
  CHECK(meanOf(frame.lit, yellow, 0) == doctest::Approx(meanOf(frame.lit, white, 0)).epsilon(0.02));
  CHECK(meanOf(frame.lit, yellow, 2) < 0.75 * meanOf(frame.lit, white, 2));
}

TEST_CASE("conformance: ClearCoatTest's coated column outshines its base column in the highlight" *
          doctest::skip(!haveConformanceModel("ClearCoatTest"))) {
  const Scene scene = loadScene(conformanceGltf("ClearCoatTest"));
  CHECK(!ignores(scene, "KHR_materials_clearcoat"));
  constexpr int kSize = 128;
  const Frame frame = renderFresh(scene, smallSettings(kSize, kSize));
  REQUIRE(!frame.clearcoat.empty());
  // Each row's samples are 2 x 2 tiles at x = -2.1 (base layer), 0 (coated)
  // and 2.1 (coating only); row 0 ("simple coating") at y = 5.25.
  auto sample = [&](float column, float row) {
    return region(frame, [=](glm::vec3 p) { return std::abs(p.x - column) < 0.95f && std::abs(p.y - row) < 0.95f; });
  };
  const Region base = sample(-2.1f, 5.25f), coated = sample(0.0f, 5.25f);
  REQUIRE(base.pixels.size() > 50);
  REQUIRE(coated.pixels.size() > 50);
  // The clearcoat target: factor 1 and roughness 0.03 on the coated sample, 0 on its base.
  CHECK(meanOf(frame.clearcoat, coated, 0) == doctest::Approx(1.0).epsilon(2e-3));
  CHECK(meanOf(frame.clearcoat, coated, 1) == doctest::Approx(0.03).epsilon(2e-2));
  CHECK(meanOf(frame.clearcoat, base, 0) == 0.0);
  CAPTURE(base.maxLuminance);
  CAPTURE(coated.maxLuminance);
  CAPTURE(base.meanLuminance);
  CAPTURE(coated.meanLuminance);
  CHECK(coated.maxLuminance > 1.1f * base.maxLuminance);
  CHECK(coated.meanLuminance > 1.1 * base.meanLuminance);
  // Row 1 ("partial coating"): the coat's texture (R) turns it off in parts.
  const Region partial = sample(0.0f, 3.15f);
  REQUIRE(partial.pixels.size() > 50);
  int on = 0, off = 0;
  for (const auto& [x, y] : partial.pixels) (frame.clearcoat.at(x, y, 0) > 0.9f ? on : off) += 1;
  CAPTURE(on);
  CAPTURE(off);
  CHECK(on > int(partial.pixels.size()) / 10);
  CHECK(off > int(partial.pixels.size()) / 10);
}

TEST_CASE("conformance: TextureTransformMultiTest's clearcoat row is drawn, its transformed tiles as the sample" *
          doctest::skip(!haveConformanceModel("TextureTransformMultiTest"))) {
  const Scene scene = loadScene(conformanceGltf("TextureTransformMultiTest"));
  CHECK(!ignores(scene, "KHR_materials_clearcoat"));
  constexpr int kSize = 384;  // a tile is ~21 pixels wide
  const Frame frame = renderFresh(scene, smallSettings(kSize, kSize));
  REQUIRE(!frame.clearcoat.empty());
  // The clearcoat row (y = -0.75): tiles 0.2 wide at x = 0.1 (TEXCOORD_0
  // through a transform), 0.35 (TEXCOORD_1 through it) and 0.6 (the sample,
  // untransformed); the background plane lies at z = -0.025, behind them.
  struct Tile {
    int pixels = 0, coated = 0;
    glm::vec2 coatedCentroid{0.0f};                  // relative to the tile's centre, world units
    std::vector<std::pair<glm::vec2, bool>> points;  // each pixel's place in the tile (world) and whether coated
    double coatedLuminance = 0, bareLuminance = 0;
  };
  auto tile = [&](float column) {
    Tile t;
    const glm::vec2 center(column, -0.75f);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        if (frame.position.at(x, y, 3) == 0.0f) continue;
        const glm::vec3 p(frame.position.at(x, y, 0), frame.position.at(x, y, 1), frame.position.at(x, y, 2));
        if (p.z < -0.02f || std::abs(p.x - center.x) > 0.095f || std::abs(p.y - center.y) > 0.095f) continue;
        ++t.pixels;
        t.points.emplace_back(glm::vec2(p) - center, frame.clearcoat.at(x, y, 0) > 0.5f);
        if (frame.clearcoat.at(x, y, 0) > 0.5f) {
          ++t.coated;
          t.coatedCentroid += glm::vec2(p) - center;
          t.coatedLuminance += luminance(frame, x, y);
        } else {
          t.bareLuminance += luminance(frame, x, y);
        }
      }
    if (t.coated > 0) t.coatedCentroid /= float(t.coated), t.coatedLuminance /= t.coated;
    if (t.pixels > t.coated) t.bareLuminance /= t.pixels - t.coated;
    return t;
  };
  const Tile sample = tile(0.6f);
  REQUIRE(sample.pixels > 100);
  // The checkmark: coated in part, off-centre.
  CAPTURE(sample.pixels);
  CAPTURE(sample.coated);
  CAPTURE(sample.coatedCentroid.x);
  CAPTURE(sample.coatedCentroid.y);
  CHECK(sample.coated > sample.pixels / 20);
  CHECK(sample.coated < sample.pixels * 19 / 20);
  CHECK(glm::length(sample.coatedCentroid) > 0.005f);
  // Drawn: the coat reflects what the bare metal beside it does not.
  CAPTURE(sample.coatedLuminance);
  CAPTURE(sample.bareLuminance);
  CHECK(sample.coatedLuminance > 1.1 * sample.bareLuminance);
  for (float column : {0.1f, 0.35f}) {
    CAPTURE(column);
    const Tile transformed = tile(column);
    CAPTURE(transformed.pixels);
    CAPTURE(transformed.coated);
    CAPTURE(transformed.coatedCentroid.x);
    CAPTURE(transformed.coatedCentroid.y);
    MESSAGE("column " << column << ": " << transformed.coated << " of " << transformed.pixels << " coated, centroid ("
                      << transformed.coatedCentroid.x << ", " << transformed.coatedCentroid.y << "); sample "
                      << sample.coated << " of " << sample.pixels << ", (" << sample.coatedCentroid.x << ", "
                      << sample.coatedCentroid.y << ")");
    // The same checkmark at the same place: each pixel is coated as the
    // sample's point nearest to the same place in its tile, but where a
    // pixel straddles the mark's edge (rasterized at other sub-pixel offsets
    // and, in perspective, other parallax over the tiles' relief; 90 % agree
    // at 384 x 384 with llvmpipe): 85 %. An
    // untransformed texture shows a crossed-out circle instead (the model's
    // README). And its share of the tile within 4 %.
    int agree = 0;
    for (const auto& [place, coated] : transformed.points) {
      const auto nearest = std::min_element(
          sample.points.begin(), sample.points.end(),
          [&](const auto& a, const auto& b) { return glm::length(a.first - place) < glm::length(b.first - place); });
      agree += nearest->second == coated;
    }
    CAPTURE(agree);
    CHECK(agree > transformed.pixels * 85 / 100);
    CHECK(std::abs(double(transformed.coated) / transformed.pixels - double(sample.coated) / sample.pixels) < 0.04);
  }
}

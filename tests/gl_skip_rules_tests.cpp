// GL tests of the frame plan's skip rules: work a scene does not need is
// skipped, listed with its reason, and leaves the image unchanged.
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

namespace {

bool skips(const Frame& frame, std::string_view work, std::string_view reason = {}) {
  return std::any_of(frame.skipped.begin(), frame.skipped.end(), [&](const SkippedWork& skipped) {
    return skipped.work == work && skipped.reason.find(reason) != std::string::npos;
  });
}

float largestDifference(const ImageF& a, const ImageF& b) {
  REQUIRE(a.pixels.size() == b.pixels.size());
  float worst = 0;
  for (std::size_t i = 0; i < a.pixels.size(); ++i) worst = std::max(worst, std::abs(a.pixels[i] - b.pixels[i]));
  return worst;
}

}  // namespace

TEST_CASE("skip rules: work a scene does not need is skipped and listed, and the image is the unskipped one") {
  const RenderSettings settings = smallSettings(64, 48);
  SUBCASE("a scene with shadows, sky and emission skips nothing but the material lobes it lacks") {
    const Frame frame = renderFresh(loadScene("builtin:cornell"), settings);
    REQUIRE(frame.skipped.size() == 1);
    CHECK(frame.skipped[0].work == "lobes");
    CHECK(timed(frame, "shadows"));
    CHECK(!frame.emissive.empty());
  }
  SUBCASE("no shadow-casting light, sky intensity 0, no emission") {
    Scene scene = loadScene("builtin:spheres");
    for (Light& light : scene.lights) light.castsShadows = false;
    RenderSettings dark = settings;
    dark.lighting.skyIntensity = 0.0f;
    const Frame skipped = renderFresh(scene, dark);
    CHECK(skips(skipped, "shadows", "no light casts shadows"));
    CHECK(skips(skipped, "sky", "sky intensity 0"));
    CHECK(skips(skipped, "emissive", "no material emits"));
    CHECK(!timed(skipped, "shadows"));
    CHECK(!timed(skipped, "sky"));
    CHECK(skipped.emissive.empty());
    // The unskipped path with a sky too faint to count: 1e-30 of a radiance
    // of order 1 is below half's smallest subnormal (6e-8), so the lit
    // targets (half on the GPU) must agree exactly; 1e-6 allows nothing
    // visible.
    dark.lighting.skyIntensity = 1e-30f;
    const Frame full = renderFresh(scene, dark);
    CHECK(!skips(full, "sky"));
    CHECK(largestDifference(skipped.lit, full.lit) <= 1e-6f);
    CHECK(largestDifference(skipped.ssgi, full.ssgi) <= 1e-6f);
  }
  SUBCASE("ssgi alone: the bitmask method still gets its direct light, and the same SSGI as a full frame") {
    Renderer renderer(sharedContext());
    renderer.setScene(loadScene("builtin:cornell"));
    const Frame full = renderer.render(settings);
    const std::vector<std::string> onlySsgi{"ssgi"};
    Renderer fresh(sharedContext());  // no direct light left over from a full frame
    fresh.setScene(loadScene("builtin:cornell"));
    const Frame alone = fresh.render(settings, nullptr, onlySsgi);
    CHECK(skips(alone, "composite", "lit not asked for"));
    CHECK(!skips(alone, "direct"));
    CHECK(alone.lit.empty());
    CHECK(largestDifference(alone.ssgi, full.ssgi) <= 1e-6f);
  }
  SUBCASE("the emissive target asked for by name in a scene without emission: zeros") {
    Renderer renderer(sharedContext());
    renderer.setScene(loadScene("builtin:spheres"));
    const std::vector<std::string> targets{"emissive", "lit"};
    const Frame frame = renderer.render(settings, nullptr, targets);
    CHECK(skips(frame, "emissive"));
    REQUIRE(frame.emissive.width == 64);
    REQUIRE(frame.emissive.channelCount() == 3);
    CHECK(*std::max_element(frame.emissive.pixels.begin(), frame.emissive.pixels.end()) == 0.0f);
    CHECK(*std::min_element(frame.emissive.pixels.begin(), frame.emissive.pixels.end()) == 0.0f);
  }
}

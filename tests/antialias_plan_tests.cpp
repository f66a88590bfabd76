// Antialiasing's plan and sample pattern (lib/frame/antialias.hpp,
// AntialiasStep in lib/frame/frame_plan.hpp), without GL.
#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <vector>

#include "frame/antialias.hpp"
#include "frame/frame_plan.hpp"
#include "support/plan_settings.hpp"

namespace headlight {
namespace {

SceneSummary plainScene() {
  SceneSummary scene;
  scene.planarShadowCasters = 1;
  return scene;
}

}  // namespace

TEST_CASE("antialias: the samples centre on the pixel, stay near it and stratify it") {
  for (int count : {1, 2, 3, 4, 5, 8, 16, 64}) {
    CAPTURE(count);
    std::vector<glm::vec2> offsets;
    glm::dvec2 mean(0.0);
    for (int index = 0; index < count; ++index) {
      offsets.push_back(antialiasOffset(index, count));
      mean += glm::dvec2(offsets.back());
      // Within the pixel, moved by the mean (at most 0.19 px for these counts).
      CHECK(std::abs(offsets.back().x) < 0.7f);
      CHECK(std::abs(offsets.back().y) < 0.7f);
    }
    mean /= double(count);
    CHECK(std::abs(mean.x) < 1e-6);
    CHECK(std::abs(mean.y) < 1e-6);
    // Spread evenly: no two closer than 0.6 / sqrt(count) (the R2 sequence's
    // points keep 0.63-0.86; 16 random points would share a spot).
    for (int i = 0; i < count; ++i)
      for (int j = 0; j < i; ++j) CHECK(glm::distance(offsets[i], offsets[j]) >= 0.6f / std::sqrt(float(count)));
  }
  CHECK(antialiasOffset(0, 1) == glm::vec2(0.0f));
  // Four samples: one in each quadrant, each in its own quarter of x and of y.
  std::set<std::pair<bool, bool>> quadrants;
  std::set<int> columns, rows;
  for (int index = 0; index < 4; ++index) {
    const glm::vec2 offset = antialiasOffset(index, 4);
    quadrants.insert({offset.x > 0.0f, offset.y > 0.0f});
    columns.insert(int(std::floor((offset.x + 0.5f) * 4.0f)));
    rows.insert(int(std::floor((offset.y + 0.5f) * 4.0f)));
  }
  CHECK(quadrants.size() == 4);
  CHECK(columns.size() == 4);
  CHECK(rows.size() == 4);
}

TEST_CASE("antialias: a jittered view moves every point by the offset in pixels, perspective and orthographic") {
  for (bool orthographic : {false, true}) {
    CAPTURE(orthographic);
    CameraView view;
    view.orthographic = orthographic;
    view.projection = orthographic ? glm::mat4(glm::vec4(0.5f, 0, 0, 0), glm::vec4(0, 0.5f, 0, 0),
                                               glm::vec4(0, 0, -0.1f, 0), glm::vec4(0, 0, -1.0f, 1))
                                   : glm::mat4(glm::vec4(1.2f, 0, 0, 0), glm::vec4(0, 1.6f, 0, 0),
                                               glm::vec4(0, 0, -1.02f, -1), glm::vec4(0, 0, -0.2f, 0));
    const int width = 64, height = 48;
    const glm::vec2 offset(0.25f, -0.375f);
    const CameraView jittered = jitteredView(view, offset, width, height);
    for (const glm::vec4 point : {glm::vec4(0.3f, -0.2f, -2.0f, 1), glm::vec4(-1.0f, 0.7f, -5.0f, 1)}) {
      const glm::vec4 a = view.projection * point, b = jittered.projection * point;
      const glm::vec2 pixelA = (glm::vec2(a) / a.w * 0.5f + 0.5f) * glm::vec2(width, height);
      const glm::vec2 pixelB = (glm::vec2(b) / b.w * 0.5f + 0.5f) * glm::vec2(width, height);
      CHECK(pixelB.x - pixelA.x == doctest::Approx(offset.x).epsilon(1e-4));
      CHECK(pixelB.y - pixelA.y == doctest::Approx(offset.y).epsilon(1e-4));
      CHECK(b.z / b.w == doctest::Approx(a.z / a.w));  // depth unmoved
    }
    CHECK(jittered.view == view.view);
  }
}

TEST_CASE("antialias: the plan draws each sample's geometry and light again, reuses the SSGI, and reads lit last") {
  RenderSettings settings = test::resolvedPlanSettings();
  REQUIRE(settings.antialiasSamples == 8);  // the default
  FramePlan plan = planFrame(plainScene(), settings, {});
  REQUIRE(plan.antialias);
  CHECK(plan.antialias->samples == 8);
  CHECK(!plan.antialias->ssgiPerSample);
  std::vector<std::string_view> perSample;
  for (std::size_t index : plan.antialias->perSamplePasses)
    perSample.push_back(fullscreenPassRows()[plan.passes[index].row].name);
  CHECK(perSample == std::vector<std::string_view>{"direct", "composite"});
  CHECK(plan.antialias->accumulate.readsAttachment(Attachment::Lit));
  CHECK(plan.antialias->accumulate.writes == std::vector<Attachment>{Attachment::LitAccumulation});
  CHECK(plan.allocates(Attachment::LitAccumulation));
  CHECK(!plan.antialias->foreground);  // the preview shows lit as it is, sky and all
  CHECK(!plan.allocates(Attachment::LitForeground));
  for (const TargetRead& read : plan.reads) {
    CAPTURE(read.target->name);
    const bool lit = read.target->name == "lit";
    CHECK(read.afterAntialias == lit);
    if (lit) CHECK(read.sources == std::vector<Attachment>{Attachment::LitAccumulation});
  }

  // A preview over a colour or transparent: the foreground is accumulated beside lit.
  for (const char* background : {"transparent", "#3060a0"}) {
    RenderSettings over = settings;
    over.previewBackground = background;
    const FramePlan withForeground = planFrame(plainScene(), over, {});
    REQUIRE(withForeground.antialias);
    CHECK(withForeground.antialias->foreground);
    CHECK(withForeground.antialias->accumulate.writes ==
          std::vector<Attachment>{Attachment::LitAccumulation, Attachment::LitForeground});
    CHECK(withForeground.allocates(Attachment::LitForeground));
  }

  // antialias-ssgi: every pass again, the SSGI's included.
  settings.antialiasSsgi = true;
  plan = planFrame(plainScene(), settings, {});
  REQUIRE(plan.antialias);
  CHECK(plan.antialias->ssgiPerSample);
  CHECK(plan.antialias->perSamplePasses.size() == plan.passes.size());

  // One sample, or no lit asked for: no step, no accumulation, lit from its own attachment.
  settings.antialiasSamples = 1;
  plan = planFrame(plainScene(), settings, {});
  CHECK(!plan.antialias);
  CHECK(!plan.allocates(Attachment::LitAccumulation));
  for (const TargetRead& read : plan.reads) CHECK(!read.afterAntialias);
  settings.antialiasSamples = 8;
  const std::string depthOnly[] = {"depth", "normal"};
  plan = planFrame(plainScene(), settings, depthOnly);
  CHECK(!plan.antialias);
  CHECK(!plan.allocates(Attachment::LitAccumulation));
}

}  // namespace headlight

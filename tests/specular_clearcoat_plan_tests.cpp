// The frame plan of the specular and clearcoat lobes, without a GL context:
// their attachments, locations, defines and targets exist only for scenes
// that use them (issue 18: a scene without a lobe pays nothing for it).
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "frame/frame_plan.hpp"
#include "headlight/targets.hpp"
#include "support/plan_settings.hpp"

namespace headlight {
namespace {

using test::readOf;

bool has(const std::vector<std::string>& defines, std::string_view define) {
  return std::find(defines.begin(), defines.end(), define) != defines.end();
}

}  // namespace

TEST_CASE("lobes plan: without the lobes, no attachment, define or target") {
  const FramePlan plan = planFrame(SceneSummary{}, test::resolvedPlanSettings(), {});
  CHECK(!plan.allocates(lobeAttachment(Lobe::Specular)));
  CHECK(!plan.allocates(lobeAttachment(Lobe::Clearcoat)));
  CHECK(plan.gbuffer.lobes == 0);
  CHECK(plan.direct->lobes == 0);
  CHECK(plan.composite->lobes == 0);
  CHECK(readOf(plan, "specular") == nullptr);
  CHECK(readOf(plan, "clearcoat") == nullptr);
}

TEST_CASE("lobes plan: each lobe gets its attachment at the next location, its defines, and its target") {
  SceneSummary scene;
  scene.emissive = true;
  scene.lobes = lobeBit(Lobe::Specular) | lobeBit(Lobe::Clearcoat);
  const FramePlan plan = planFrame(scene, test::resolvedPlanSettings(), {});
  CHECK(plan.allocates(lobeAttachment(Lobe::Specular)));
  CHECK(plan.allocates(lobeAttachment(Lobe::Clearcoat)));
  // Position, normal, albedo, material, emissive, then the lobes in row order.
  CHECK(plan.gbuffer.colorAttachments ==
        std::vector<Attachment>{Attachment::GbufferPosition, Attachment::GbufferNormal, Attachment::GbufferAlbedo,
                                Attachment::GbufferMaterial, Attachment::GbufferEmissive,
                                lobeAttachment(Lobe::Specular), lobeAttachment(Lobe::Clearcoat),
                                Attachment::GbufferIds});
  for (const char* define : {"HAS_SPECULAR_TARGET", "SPECULAR_TARGET_LOCATION 5", "HAS_CLEARCOAT_TARGET",
                             "CLEARCOAT_TARGET_LOCATION 6", "HAS_SPECULAR_LOBE", "HAS_CLEARCOAT_LOBE"}) {
    CAPTURE(define);
    CHECK(has(plan.gbuffer.defines, define));
  }
  CHECK(plan.direct->lobes == scene.lobes);
  CHECK(plan.composite->lobes == scene.lobes);
  // Half floats: a dielectric F0 of 0.04 would lose 10 % to one 8-bit step.
  CHECK(plan.formatOf(lobeAttachment(Lobe::Specular)) == GpuFormat::Rgba16F);
  CHECK(plan.formatOf(lobeAttachment(Lobe::Clearcoat)) == GpuFormat::Rgba16F);
  REQUIRE(readOf(plan, "specular"));
  CHECK(readOf(plan, "specular")->sources == std::vector<Attachment>{lobeAttachment(Lobe::Specular)});
  CHECK(readOf(plan, "specular")->channels ==
        std::vector<std::string>{"specularF0.R", "specularF0.G", "specularF0.B", "specular"});
  REQUIRE(readOf(plan, "clearcoat"));
  CHECK(readOf(plan, "clearcoat")->channels ==
        std::vector<std::string>{"clearcoat", "clearcoatRoughness", "clearcoatNormal.U", "clearcoatNormal.V"});
  // Each target has its tolerance row (diff thresholds and the reason).
  for (const char* name : {"specular", "clearcoat"}) {
    CAPTURE(name);
    REQUIRE(findFrameTarget(name));
    CHECK(findFrameTarget(name)->thresholds.fail > 0.0);
    CHECK(!findFrameTarget(name)->reason.empty());
  }
}

TEST_CASE("lobes plan: only the clearcoat, and only G-buffer targets asked for") {
  SceneSummary scene;
  scene.lobes = lobeBit(Lobe::Clearcoat);
  const std::vector<std::string> targets{"clearcoat"};
  const FramePlan plan = planFrame(scene, test::resolvedPlanSettings(), targets);
  CHECK(!plan.allocates(lobeAttachment(Lobe::Specular)));
  CHECK(plan.allocates(lobeAttachment(Lobe::Clearcoat)));
  CHECK(has(plan.gbuffer.defines, "CLEARCOAT_TARGET_LOCATION 4"));
  CHECK(!has(plan.gbuffer.defines, "HAS_SPECULAR_LOBE"));
  CHECK(!plan.direct);
  REQUIRE(plan.reads.size() == 1);
  CHECK(plan.reads[0].target->name == "clearcoat");
}

}  // namespace headlight

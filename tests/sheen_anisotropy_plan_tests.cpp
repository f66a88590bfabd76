// The frame plan of the sheen and anisotropy lobes, without GL: a scene
// without them allocates no lobe attachment and builds no lobe code; with
// them, each gets an attachment at the next G-buffer location, its define
// in every lighting pass's variant, and its target read back.
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

bool defines(const FramePlan& plan, const std::string& define) {
  const std::vector<std::string>& all = plan.gbuffer.defines;
  return std::find(all.begin(), all.end(), define) != all.end();
}

}  // namespace

TEST_CASE("lobes: a scene without sheen or anisotropy pays nothing for them") {
  const FramePlan plan = planFrame(SceneSummary{}, test::resolvedPlanSettings(), {});
  CHECK(!plan.allocates(lobeAttachment(Lobe::Sheen)));
  CHECK(!plan.allocates(lobeAttachment(Lobe::Anisotropy)));
  CHECK(plan.gbuffer.lobes == 0);
  CHECK(plan.gbuffer.colorAttachments.size() == 5);  // the four fixed ones and ids
  CHECK(!defines(plan, "HAS_SHEEN_LOBE"));
  REQUIRE(plan.direct);
  REQUIRE(plan.composite);
  CHECK(plan.direct->lobes == 0);
  CHECK(plan.composite->lobes == 0);
  CHECK(readOf(plan, "sheen") == nullptr);
  CHECK(readOf(plan, "anisotropy") == nullptr);
}

TEST_CASE("lobes: sheen and anisotropy get an attachment each, their defines and their targets") {
  SceneSummary scene;
  scene.lobes = lobeBit(Lobe::Sheen) | lobeBit(Lobe::Anisotropy);
  const FramePlan plan = planFrame(scene, test::resolvedPlanSettings(), {});
  CHECK(plan.allocates(lobeAttachment(Lobe::Sheen)));
  CHECK(plan.allocates(lobeAttachment(Lobe::Anisotropy)));
  CHECK(plan.formatOf(lobeAttachment(Lobe::Sheen)) == GpuFormat::Srgb8Alpha8);
  CHECK(plan.formatOf(lobeAttachment(Lobe::Anisotropy)) == GpuFormat::Rgba16F);
  // After the four fixed attachments (no emission here), in row order.
  CHECK(plan.gbuffer.colorAttachments ==
        std::vector<Attachment>{Attachment::GbufferPosition, Attachment::GbufferNormal, Attachment::GbufferAlbedo,
                                Attachment::GbufferMaterial, lobeAttachment(Lobe::Sheen),
                                lobeAttachment(Lobe::Anisotropy), Attachment::GbufferIds});
  CHECK(defines(plan, "HAS_SHEEN_TARGET"));
  CHECK(defines(plan, "SHEEN_TARGET_LOCATION 4"));
  CHECK(defines(plan, "HAS_ANISOTROPY_TARGET"));
  CHECK(defines(plan, "ANISOTROPY_TARGET_LOCATION 5"));
  CHECK(defines(plan, "HAS_SHEEN_LOBE"));
  CHECK(defines(plan, "HAS_ANISOTROPY_LOBE"));
  REQUIRE(plan.direct);
  REQUIRE(plan.composite);
  CHECK(plan.direct->lobes == scene.lobes);
  CHECK(plan.composite->lobes == scene.lobes);
  const TargetRead* sheen = readOf(plan, "sheen");
  const TargetRead* anisotropy = readOf(plan, "anisotropy");
  REQUIRE(sheen);
  REQUIRE(anisotropy);
  CHECK(sheen->channels == std::vector<std::string>{"sheen.R", "sheen.G", "sheen.B", "sheenRoughness"});
  CHECK(anisotropy->channels ==
        std::vector<std::string>{"anisotropy.X", "anisotropy.Y", "anisotropy.Z", "anisotropyStrength"});
  // Each row says why its diff tolerance is what it is.
  CHECK(!sheen->target->reason.empty());
  CHECK(!anisotropy->target->reason.empty());
}

}  // namespace headlight

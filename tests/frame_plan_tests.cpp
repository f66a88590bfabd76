// The frame plan and resolve's auto values, without a GL context: what a
// frame runs, allocates and reads back for a scene, its settings and the
// targets asked for.
#include <doctest/doctest.h>

#include <algorithm>
#include <string>
#include <vector>

#include "frame/frame_plan.hpp"
#include "frame/resolve.hpp"
#include "headlight/scene_builder.hpp"
#include "headlight/shapes.hpp"
#include "headlight/targets.hpp"
#include "scene/ids.hpp"
#include "support/plan_settings.hpp"

namespace headlight {
namespace {

using test::readOf;
using test::skips;

SceneSummary litScene() {
  SceneSummary scene;
  scene.planarShadowCasters = 1;
  return scene;
}

}  // namespace

TEST_CASE("frame plan: the default frame runs every pass and reads every target it draws") {
  const FramePlan plan = planFrame(litScene(), test::resolvedPlanSettings(), {});
  CHECK(plan.skipped.size() == 2);  // emissive: the scene has no emission; it has no KHR_materials_* lobe
  CHECK(skips(plan, "emissive", "no material emits"));
  CHECK(skips(plan, "lobes",
              "no material uses specular (KHR_materials_specular, _ior), clearcoat, sheen, anisotropy, "
              "iridescence (no attachment, no shader code)"));
  CHECK(!skips(plan, "blend"));  // no BLEND material: no blend pass, and nothing to list
  CHECK(!plan.blend);
  CHECK(!plan.allocates(Attachment::BlendCoverage));
  CHECK(readOf(plan, "coverage") == nullptr);
  REQUIRE(plan.shadows);
  CHECK(plan.shadows->mapSize == 1024);
  REQUIRE(plan.direct);
  CHECK(*plan.direct ==
        DirectLightVariant{.shadows = {.planar = true}, .diffuseTarget = true});  // bitmask gathers direct light
  REQUIRE(plan.ssgi);
  CHECK(plan.ssgi->method->method == SsgiMethod::Bitmask);
  CHECK(plan.ssgi->blur);
  CHECK(plan.skyTables);
  REQUIRE(plan.composite);
  CHECK(*plan.composite == CompositeVariant{.ssgi = true, .sky = true});
  CHECK(plan.passNames() == std::vector<std::string_view>{"shadows", "virtual-lights", "sky", "gbuffer", "direct",
                                                          "ssgi-surface", "ssgi", "ssgi-blur", "composite", "antialias",
                                                          "readback"});
  CHECK(!plan.allocates(Attachment::GbufferEmissive));
  CHECK(plan.allocates(Attachment::SsgiRaw));
  // The one optional attachment: ids, wanted with every target.
  CHECK(plan.gbuffer.defines == std::vector<std::string>{"HAS_IDS_TARGET", "IDS_TARGET_LOCATION 4"});
  CHECK(readOf(plan, "emissive") == nullptr);  // not drawn, not named: not written
  const TargetRead* ssgi = readOf(plan, "ssgi");
  REQUIRE(ssgi);
  CHECK(ssgi->sources == std::vector<Attachment>{Attachment::Ssgi, Attachment::SsgiSky, Attachment::SsgiSpecular});
  for (const char* name : {"position", "normal", "albedo", "material", "depth", "lit"}) CHECK(readOf(plan, name));
}

TEST_CASE("frame plan: a scene that blends gets the blend pass after the composite, and the coverage target") {
  SceneSummary scene = litScene();
  scene.blended = true;
  FramePlan plan = planFrame(scene, test::resolvedPlanSettings(), {});
  REQUIRE(plan.blend);
  CHECK(*plan.blend ==
        BlendVariant{.shadows = {.planar = true}, .sky = true});  // the planar caster's map, the sky term, no map
  CHECK(!skips(plan, "blend"));
  CHECK(plan.passNames() == std::vector<std::string_view>{"shadows", "virtual-lights", "sky", "gbuffer", "direct",
                                                          "ssgi-surface", "ssgi", "ssgi-blur", "composite", "blend",
                                                          "antialias", "readback"});
  CHECK(plan.allocates(Attachment::BlendCoverage));
  CHECK(plan.allocates(Attachment::Lit));
  const TargetRead* coverage = readOf(plan, "coverage");
  REQUIRE(coverage);
  CHECK(coverage->sources == std::vector<Attachment>{Attachment::BlendCoverage});
  // It follows the composite's choices: no shadows, no sky.
  RenderSettings settings = test::resolvedPlanSettings();
  settings.lighting.shadows = false;
  settings.lighting.skyIntensity = 0.0f;
  plan = planFrame(scene, settings, {});
  REQUIRE(plan.blend);
  CHECK(*plan.blend == BlendVariant{});
  // Without lit there is nothing to blend over.
  const std::vector<std::string> gbufferOnly{"albedo", "coverage"};
  plan = planFrame(scene, test::resolvedPlanSettings(), gbufferOnly);
  CHECK(!plan.blend);
  CHECK(skips(plan, "blend", "lit not asked for"));
  CHECK(!plan.allocates(Attachment::BlendCoverage));
  CHECK(readOf(plan, "coverage") == nullptr);
}

TEST_CASE("frame plan: an emissive scene gets the emissive attachment, its define and its target") {
  SceneSummary scene = litScene();
  scene.emissive = true;
  const FramePlan plan = planFrame(scene, test::resolvedPlanSettings(), {});
  CHECK(plan.allocates(Attachment::GbufferEmissive));
  CHECK(plan.gbuffer.defines == std::vector<std::string>{"HAS_EMISSIVE_TARGET", "EMISSIVE_TARGET_LOCATION 4",
                                                         "HAS_IDS_TARGET", "IDS_TARGET_LOCATION 5"});
  CHECK(plan.gbuffer.colorAttachments.at(4) == Attachment::GbufferEmissive);
  CHECK(plan.direct->emissive);
  REQUIRE(readOf(plan, "emissive"));
  CHECK(readOf(plan, "emissive")->sources == std::vector<Attachment>{Attachment::GbufferEmissive});
}

TEST_CASE("frame plan: the ids target is the G-buffer's last attachment, only when wanted and when it fits") {
  SceneSummary scene = litScene();
  FramePlan plan = planFrame(scene, test::resolvedPlanSettings(), {});
  REQUIRE(plan.allocates(Attachment::GbufferIds));
  CHECK(plan.gbuffer.colorAttachments.back() == Attachment::GbufferIds);
  CHECK(plan.formatOf(Attachment::GbufferIds) == GpuFormat::Rgba32Ui);
  REQUIRE(readOf(plan, "ids"));
  CHECK(readOf(plan, "ids")->sources == std::vector<Attachment>{Attachment::GbufferIds});
  CHECK(readOf(plan, "ids")->channels ==
        std::vector<std::string>{"instance.id", "mesh.id", "material.id", "primitive.id"});

  // Not asked for: no attachment, no define.
  const std::vector<std::string> litOnly{"lit"};
  plan = planFrame(scene, test::resolvedPlanSettings(), litOnly);
  CHECK(!plan.allocates(Attachment::GbufferIds));
  CHECK(std::find(plan.gbuffer.defines.begin(), plan.gbuffer.defines.end(), "HAS_IDS_TARGET") ==
        plan.gbuffer.defines.end());

  // Every lobe and emission take GL's 8 attachments: lit keeps them, ids is named.
  scene.emissive = true;
  scene.lobes = lobeBit(Lobe::Count) - 1;
  plan = planFrame(scene, test::resolvedPlanSettings(), {});
  CHECK(!plan.allocates(Attachment::GbufferIds));
  CHECK(plan.gbuffer.colorAttachments.size() == kMaxGbufferColorAttachments);
  CHECK(skips(plan, "gbuffer.ids", "no colour attachment left"));

  // More of one kind than a float holds exactly: named, not rounded.
  scene = litScene();
  scene.largestId = kLargestExactId + 1;
  plan = planFrame(scene, test::resolvedPlanSettings(), {});
  CHECK(!plan.allocates(Attachment::GbufferIds));
  CHECK(skips(plan, "gbuffer.ids", "beyond what a float holds exactly"));
  REQUIRE(!plan.unrendered.empty());
  CHECK(plan.unrendered.back().find("ids is not rendered") != std::string::npos);
}

TEST_CASE("frame plan: the emissive target asked for by name without emission is written as zeros") {
  const std::vector<std::string> targets{"emissive"};
  const FramePlan plan = planFrame(litScene(), test::resolvedPlanSettings(), targets);
  REQUIRE(readOf(plan, "emissive"));
  CHECK(readOf(plan, "emissive")->sources.empty());
  CHECK(plan.reads.size() == 1);
}

TEST_CASE("frame plan: G-buffer targets alone need neither light nor SSGI") {
  const std::vector<std::string> targets{"normal", "depth"};
  const FramePlan plan = planFrame(litScene(), test::resolvedPlanSettings(), targets);
  CHECK(!plan.shadows);
  CHECK(!plan.direct);
  CHECK(!plan.ssgi);
  CHECK(!plan.composite);
  CHECK(skips(plan, "direct", "only G-buffer targets"));
  CHECK(skips(plan, "ssgi", "neither ssgi nor lit"));
  for (Attachment id : {Attachment::DirectTowardEye, Attachment::DirectDiffuse, Attachment::Ssgi, Attachment::Lit})
    CHECK(!plan.allocates(id));
  CHECK(plan.reads.size() == 2);
}

TEST_CASE("frame plan: ssgi alone needs no composite, but the direct light it gathers") {
  const std::vector<std::string> targets{"ssgi"};
  const FramePlan plan = planFrame(litScene(), test::resolvedPlanSettings(), targets);
  CHECK(plan.ssgi);
  REQUIRE(plan.direct);
  CHECK(plan.direct->diffuseTarget);
  CHECK(!plan.composite);
  CHECK(!plan.skyTables);
  CHECK(!plan.allocates(Attachment::Lit));
}

TEST_CASE("frame plan: each SSGI method's row decides the direct light, the blur attachments and the frames") {
  RenderSettings settings = test::resolvedPlanSettings();
  settings.ssgi.frames = 4;
  settings.ssgi.method = SsgiMethod::Hemisphere;
  FramePlan plan = planFrame(litScene(), settings, {});
  CHECK(!plan.direct->diffuseTarget);
  CHECK(!plan.allocates(Attachment::DirectDiffuse));
  CHECK(plan.ssgi->frames == 1);  // the kernel methods do not accumulate
  settings.ssgi.method = SsgiMethod::Bitmask;
  CHECK(planFrame(litScene(), settings, {}).ssgi->frames == 4);
  settings.ssgi.blur = false;
  plan = planFrame(litScene(), settings, {});
  CHECK(!plan.allocates(Attachment::SsgiRaw));
  CHECK(plan.passNames() == std::vector<std::string_view>{"shadows", "virtual-lights", "sky", "gbuffer", "direct",
                                                          "ssgi-surface", "ssgi", "composite", "antialias",
                                                          "readback"});
  settings.ssgi.enabled = false;
  plan = planFrame(litScene(), settings, {});
  CHECK(!plan.ssgi);
  CHECK(!plan.direct->diffuseTarget);
  CHECK(*plan.composite == CompositeVariant{.sky = true});
  CHECK(skips(plan, "ssgi", "setting ssgi is off"));
  CHECK(readOf(plan, "ssgi") == nullptr);
}

TEST_CASE("frame plan: no shadow caster, shadows off, sky intensity 0") {
  RenderSettings settings = test::resolvedPlanSettings();
  FramePlan plan = planFrame(SceneSummary{}, settings, {});
  CHECK(!plan.shadows);
  CHECK(!plan.dropShadowMaps);
  CHECK(skips(plan, "shadows", "no light casts shadows"));
  CHECK(!plan.direct->shadows.planar);
  settings.lighting.shadows = false;
  plan = planFrame(litScene(), settings, {});
  CHECK(plan.dropShadowMaps);
  CHECK(skips(plan, "shadows", "setting shadows is off"));
  CHECK(!plan.direct->shadows.planar);
  settings.lighting.skyIntensity = 0.0f;
  plan = planFrame(litScene(), settings, {});
  CHECK(!plan.skyTables);
  CHECK(!plan.composite->sky);
  CHECK(skips(plan, "sky", "sky intensity 0"));
}

TEST_CASE("frame plan: every frame target is held by attachments, and the SSGI table covers every method") {
  for (std::size_t i = 0; i < kAttachmentCount; ++i) CHECK(std::size_t(attachmentRows()[i].id) == i);
  for (const AttachmentRow& row : attachmentRows()) {
    if (!row.target) continue;
    const auto targets = frameTargets();
    CHECK_MESSAGE(
        std::any_of(targets.begin(), targets.end(), [&](const FrameTarget& t) { return t.image == row.target; }),
        row.name);
  }
  // Every target a frame can have is held by some attachment.
  for (const FrameTarget& target : frameTargets()) {
    if (!target.image) continue;
    const auto rows = attachmentRows();
    CHECK_MESSAGE(
        std::any_of(rows.begin(), rows.end(), [&](const AttachmentRow& row) { return row.target == target.image; }),
        target.name);
  }
  // G-buffer locations are distinct.
  std::vector<int> locations;
  for (const AttachmentRow& row : attachmentRows())
    if (row.gbufferLocation >= 0) locations.push_back(row.gbufferLocation);
  std::sort(locations.begin(), locations.end());
  CHECK(std::adjacent_find(locations.begin(), locations.end()) == locations.end());
  for (SsgiMethod method : {SsgiMethod::Hemisphere, SsgiMethod::Radiance, SsgiMethod::Bitmask})
    CHECK(ssgiMethodTraits(method).method == method);
}

TEST_CASE("resolve: auto values come from the scene and the image size") {
  Scene scene;
  addInstance(scene, makeBox(glm::vec3(2.0f)), addMaterial(scene, Material{}));
  RenderSettings settings;
  settings.width = 300;
  settings.height = 200;
  const RenderSettings used = resolveSettings(settings, scene);
  const float diagonal = 2.0f * scene.worldBounds().radius();
  CHECK(*used.ssgi.radius == doctest::Approx(settings.ssgi.radiusFraction * diagonal));
  CHECK(*used.ssgi.bias == doctest::Approx(SsgiSettings::kAutoBiasFraction * *used.ssgi.radius));
  CHECK(*used.lighting.shadowMapSize == 2048);  // 4 x 300 -> 2048
  CHECK(autoShadowMapSize(200, 10) == 1024);    // 4 x 200 -> 1024
  CHECK(autoShadowMapSize(64, 48) == 1024);     // the floor
  CHECK(autoShadowMapSize(5000, 10) == 2048);   // held at 2048
  CHECK(*used.lighting.skyIntensity == scene.sky.intensity);
  CHECK(*used.ssgi.indirectStrength == 1.0f);
  settings.ssgi.method = SsgiMethod::Hemisphere;
  CHECK(*resolveSettings(settings, scene).ssgi.indirectStrength == 0.5f);
  settings.ssgi.radius = 2.0f;  // a set value is kept
  CHECK(*resolveSettings(settings, scene).ssgi.radius == 2.0f);
  // A box 2 units deep: thickness 2/3 of its smallest side, held within the radius.
  CHECK(*resolveSettings(settings, scene).ssgi.thickness == doctest::Approx(4.0f / 3.0f));
}

TEST_CASE("frame plan: --verbose names the KHR_materials_* lobes a scene does not pay for, and only those") {
  SceneSummary scene = litScene();
  scene.lobes = lobeBit(Lobe::Clearcoat) | lobeBit(Lobe::Iridescence);
  const FramePlan plan = planFrame(scene, test::resolvedPlanSettings(), {});
  CHECK(skips(plan, "lobes", "no material uses specular (KHR_materials_specular, _ior), sheen, anisotropy ("));
  CHECK(!skips(plan, "lobes", "clearcoat"));
  CHECK(!skips(plan, "lobes", "iridescence"));
  scene.lobes = lobeBit(Lobe::Count) - 1;
  CHECK(!skips(planFrame(scene, test::resolvedPlanSettings(), {}), "lobes"));
}

}  // namespace headlight

namespace headlight {
namespace {

// Whether `plan` reads `id` back into a frame target.
bool readBack(const FramePlan& plan, Attachment id) {
  return std::any_of(plan.reads.begin(), plan.reads.end(), [&](const TargetRead& read) {
    return std::find(read.sources.begin(), read.sources.end(), id) != read.sources.end();
  });
}

}  // namespace

TEST_CASE("frame plan: the fullscreen passes' declarations give the allocations, in an order that works") {
  // Every combination of what decides them: method, blur, far field, virtual
  // lights, scene features and targets asked for.
  SceneSummary plain = litScene();
  SceneSummary rich = litScene();
  rich.emissive = rich.blended = rich.transmission = true;
  rich.lobes = lobeBit(Lobe::Clearcoat) | lobeBit(Lobe::Sheen);
  const std::vector<std::vector<std::string>> targetSets = {{}, {"lit"}, {"ssgi"}, {"depth"}, {"normal", "ssgi"}};
  int plans = 0;
  for (const SceneSummary& scene : {plain, rich})
    for (SsgiMethod method : {SsgiMethod::Hemisphere, SsgiMethod::Radiance, SsgiMethod::Bitmask})
      for (bool ssgi : {true, false})
        for (bool blur : {true, false})
          for (SsgiResolution far : {SsgiResolution::Full, SsgiResolution::Half})
            for (int virtualLights : {0, 16})
              for (const std::vector<std::string>& targets : targetSets) {
                RenderSettings settings = test::resolvedPlanSettings();
                settings.ssgi.method = method;
                settings.ssgi.enabled = ssgi;
                settings.ssgi.blur = blur;
                settings.ssgi.farResolution = far;
                settings.ssgi.virtualLightCount = virtualLights;
                CAPTURE(int(method));
                CAPTURE(ssgi);
                CAPTURE(blur);
                CAPTURE(int(far));
                CAPTURE(virtualLights);
                CAPTURE(targets.size());
                const FramePlan plan = planFrame(scene, settings, targets);
                ++plans;
                // The fullscreen passes are the plan's, in row order, each once.
                for (std::size_t i = 1; i < plan.passes.size(); ++i) CHECK(plan.passes[i - 1].row < plan.passes[i].row);
                // (The bitmask's marches read the packed surface, a pass of its own.)
                const bool bitmask = plan.ssgi && plan.ssgi->method->program == SsgiProgram::Bitmask;
                CHECK(plan.passes.size() == std::size_t(bool(plan.direct)) + std::size_t(bool(plan.ssgi)) +
                                                std::size_t(bitmask) + std::size_t(plan.ssgi && plan.ssgi->blur) +
                                                std::size_t(bool(plan.composite)));
                // Allocated exactly: what the G-buffer, a declared pass or a forward pass writes.
                for (const AttachmentRow& row : attachmentRows()) {
                  CAPTURE(row.name);
                  const bool gbuffer =
                      row.id == Attachment::GbufferDepth ||
                      std::find(plan.gbuffer.colorAttachments.begin(), plan.gbuffer.colorAttachments.end(), row.id) !=
                          plan.gbuffer.colorAttachments.end();
                  const bool declared =
                      std::any_of(plan.passes.begin(), plan.passes.end(),
                                  [&](const PassDeclaration& pass) { return pass.writesAttachment(row.id); });
                  const bool forward = (row.id == Attachment::BlendCoverage && plan.blend) ||
                                       (row.id == Attachment::Transmission && plan.transmission);
                  const bool antialias = plan.antialias && plan.antialias->accumulate.writesAttachment(row.id);
                  CHECK(plan.allocates(row.id) == (gbuffer || declared || forward || antialias));
                }
                // No pass runs for nothing: each writes something a later pass
                // reads or the frame reads back (lit: also what the forward passes draw over).
                for (std::size_t i = 0; i < plan.passes.size(); ++i) {
                  CAPTURE(fullscreenPassRows()[plan.passes[i].row].name);
                  const bool consumed =
                      std::any_of(plan.passes[i].writes.begin(), plan.passes[i].writes.end(), [&](Attachment id) {
                        return readBack(plan, id) ||
                               (plan.antialias && plan.antialias->accumulate.readsAttachment(id)) ||
                               std::any_of(plan.passes.begin() + std::ptrdiff_t(i) + 1, plan.passes.end(),
                                           [&](const PassDeclaration& later) { return later.readsAttachment(id); });
                      });
                  CHECK(consumed);
                }
              }
  CHECK(plans == 2 * 3 * 2 * 2 * 2 * 2 * 5);
}

TEST_CASE("frame plan: a pass that reads what no earlier pass writes is refused, naming both") {
  const FramePlan plan = planFrame(litScene(), test::resolvedPlanSettings(), {});
  // The composite moved ahead of the direct light it reads.
  const auto rows = fullscreenPassRows();
  const FullscreenPassRow reordered[] = {rows[fullscreenPassIndex("composite")], rows[fullscreenPassIndex("direct")]};
  CHECK_THROWS_WITH_AS(declareFullscreenPasses(plan, reordered),
                       "composite reads direct.towardEye, which neither the G-buffer nor an earlier pass writes",
                       std::logic_error);
  // In the table's order the same plan declares all five (direct, ssgi-surface, ssgi, ssgi-blur, composite).
  CHECK(declareFullscreenPasses(plan, rows).size() == 5);
  CHECK_THROWS_AS(fullscreenPassIndex("exposure"), std::out_of_range);
}

}  // namespace headlight

#include "frame/frame_plan.hpp"

#include <algorithm>
#include <cctype>
#include <stdexcept>

#include "scene/ids.hpp"
#include "settings/preview_background.hpp"
#include "shared_layout.h"

namespace headlight {

std::string_view passFormName(PassForm form) { return form == PassForm::Compute ? "compute" : "fragment"; }

std::size_t fullscreenPassIndex(std::string_view name) {
  const auto rows = fullscreenPassRows();
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i].name == name) return i;
  throw std::out_of_range("no fullscreen pass named " + std::string(name));
}

bool PassDeclaration::readsAttachment(Attachment id) const {
  return std::any_of(reads.begin(), reads.end(), [&](const PassRead& read) { return read.attachment == id; });
}
bool PassDeclaration::writesAttachment(Attachment id) const {
  return std::find(writes.begin(), writes.end(), id) != writes.end();
}

PassForms choosePassForms(std::optional<FullscreenForm> setting, bool softwareRasterizer) {
  PassForms forms;
  for (const FullscreenPassRow& row : fullscreenPassRows()) {
    PassForm& form = forms.emplace_back();
    if (setting)
      form = *setting == FullscreenForm::Compute ? PassForm::Compute : PassForm::Fragment;
    else
      form = softwareRasterizer ? row.softwareForm : PassForm::Compute;
  }
  return forms;
}

bool isSoftwareRasterizer(std::string_view glRenderer) {
  for (std::string_view name : {"llvmpipe", "softpipe", "swrast", "SwiftShader", "Software Rasterizer"})
    if (glRenderer.find(name) != std::string_view::npos) return true;
  return false;
}
namespace {

// ---- SSGI methods --------------------------------------------------------------

// The hemisphere method's indirect term is albedo-weighted occlusion, not
// radiance: 0.5 keeps it from doubling the ambient (the seed's value).
constexpr SsgiMethodTraits kSsgiMethods[] = {
    {SsgiMethod::Hemisphere, SsgiProgram::Kernel, "", false, false, false, 0.5f},
    {SsgiMethod::Radiance, SsgiProgram::Kernel, "METHOD_RADIANCE", true, false, false, 1.0f},
    {SsgiMethod::Bitmask, SsgiProgram::Bitmask, "", true, true, true, 1.0f},
};

// ---- Attachments -----------------------------------------------------------------

using F = GpuFormat;
using S = AttachmentScale;
// The one table of GPU formats: a target's format is the format of the
// attachment that holds it. Direct light is internal. The rows marked
// radiance hold light: half float, or float32 with radiance-precision float.
constexpr AttachmentRow kAttachmentRows[] = {
    {.id = Attachment::GbufferPosition,
     .name = "gbuffer.position",
     .format = F::Rgba32F,
     .gbufferLocation = 0,
     .target = &Frame::position},
    {.id = Attachment::GbufferNormal,
     .name = "gbuffer.normal",
     .format = F::Rgba16F,
     .gbufferLocation = 1,
     .target = &Frame::normal},
    {.id = Attachment::GbufferAlbedo,
     .name = "gbuffer.albedo",
     .format = F::Srgb8Alpha8,
     .gbufferLocation = 2,
     .target = &Frame::albedo},
    {.id = Attachment::GbufferMaterial,
     .name = "gbuffer.material",
     .format = F::Rgba8,
     .gbufferLocation = 3,
     .target = &Frame::material},
    {.id = Attachment::GbufferEmissive,
     .name = "gbuffer.emissive",
     .format = F::Rgba16F,
     .gbufferLocation = kAssignedLocation,
     .gbufferDefine = "EMISSIVE_TARGET",
     .target = &Frame::emissive,
     .radiance = true},
    // The lobes' attachments, in Lobe order (lobeAttachment): allocated, and
    // given the next G-buffer location, only when a material of the scene
    // uses the lobe. Specular and clearcoat (glsl/lobe_*_material.glsl): half
    // floats, a dielectric F0 is ~0.04, where an 8-bit step would be 10 % of
    // it; the coat's octahedral normal needs ~11 bits per coordinate.
    {.id = lobeAttachment(Lobe::Specular),
     .name = "gbuffer.specularLobe",
     .format = F::Rgba16F,
     .gbufferLocation = kAssignedLocation,
     .gbufferDefine = "SPECULAR_TARGET",
     .target = &Frame::specular,
     .lobe = Lobe::Specular,
     .lobeUnit = gpu::kUnitSpecularLobe},
    {.id = lobeAttachment(Lobe::Clearcoat),
     .name = "gbuffer.clearcoatLobe",
     .format = F::Rgba16F,
     .gbufferLocation = kAssignedLocation,
     .gbufferDefine = "CLEARCOAT_TARGET",
     .target = &Frame::clearcoat,
     .lobe = Lobe::Clearcoat,
     .lobeUnit = gpu::kUnitClearcoatLobe},
    // Sheen colour in sRGB8 like the albedo (it comes from sRGB textures and
    // factors; the targets' sRGB encoding is applied on write), sheen
    // roughness in the linear alpha: 8 bits like the material factors.
    {.id = lobeAttachment(Lobe::Sheen),
     .name = "gbuffer.sheen",
     .format = F::Srgb8Alpha8,
     .gbufferLocation = kAssignedLocation,
     .gbufferDefine = "SHEEN_TARGET",
     .target = &Frame::sheen,
     .lobe = Lobe::Sheen,
     .lobeUnit = gpu::kUnitSheenLobe},
    // The anisotropy direction resolved to world space in the G-buffer pass
    // (the tangent frame lives there), half float like the normal: 0.03 deg.
    {.id = lobeAttachment(Lobe::Anisotropy),
     .name = "gbuffer.anisotropy",
     .format = F::Rgba16F,
     .gbufferLocation = kAssignedLocation,
     .gbufferDefine = "ANISOTROPY_TARGET",
     .target = &Frame::anisotropy,
     .lobe = Lobe::Anisotropy,
     .lobeUnit = gpu::kUnitAnisotropyLobe},
    // Half float: the film's thickness in nm (up to kMaxFilmThicknessNm, 1e4) keeps 11 bits, 0.25 nm at 400
    // nm, far below the 8-bit thickness texture's step; its IORs to 5e-4.
    {.id = lobeAttachment(Lobe::Iridescence),
     .name = "gbuffer.iridescence",
     .format = F::Rgba16F,
     .gbufferLocation = kAssignedLocation,
     .gbufferDefine = "IRIDESCENCE_TARGET",
     .target = &Frame::iridescence,
     .lobe = Lobe::Iridescence,
     .lobeUnit = gpu::kUnitIridescenceLobe},
    {.id = Attachment::GbufferDepth, .name = "gbuffer.depth", .format = F::Depth32F, .target = &Frame::depth},
    {.id = Attachment::DirectTowardEye, .name = "direct.towardEye", .format = F::Rgba16F, .radiance = true},
    {.id = Attachment::DirectDiffuse, .name = "direct.diffuse", .format = F::Rgba16F, .radiance = true},
    {.id = Attachment::SsgiRaw, .name = "ssgi.raw", .format = F::Rgba16F, .scale = S::SsgiNear, .radiance = true},
    {.id = Attachment::SsgiRawSky, .name = "ssgi.rawSky", .format = F::Rgba16F, .scale = S::SsgiFar},
    {.id = Attachment::SsgiFarSky, .name = "ssgi.farSky", .format = F::Rgba16F, .scale = S::SsgiFar},
    // Written with the sky (the far field's pass): its lobe reaches past R.
    {.id = Attachment::SsgiRawSpecular, .name = "ssgi.rawSpecular", .format = F::Rgba16F, .scale = S::SsgiFar},
    {.id = Attachment::SsgiFarSpecular, .name = "ssgi.farSpecular", .format = F::Rgba16F, .scale = S::SsgiFar},
    {.id = Attachment::Ssgi, .name = "ssgi", .format = F::Rgba16F, .target = &Frame::ssgi, .radiance = true},
    {.id = Attachment::SsgiSky, .name = "ssgi.sky", .format = F::Rgba16F, .target = &Frame::ssgi},
    // The specular sky visibility (ssgi channel 8) and, internal, its weight.
    {.id = Attachment::SsgiSpecular, .name = "ssgi.specular", .format = F::Rgba16F, .target = &Frame::ssgi},
    {.id = Attachment::Lit, .name = "lit", .format = F::Rgba16F, .target = &Frame::lit, .radiance = true},
    // Float: coverage accumulates a + (1 - a) c over every layer, and in
    // half float it stopped once a layer's share fell under half a step near
    // 1 (0.976 after ~200 layers of alpha 0.03, where 0.9999 is due; issue
    // 32). The file keeps half: 0..1 to ~5e-4.
    {.id = Attachment::BlendCoverage, .name = "blend.coverage", .format = F::Rgba32F, .target = &Frame::coverage},
    // Half float: a throughput 0..1 and a path length in world units.
    // Float: the path length through a KHR_materials_volume is the file's thickness times its scale,
    // unbounded; half turned any beyond 65504 into inf and the set could not be written (issue 32).
    {.id = Attachment::Transmission, .name = "transmission", .format = F::Rgba32F, .target = &Frame::transmission},
    // float32: the depth buffer's value exactly, and the view normal as the marches computed it.
    {.id = Attachment::SsgiSurface, .name = "ssgi.surface", .format = F::Rgba32F},
    // float32 whatever lit's precision: 64 samples' running mean in half would round at every step.
    {.id = Attachment::LitAccumulation, .name = "lit.accumulation", .format = F::Rgba32F},
    {.id = Attachment::LitForeground, .name = "lit.foreground", .format = F::Rgba32F},
    // Last of the G-buffer's: where a scene's lobes fill GL's 8 attachments, lit keeps them and ids is named.
    {.id = Attachment::GbufferIds,
     .name = "gbuffer.ids",
     .format = F::Rgba32Ui,
     .gbufferLocation = kAssignedLocation,
     .gbufferDefine = "IDS_TARGET",
     .target = &Frame::ids},
};
static_assert(std::size(kAttachmentRows) == kAttachmentCount);

// ---- Fullscreen passes: what each reads and writes -------------------------------

// The reads of a pass that lights the G-buffer (direct light, composite):
// its four fixed attachments and each lobe attachment the plan's G-buffer
// draws, on the lobe's unit.
std::vector<PassRead> gbufferSurfaceReads(const GBufferVariant& gbuffer) {
  std::vector<PassRead> reads{{Attachment::GbufferPosition, gpu::kUnitGbufferPosition},
                              {Attachment::GbufferNormal, gpu::kUnitGbufferNormal},
                              {Attachment::GbufferAlbedo, gpu::kUnitGbufferAlbedo},
                              {Attachment::GbufferMaterial, gpu::kUnitGbufferMaterial}};
  for (Attachment id : gbuffer.colorAttachments)
    if (attachmentRow(id).lobe) reads.push_back({id, attachmentRow(id).lobeUnit});
  return reads;
}

// lib/passes/direct_light.hpp: the G-buffer's surface and its emission;
// toward the eye, and the diffuse radiance for the SSGI methods that gather it.
std::optional<PassDeclaration> declareDirectLight(const FramePlan& plan) {
  if (!plan.direct) return std::nullopt;
  PassDeclaration pass;
  pass.reads = gbufferSurfaceReads(plan.gbuffer);
  if (plan.direct->emissive) pass.reads.push_back({Attachment::GbufferEmissive, gpu::kUnitGbufferEmissive});
  pass.writes = {Attachment::DirectTowardEye};
  if (plan.direct->diffuseTarget) pass.writes.push_back(Attachment::DirectDiffuse);
  return pass;
}

// glsl/ssgi_surface.glsl, for the bitmask method's marches: depth and normal packed.
std::optional<PassDeclaration> declareSsgiSurface(const FramePlan& plan) {
  if (!plan.ssgi || plan.ssgi->method->program != SsgiProgram::Bitmask) return std::nullopt;
  return PassDeclaration{.reads = {{Attachment::GbufferDepth, gpu::kUnitGbufferDepth},
                                   {Attachment::GbufferNormal, gpu::kUnitGbufferNormal}},
                         .writes = {Attachment::SsgiSurface}};
}
constexpr std::string_view kSsgiSurfaceOutputs[] = {"surface"};

// lib/passes/ssgi.hpp: the G-buffer's surface as the method reads it
// (position for the kernels, depth for the bitmask), direct.diffuse for the
// methods that gather it, the emission for the bitmask's virtual lights; the
// raw SSGI when the blur follows, else the blurred textures directly.
std::optional<PassDeclaration> declareSsgi(const FramePlan& plan) {
  if (!plan.ssgi) return std::nullopt;
  const SsgiMethodTraits& method = *plan.ssgi->method;
  PassDeclaration pass;
  if (method.program == SsgiProgram::Bitmask) {
    pass.reads = {{Attachment::GbufferDepth, gpu::kUnitGbufferDepth},
                  {Attachment::GbufferNormal, gpu::kUnitGbufferNormal},
                  {Attachment::GbufferAlbedo, gpu::kUnitGbufferAlbedo},
                  {Attachment::GbufferMaterial, gpu::kUnitGbufferMaterial},
                  {Attachment::SsgiSurface, gpu::kUnitSsgiSurface}};
    const auto& colors = plan.gbuffer.colorAttachments;
    if (plan.ssgi->virtualLights > 0 &&
        std::find(colors.begin(), colors.end(), Attachment::GbufferEmissive) != colors.end())
      pass.reads.push_back({Attachment::GbufferEmissive, gpu::kUnitGbufferEmissive});
  } else {
    pass.reads = {{Attachment::GbufferPosition, gpu::kUnitGbufferPosition},
                  {Attachment::GbufferNormal, gpu::kUnitGbufferNormal},
                  {Attachment::GbufferAlbedo, gpu::kUnitGbufferAlbedo}};
    if (method.readsDirectDiffuse) pass.reads.push_back({Attachment::GbufferMaterial, gpu::kUnitGbufferMaterial});
  }
  if (method.readsDirectDiffuse) pass.reads.push_back({Attachment::DirectDiffuse, gpu::kUnitDirectDiffuse});
  if (plan.ssgi->blur)
    pass.writes = {Attachment::SsgiRaw, Attachment::SsgiRawSky, Attachment::SsgiRawSpecular};
  else
    pass.writes = {Attachment::Ssgi, Attachment::SsgiSky, Attachment::SsgiSpecular};
  return pass;
}

// lib/passes/ssgi_blur.hpp: position, normal and the raw SSGI; the blurred
// SSGI, and with a coarser far field ssgi.farSky and ssgi.farSpecular and the
// raw sky and specular it blurs in place.
std::optional<PassDeclaration> declareSsgiBlur(const FramePlan& plan) {
  if (!plan.ssgi || !plan.ssgi->blur) return std::nullopt;
  PassDeclaration pass;
  pass.reads = {{Attachment::GbufferPosition, gpu::kUnitGbufferPosition},
                {Attachment::GbufferNormal, gpu::kUnitGbufferNormal},
                {Attachment::SsgiRaw, gpu::kUnitSsgi},
                {Attachment::SsgiRawSky, gpu::kUnitSsgiSky},
                {Attachment::SsgiRawSpecular, gpu::kUnitSsgiSpecular}};
  pass.writes = {Attachment::Ssgi, Attachment::SsgiSky, Attachment::SsgiSpecular};
  if (plan.ssgi->splitsFarField())
    pass.writes.insert(pass.writes.end(), {Attachment::SsgiFarSky, Attachment::SsgiRawSky, Attachment::SsgiFarSpecular,
                                           Attachment::SsgiRawSpecular});
  return pass;
}

// lib/passes/composite.hpp: the G-buffer's surface, the direct light and
// (with SSGI) the blurred SSGI; lit.
std::optional<PassDeclaration> declareComposite(const FramePlan& plan) {
  if (!plan.composite) return std::nullopt;
  PassDeclaration pass;
  pass.reads = gbufferSurfaceReads(plan.gbuffer);
  pass.reads.push_back({Attachment::DirectTowardEye, gpu::kUnitDirect});
  if (plan.composite->ssgi)
    pass.reads.insert(pass.reads.end(), {{Attachment::Ssgi, gpu::kUnitSsgi},
                                         {Attachment::SsgiSky, gpu::kUnitSsgiSky},
                                         {Attachment::SsgiSpecular, gpu::kUnitSsgiSpecular}});
  pass.writes = {Attachment::Lit};
  return pass;
}

// softwareForm: the faster form on llvmpipe, wall time, tools/form_times.sh on cornell and spheres at
// 256x256 and 640x480 (docs/BENCHMARKS.md, "Fullscreen forms"): compute / fragment was 1.03-1.15 for
// direct, 0.98-1.53 for SSGI, 0.99-1.33 for the blur, 0.83-1.03 for the composite. The tables run once
// per renderer and were not told apart: fragment, as before.
const FullscreenPassRow kFullscreenPassRows[] = {
    {.name = "direct", .softwareForm = PassForm::Fragment, .declare = declareDirectLight},
    // ssgi-surface: compute 5.5-7.9 ms against fragment 11.9-13.0 at cornell 640x480, 3.3-5.0 against 8.8-14.8
    // at spheres 256x256 (--verbose, three cold runs each; one compute outlier of 31 ms, a first run's JIT).
    {.name = "ssgi-surface",
     .softwareForm = PassForm::Compute,
     .declare = declareSsgiSurface,
     .body = "ssgi_surface.glsl",
     .outputs = kSsgiSurfaceOutputs,
     .perAntialiasSample = false},
    {.name = "ssgi", .softwareForm = PassForm::Fragment, .declare = declareSsgi, .perAntialiasSample = false},
    {.name = "ssgi-blur", .softwareForm = PassForm::Fragment, .declare = declareSsgiBlur, .perAntialiasSample = false},
    {.name = "composite", .softwareForm = PassForm::Compute, .declare = declareComposite},
    // The BRDF, sky and environment tables (EnvironmentPass): made on demand
    // ahead of the frame's passes, not attachments of it.
    {.name = "sky", .softwareForm = PassForm::Fragment},
    // Lit's samples averaged (AntialiasStep): after the transmission and
    // blend passes, which are no rows, so the plan declares it itself
    // (declareAntialias). A copy: compute, untimed apart.
    {.name = "antialias", .softwareForm = PassForm::Compute},
};

// The antialias pass: one sample of lit into lit.accumulation's running
// mean, and with `foreground` its RGB x A and A into lit.foreground's.
PassDeclaration declareAntialias(bool foreground) {
  PassDeclaration pass{.row = fullscreenPassIndex("antialias"),
                       .reads = {{Attachment::Lit, gpu::kUnitLit}},
                       .writes = {Attachment::LitAccumulation}};
  if (foreground) pass.writes.push_back(Attachment::LitForeground);
  return pass;
}

// ---- What a frame skips ------------------------------------------------------------

// What decides which work a frame needs: the scene, the resolved settings
// and the targets asked for.
struct FrameFacts {
  bool wantLit = true;
  bool wantSsgi = true;
  bool ssgiOn = true;
  bool ssgiReadsDirect = true;
  bool shadowsOn = true;       // --shadows
  bool shadowCasters = true;   // a light of the scene casts shadows
  bool skyLit = true;          // sky intensity > 0
  bool environment = false;    // an environment map replaces the sky
  bool environmentLit = true;  // environment intensity > 0
  bool sceneEmits = true;      // a material has a non-zero emissiveFactor
  bool sceneBlends = true;     // a material is alphaMode BLEND
  bool sceneTransmits = true;  // a material is drawn by the transmission pass (Material::transmissive)
};

bool ssgiRuns(const FrameFacts& f) { return f.ssgiOn && (f.wantLit || f.wantSsgi); }
bool directNeeded(const FrameFacts& f) { return f.wantLit || (ssgiRuns(f) && f.ssgiReadsDirect); }

// Work a frame can leave out, each named in --verbose.
enum class Work { Shadows, Direct, Ssgi, Composite, Sky, Emissive, Blend, Transmission, Count };
constexpr std::string_view kWorkNames[] = {"shadows", "direct",   "ssgi",  "composite",
                                           "sky",     "emissive", "blend", "transmission"};
static_assert(std::size(kWorkNames) == std::size_t(Work::Count));

// The one table of what a frame skips and why: work runs unless a row says
// it is not needed, and the first row that applies is the reason given.
// Every output stays what the full frame would give: shadow maps without a
// shadow-casting light would be read by no light; the sky term with sky
// intensity 0 adds exactly 0 (and its tables are then not made); a scene
// with no emission has no emissive target (asked for by name, it is written
// as zeros).
struct SkipRule {
  Work work;
  std::string_view reason;
  bool (*applies)(const FrameFacts&);
};
constexpr SkipRule kSkipRules[] = {
    {Work::Shadows, "setting shadows is off", [](const FrameFacts& f) { return !f.shadowsOn; }},
    {Work::Shadows, "no light casts shadows", [](const FrameFacts& f) { return !f.shadowCasters; }},
    {Work::Shadows, "no direct light is drawn (only G-buffer targets asked for)",
     [](const FrameFacts& f) { return !directNeeded(f); }},
    {Work::Direct, "only G-buffer targets asked for", [](const FrameFacts& f) { return !directNeeded(f); }},
    {Work::Ssgi, "setting ssgi is off", [](const FrameFacts& f) { return !f.ssgiOn; }},
    {Work::Ssgi, "neither ssgi nor lit asked for", [](const FrameFacts& f) { return !ssgiRuns(f); }},
    {Work::Composite, "lit not asked for", [](const FrameFacts& f) { return !f.wantLit; }},
    {Work::Sky, "sky intensity 0 (no sky tables, no sky term)",
     [](const FrameFacts& f) { return !f.environment && !f.skyLit; }},
    {Work::Sky, "environment intensity 0 (no environment tables, no ambient term)",
     [](const FrameFacts& f) { return f.environment && !f.environmentLit; }},
    {Work::Sky, "lit not asked for", [](const FrameFacts& f) { return !f.wantLit; }},
    {Work::Emissive, "no material emits (no emissive target, no emission term)",
     [](const FrameFacts& f) { return !f.sceneEmits; }},
    // A scene without BLEND has no blend pass to skip (planFrame): nothing listed.
    {Work::Blend, "lit not asked for (no coverage target)",
     [](const FrameFacts& f) { return f.sceneBlends && !f.wantLit; }},
    // Listed only for a scene that transmits; its G-buffer pass then draws
    // the transmissive surfaces itself (nothing refracts the opaque image).
    {Work::Transmission, "lit not asked for (no transmission target; the G-buffer pass draws the surfaces)",
     [](const FrameFacts& f) { return f.sceneTransmits && !f.wantLit; }},
};

struct SkipDecisions {
  std::optional<std::string_view> reason[std::size_t(Work::Count)];
  bool runs(Work work) const { return !reason[std::size_t(work)]; }
};

SkipDecisions decideSkips(const FrameFacts& facts) {
  SkipDecisions decisions;
  for (const SkipRule& rule : kSkipRules)
    if (!decisions.reason[std::size_t(rule.work)] && rule.applies(facts))
      decisions.reason[std::size_t(rule.work)] = rule.reason;
  return decisions;
}

// Whether the caller asked for a frame target (an empty list: all).
struct TargetWanted {
  std::span<const std::string> names;
  bool operator()(std::string_view name) const {
    return names.empty() || std::find(names.begin(), names.end(), name) != names.end();
  }
  // Named in the list itself, not just included in "all".
  bool named(std::string_view name) const { return std::find(names.begin(), names.end(), name) != names.end(); }
};

// The attachments the planned passes draw into: the G-buffer's, what the
// fullscreen passes declare they write, and the forward passes' targets.
void planAttachments(FramePlan& plan) {
  auto allocate = [&](Attachment id) { plan.allocate[std::size_t(id)] = true; };
  for (Attachment id : plan.gbuffer.colorAttachments) allocate(id);
  allocate(Attachment::GbufferDepth);
  for (const PassDeclaration& pass : plan.passes)
    for (Attachment id : pass.writes) allocate(id);
  if (plan.blend) allocate(Attachment::BlendCoverage);
  if (plan.transmission) allocate(Attachment::Transmission);
  if (plan.antialias)
    for (Attachment id : plan.antialias->accumulate.writes) allocate(id);
}

// The G-buffer's colour attachments, in row order: the fixed ones, then each
// optional one the frame needs (emission, the scene's lobes) at the next
// location, while GL's guaranteed 8 last; a lobe beyond them is named.
void planGBuffer(FramePlan& plan, const SceneSummary& scene, bool emissive, const TargetWanted& wanted) {
  GBufferVariant& gbuffer = plan.gbuffer;
  for (const AttachmentRow& row : kAttachmentRows) {
    if (row.gbufferLocation == -1) continue;
    if (row.id == Attachment::GbufferEmissive && !emissive) continue;
    if (row.lobe && !(scene.lobes & lobeBit(*row.lobe))) continue;
    if (row.id == Attachment::GbufferIds) {
      if (!wanted("ids")) continue;
      if (scene.largestId > kLargestExactId) {
        plan.skipped.push_back({std::string(row.name), "an id reaches " + std::to_string(scene.largestId) +
                                                           ", beyond what a float holds exactly (2^24)"});
        plan.unrendered.push_back("ids is not rendered: the scene has " + std::to_string(scene.largestId) +
                                  " of one kind, more than 2^24 (16777216)");
        continue;
      }
    }
    const std::size_t location = gbuffer.colorAttachments.size();
    if (location == kMaxGbufferColorAttachments) {
      plan.skipped.push_back({std::string(row.name), "the G-buffer has no colour attachment left (GL 4.5 guarantees " +
                                                         std::to_string(kMaxGbufferColorAttachments) + ")"});
      plan.unrendered.push_back(std::string(row.name) + " is not rendered: the G-buffer has no colour attachment left");
      continue;
    }
    gbuffer.colorAttachments.push_back(row.id);
    if (row.gbufferLocation == kAssignedLocation) {
      gbuffer.defines.push_back("HAS_" + std::string(row.gbufferDefine));
      gbuffer.defines.push_back(std::string(row.gbufferDefine) + "_LOCATION " + std::to_string(location));
    }
    if (row.lobe) gbuffer.lobes |= lobeBit(*row.lobe);
  }
  for (std::string& define : lobeDefines(gbuffer.lobes)) gbuffer.defines.push_back(std::move(define));
}

// Each wanted target is read from the allocated attachments that hold it.
void planReads(FramePlan& plan, const TargetWanted& wanted, const SceneSummary& scene) {
  for (const FrameTarget& target : frameTargets()) {
    if (!target.image || !wanted(target.name)) continue;
    TargetRead read{&target, {}, {target.channels.begin(), target.channels.end()}};
    // The material attachment's A holds the unlit flag (gbuffer.frag).
    if (target.image == &Frame::material && scene.unlit) read.channels.emplace_back(kMaterialUnlitChannel);
    for (const AttachmentRow& row : kAttachmentRows)
      if (row.target == target.image && plan.allocates(row.id)) read.sources.push_back(row.id);
    if (target.image == &Frame::lit && plan.antialias) {
      read.sources = {Attachment::LitAccumulation};
      read.afterAntialias = true;
    }
    // Asked for by name and drawn by nothing the scene needs (the emissive
    // target of a scene without emission): what it would hold, zeros.
    const bool zeros = read.sources.empty() && target.image == &Frame::emissive && wanted.named(target.name);
    if (!read.sources.empty() || zeros) plan.reads.push_back(std::move(read));
  }
}

}  // namespace

std::span<const FullscreenPassRow> fullscreenPassRows() { return kFullscreenPassRows; }

std::vector<PassDeclaration> declareFullscreenPasses(const FramePlan& plan, std::span<const FullscreenPassRow> rows) {
  std::vector<PassDeclaration> passes;
  std::vector<Attachment> written(plan.gbuffer.colorAttachments);
  written.push_back(Attachment::GbufferDepth);
  for (std::size_t index = 0; index < rows.size(); ++index) {
    if (!rows[index].declare) continue;
    std::optional<PassDeclaration> pass = rows[index].declare(plan);
    if (!pass) continue;
    pass->row = index;
    for (const PassRead& read : pass->reads)
      if (std::find(written.begin(), written.end(), read.attachment) == written.end())
        throw std::logic_error(std::string(rows[index].name) + " reads " +
                               std::string(attachmentRow(read.attachment).name) +
                               ", which neither the G-buffer nor an earlier pass writes");
    written.insert(written.end(), pass->writes.begin(), pass->writes.end());
    passes.push_back(std::move(*pass));
  }
  return passes;
}

SceneSummary summarizeScene(const Scene& scene) {
  SceneSummary summary;
  for (const Light& light : scene.lights)
    if (light.castsShadows)
      (light.type == Light::Type::Point ? summary.cubeShadowCasters : summary.planarShadowCasters)++;
  summary.emissive = scene.hasEmissive();
  summary.blended = scene.hasBlended();
  summary.environment = scene.environment != nullptr;
  summary.unlit =
      std::any_of(scene.materials.begin(), scene.materials.end(), [](const Material& m) { return m.unlit; });
  for (const Material& material : scene.materials) {
    summary.lobes |= materialLobes(material);
    summary.transmission |= material.transmissive();  // KHR_materials_volume alone transmits nothing
  }
  summary.largestId = largestId(scene);
  return summary;
}

// ---- Lobes: which extension makes a material use each, its GLSL hooks -------

namespace {
// What the lighting passes' shared GLSL (brdf.glsl, ambient.glsl,
// surface.glsl, gbuffer.frag) asks of a lobe: each hook is a function
// `<name>Lobe<Hook>` of glsl/lobe_<name>.glsl (AmbientLayer: of
// lobe_<name>_ambient.glsl, which ambient.glsl's prefilteredSky precedes),
// taking the Surface and the lobe's vec4 as the Surface holds it
// (s.lobes[<NAME>_LOBE_SLOT]). The composition calls LOBES_<HOOK>, which
// lobeDefines writes as those calls for the variant's lobes that have the
// hook; docs/PIPELINE.md, "What a lobe is made of".
enum LobeHook : std::uint32_t {
  Apply = 1u << 0,            // vec4 (inout Surface, vec4 lobe): puts it on the Surface, returns the value it keeps
  Fresnel = 1u << 1,          // vec3 (Surface, vec4, vec3 fresnel): the Fresnel at V.H
  SpecularTerm = 1u << 2,     // float (Surface, vec4, float term, alpha, vec3 toLight, halfVector, float nDotL): D Vis
  LayerScale = 1u << 3,       // float (Surface, vec4, float nDotL): what a layer over the base leaves of its light
  LayerLight = 1u << 4,       // vec3 (Surface, vec4, float nDotL, nDotH): the layer's own light, N.L included
  AlbedoRoughness = 1u << 5,  // float (Surface, vec4, float roughness): the split-sum table's roughness
  SpecularAlbedo = 1u << 6,   // vec3 (Surface, vec4, vec3 albedo, vec2 scaleBias): the split-sum result
  Reflection = 1u << 7,       // vec3 (Surface, vec4, vec3 reflected): the prefiltered lookup's direction
  AmbientLayer = 1u << 8,     // vec3 (Surface, vec4, vec3 ambient, float skyVisibility): a layer over the ambient
};

// Each hook's macro and the call it makes per lobe: `#` stands for
// `<name>Lobe`, `$` for the lobe's slot.
struct HookRow {
  std::uint32_t hook;  // 0: every lobe with hooks (its values' read, material and target)
  std::string_view macro;
  std::string_view call;
};
constexpr HookRow kHookRows[] = {
    {Apply, "LOBES_APPLY(s)", "s.lobes[$] = #Apply(s, s.lobes[$]);"},
    {Fresnel, "LOBES_FRESNEL(s, fresnel)", "fresnel = #Fresnel(s, s.lobes[$], fresnel);"},
    {SpecularTerm, "LOBES_SPECULAR_TERM(s, term, alpha, toLight, halfVector, nDotL)",
     "term = #SpecularTerm(s, s.lobes[$], term, alpha, toLight, halfVector, nDotL);"},
    {LayerScale, "LOBES_LAYER_SCALE(s, scale, nDotL)", "scale *= #LayerScale(s, s.lobes[$], nDotL);"},
    {LayerLight, "LOBES_LAYER_LIGHT(s, light, nDotL, nDotH)", "light += #LayerLight(s, s.lobes[$], nDotL, nDotH);"},
    {AlbedoRoughness, "LOBES_ALBEDO_ROUGHNESS(s, roughness)",
     "roughness = #AlbedoRoughness(s, s.lobes[$], roughness);"},
    {SpecularAlbedo, "LOBES_SPECULAR_ALBEDO(s, albedo, scaleBias)",
     "albedo = #SpecularAlbedo(s, s.lobes[$], albedo, scaleBias);"},
    {Reflection, "LOBES_REFLECTION(s, reflected)", "reflected = #Reflection(s, s.lobes[$], reflected);"},
    {AmbientLayer, "LOBES_AMBIENT_LAYER(s, ambient, skyVisibility)",
     "ambient = #AmbientLayer(s, s.lobes[$], ambient, skyVisibility);"},
    // The values: from the material (lobe_<name>_material.glsl, the G-buffer
    // and forward passes), from the lobe's G-buffer target (sampler
    // `<name>LobeTarget`, the deferred passes), and the G-buffer's output.
    {0, "LOBES_OF_MATERIAL(lobes, normal)", "lobes[$] = #OfMaterial(normal);"},
    {0, "LOBES_AT(lobes, pixel)", "lobes[$] = texelFetch(#Target, pixel, 0);"},
    {0, "LOBE_TARGET_OUTPUTS", "layout(location = %_LOCATION) out vec4 #Out;"},
    {0, "LOBES_WRITE_TARGETS(normal)", "#Out = #OfMaterial(normal);"},
};

// A lobe: its name in --verbose, its GLSL name (glsl/lobe_<glsl>*.glsl),
// which materials use it and the hooks its GLSL defines. Clearcoat, a layer
// with its own normal, is composed by each lighting pass and has none.
struct LobeRow {
  Lobe lobe;
  std::string_view name;  // in --verbose
  std::string_view glsl;
  bool (*usedBy)(const Material&);
  std::uint32_t hooks;
};
constexpr LobeRow kLobeRows[] = {
    {Lobe::Specular, "specular (KHR_materials_specular, _ior)", "specular",
     [](const Material& m) { return m.specular.has_value() || m.ior != 1.5f; }, Apply},
    {Lobe::Clearcoat, "clearcoat", "clearcoat", [](const Material& m) { return m.clearcoat.has_value(); }, 0},
    {Lobe::Sheen, "sheen", "sheen", [](const Material& m) { return m.sheen.has_value(); },
     LayerScale | LayerLight | AmbientLayer},
    {Lobe::Anisotropy, "anisotropy", "anisotropy", [](const Material& m) { return m.anisotropy.has_value(); },
     SpecularTerm | AlbedoRoughness | Reflection},
    {Lobe::Iridescence, "iridescence", "iridescence", [](const Material& m) { return m.iridescence.has_value(); },
     Apply | Fresnel | SpecularAlbedo},
};
static_assert(std::size(kLobeRows) == kLobeCount);

std::string upperCase(std::string_view text) {
  std::string upper(text);
  for (char& c : upper) c = char(std::toupper(static_cast<unsigned char>(c)));
  return upper;
}

// The lobe's G-buffer attachment's define (AttachmentRow::gbufferDefine).
std::string_view lobeTargetDefine(Lobe lobe) {
  for (const AttachmentRow& row : kAttachmentRows)
    if (row.lobe == lobe) return row.gbufferDefine;
  return {};
}

// `call` for one lobe: `#` its `<glsl>Lobe`, `$` its slot, `%` its target's define.
std::string hookCall(std::string_view call, const LobeRow& row, int slot) {
  std::string out;
  for (char c : call) {
    if (c == '#')
      out += std::string(row.glsl) + "Lobe";
    else if (c == '$')
      out += std::to_string(slot);
    else if (c == '%')
      out += lobeTargetDefine(row.lobe);
    else
      out += c;
  }
  return out;
}
}  // namespace

std::uint32_t materialLobes(const Material& material) {
  std::uint32_t lobes = 0;
  // An unlit material is not lit: its lobes would change nothing.
  if (material.unlit) return lobes;
  for (const LobeRow& row : kLobeRows)
    if (row.usedBy(material)) lobes |= lobeBit(row.lobe);
  return lobes;
}

ImageF Frame::*lobeTarget(Lobe lobe) {
  for (const AttachmentRow& row : kAttachmentRows)
    if (row.lobe == lobe) return row.target;
  throw std::logic_error("lobeTarget: a lobe without an attachment row");
}

std::string lobeNames(std::uint32_t lobes) {
  std::string names;
  for (const LobeRow& row : kLobeRows)
    if (lobes & lobeBit(row.lobe)) names += (names.empty() ? "" : ", ") + std::string(row.name);
  return names;
}

std::vector<std::string> lobeDefines(std::uint32_t lobes) {
  std::vector<std::string> defines;
  if (lobes == 0) return defines;      // glsl/lobes.glsl: no slot, no hook calls
  std::vector<const LobeRow*> hooked;  // in row order: slot i is hooked[i]
  std::string names = "LOBE_NAMES";
  for (const LobeRow& row : kLobeRows) {
    if (!(lobes & lobeBit(row.lobe))) continue;
    const std::string upper = upperCase(row.glsl);
    defines.push_back(std::string("HAS_").append(upper).append("_LOBE"));
    if (row.hooks == 0) continue;
    defines.push_back(upper + "_LOBE_SLOT " + std::to_string(hooked.size()));
    names.append(" ").append(row.glsl);
    hooked.push_back(&row);
  }
  // GLSL has no empty arrays: one unused slot without a lobe.
  defines.push_back("LOBE_SLOTS " + std::to_string(std::max<std::size_t>(hooked.size(), 1)));
  defines.push_back(names);
  for (const HookRow& hook : kHookRows) {
    std::string define(hook.macro);
    for (std::size_t slot = 0; slot < hooked.size(); ++slot)
      if (hook.hook == 0 || (hooked[slot]->hooks & hook.hook))
        define.append(" ").append(hookCall(hook.call, *hooked[slot], int(slot)));
    defines.push_back(std::move(define));
  }
  return defines;
}

const SsgiMethodTraits& ssgiMethodTraits(SsgiMethod method) {
  for (const SsgiMethodTraits& traits : kSsgiMethods)
    if (traits.method == method) return traits;
  return kSsgiMethods[0];  // unreachable: every SsgiMethod has a row (unit-tested)
}

std::span<const AttachmentRow> attachmentRows() { return kAttachmentRows; }
const AttachmentRow& attachmentRow(Attachment id) { return kAttachmentRows[std::size_t(id)]; }

int FramePlan::divisorOf(Attachment id) const {
  switch (attachmentRow(id).scale) {
    case AttachmentScale::SsgiNear:
      return ssgi ? ssgi->downsample : 1;
    case AttachmentScale::SsgiFar:
      return ssgi ? ssgi->farDownsample : 1;
    case AttachmentScale::Image:
      break;
  }
  return 1;
}

std::vector<std::string_view> FramePlan::passNames() const {
  std::vector<std::string_view> names;
  if (shadows) names.push_back("shadows");
  if (ssgi && ssgi->virtualLights > 0) names.push_back("virtual-lights");  // made once per scene
  if (ssgi && ssgi->lightFieldProbes > 0) names.push_back("light-field");  // and from them, once per scene
  // The tables, made on demand ahead of the passes that read them.
  if (skyTables) names.push_back("sky");
  if (environmentTables) names.push_back("environment");
  names.push_back("gbuffer");
  for (const PassDeclaration& pass : passes) names.push_back(fullscreenPassRows()[pass.row].name);
  if (transmission) names.push_back("transmission");
  if (blend) names.push_back("blend");
  if (antialias) names.push_back("antialias");  // the jittered samples' passes, timed as one
  names.push_back("readback");
  return names;
}

FramePlan planFrame(const SceneSummary& scene, const RenderSettings& settings, std::span<const std::string> targets) {
  const TargetWanted wanted{targets};
  const SsgiMethodTraits& method = ssgiMethodTraits(settings.ssgi.method);
  FrameFacts facts;
  facts.wantLit = wanted("lit");
  facts.wantSsgi = wanted("ssgi");
  facts.ssgiOn = settings.ssgi.enabled;
  facts.ssgiReadsDirect = method.readsDirectDiffuse;
  facts.shadowsOn = settings.lighting.shadows;
  facts.shadowCasters = scene.planarShadowCasters + scene.cubeShadowCasters > 0;
  facts.skyLit = settings.lighting.skyIntensity.value_or(0.0f) > 0.0f;
  facts.environment = scene.environment;
  facts.environmentLit = settings.lighting.environmentIntensity > 0.0f;
  facts.sceneEmits = scene.emissive;
  facts.sceneBlends = scene.blended;
  facts.sceneTransmits = scene.transmission;
  const SkipDecisions skips = decideSkips(facts);

  FramePlan plan;
  for (std::size_t w = 0; w < std::size_t(Work::Count); ++w)
    if (skips.reason[w]) plan.skipped.push_back({std::string(kWorkNames[w]), std::string(*skips.reason[w])});

  plan.dropShadowMaps = !facts.shadowsOn;
  if (skips.runs(Work::Shadows))
    plan.shadows =
        ShadowStep{.mapSize = settings.lighting.shadowMapSize.value_or(0),
                   .transmittance = scene.transmission && scene.planarShadowCasters + scene.cubeShadowCasters > 0};
  // Every lighting pass reads the same maps.
  const ShadowLookups shadowLookups{.planar = plan.shadows && scene.planarShadowCasters > 0,
                                    .cube = plan.shadows && scene.cubeShadowCasters > 0,
                                    .transmittance = plan.shadows && plan.shadows->transmittance};
  planGBuffer(plan, scene, skips.runs(Work::Emissive), wanted);
  // What a scene without a lobe does not pay for, named once.
  if (const std::uint32_t absent = ~scene.lobes & (lobeBit(Lobe::Count) - 1))
    plan.skipped.push_back({"lobes", "no material uses " + lobeNames(absent) + " (no attachment, no shader code)"});
  if (skips.runs(Work::Ssgi)) {
    const int divisor = ssgiDivisor(settings.ssgi.resolution);
    // The far field's own pass needs far samples to march and the blur to upsample it.
    const bool farPass = method.marchesBeyondRadius && settings.ssgi.skyStepCount > 0 && settings.ssgi.blur;
    plan.ssgi =
        SsgiStep{.method = &method,
                 .frames = method.accumulatesFrames ? settings.ssgi.frames : 1,
                 .downsample = divisor,
                 .blur = settings.ssgi.blur,
                 .farDownsample = farPass ? std::max(divisor, ssgiDivisor(settings.ssgi.farResolution)) : divisor};
    if (method.marchesBeyondRadius) plan.ssgi->virtualLights = settings.ssgi.virtualLightCount;
    if (plan.ssgi->virtualLights > 0) plan.ssgi->lightFieldProbes = settings.ssgi.lightFieldProbes;
  }
  if (skips.runs(Work::Direct))
    plan.direct = DirectLightVariant{.emissive = skips.runs(Work::Emissive),
                                     .shadows = shadowLookups,
                                     .diffuseTarget = plan.ssgi && method.readsDirectDiffuse,
                                     .lobes = plan.gbuffer.lobes};
  plan.skyTables = skips.runs(Work::Sky) && !scene.environment;
  plan.environmentTables = skips.runs(Work::Sky) && scene.environment;
  if (skips.runs(Work::Composite))
    plan.composite = CompositeVariant{.ssgi = plan.ssgi.has_value(),
                                      .sky = skips.runs(Work::Sky),
                                      .environment = plan.environmentTables,
                                      .lobes = plan.gbuffer.lobes};
  // Transmissive surfaces refract the composite's lit image and are lit as
  // blended ones are; they wait for it only when it is drawn.
  if (scene.transmission && skips.runs(Work::Transmission)) {
    plan.transmission = TransmissionVariant{.shadows = shadowLookups,
                                            .sky = skips.runs(Work::Sky),
                                            .environment = plan.environmentTables,
                                            .lobes = scene.lobes};
    plan.gbuffer.deferTransmissive = true;
  }
  // Blended surfaces are drawn over the composite's lit target, with the
  // same shadow maps and ambient term (the direct pass's variant decides both).
  if (scene.blended && skips.runs(Work::Blend))
    plan.blend = BlendVariant{.shadows = shadowLookups,
                              .sky = skips.runs(Work::Sky),
                              .environment = plan.environmentTables,
                              .lobes = scene.lobes};
  plan.passes = declareFullscreenPasses(plan, fullscreenPassRows());
  if (plan.composite && settings.antialiasSamples > 1) {
    // A preview over a colour or transparent shows the foreground alone.
    const bool foreground = parsePreviewBackground(settings.previewBackground).kind != PreviewBackground::Kind::Sky;
    plan.antialias = AntialiasStep{.samples = settings.antialiasSamples,
                                   .ssgiPerSample = settings.antialiasSsgi && plan.ssgi,
                                   .foreground = foreground,
                                   .perSamplePasses = {},
                                   .accumulate = declareAntialias(foreground)};
    for (std::size_t index = 0; index < plan.passes.size(); ++index)
      if (plan.antialias->ssgiPerSample || fullscreenPassRows()[plan.passes[index].row].perAntialiasSample)
        plan.antialias->perSamplePasses.push_back(index);
  }
  planAttachments(plan);
  const bool floatRadiance = settings.radiancePrecision == RadiancePrecision::Float;
  for (const AttachmentRow& row : kAttachmentRows)
    plan.format[std::size_t(row.id)] = row.radiance && floatRadiance ? GpuFormat::Rgba32F : row.format;
  planReads(plan, wanted, scene);
  return plan;
}

}  // namespace headlight

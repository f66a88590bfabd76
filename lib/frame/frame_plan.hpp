#pragma once
// The frame plan: everything one frame does, decided in one place and
// without GL. planFrame() turns (what the scene uses, the resolved settings,
// the targets asked for) into the passes to run with their shader variants,
// the attachments to allocate with their formats, the attachments each frame
// target is read from, and the work left out with the reason. The renderer
// (lib/renderer.cpp) executes the plan and decides nothing else.
//
// Adding an attachment that exists only when the scene uses a feature is one
// row of kAttachmentRows (frame_plan.cpp) and one SceneSummary field; an SSGI
// method is one row of the method table.
#include <array>
#include <cstdint>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "frame/lobe.hpp"
#include "gl/gpu_format.hpp"
#include "headlight/frame.hpp"
#include "headlight/scene.hpp"
#include "headlight/settings.hpp"
#include "headlight/targets.hpp"

namespace headlight {

// ---- Material lobes ------------------------------------------------------------

// The KHR_materials_* lobes the lighting passes evaluate from G-buffer data.
// Each has (when its extension's work has landed) one G-buffer attachment
// row (AttachmentRow::lobe) that exists only when the scene uses the lobe,
// and a HAS_<NAME>_LOBE define in the programs that read it. Specular is
// KHR_materials_specular or an ior other than 1.5: both change the
// dielectric F0.
// The lobes a material uses (a bit per Lobe).
std::uint32_t materialLobes(const Material& material);
// HAS_SPECULAR_LOBE, ... (one per bit of `lobes`), and what the shared GLSL
// composes them with: each hooked lobe's <NAME>_LOBE_SLOT, LOBE_SLOTS,
// LOBE_NAMES (for #include_lobes, gl/shader_library.cpp) and the LOBES_*
// hook macros; for the G-buffer, direct, composite, blend and transmission
// programs.
std::vector<std::string> lobeDefines(std::uint32_t lobes);
// Where a Frame keeps the lobe's G-buffer target (its attachment row's).
ImageF Frame::*lobeTarget(Lobe lobe);
// "specular (KHR_materials_specular, _ior), clearcoat, ...": the lobes of `lobes`, for --verbose.
std::string lobeNames(std::uint32_t lobes);

// What a plan needs to know of a scene; made once per setScene.
struct SceneSummary {
  int planarShadowCasters = 0;  // directional and spot lights that cast shadows
  int cubeShadowCasters = 0;    // point lights that cast shadows
  bool emissive = false;        // a material emits (emissiveFactor != 0)
  bool blended = false;         // an instance's material is alphaMode BLEND (the blend pass)
  bool environment = false;     // an environment map replaces the procedural sky (Scene::environment)
  bool unlit = false;           // a material is KHR_materials_unlit: material.exr gains kMaterialUnlitChannel
  std::uint32_t lobes = 0;      // the lobes its materials use (lobeBit)
  bool transmission = false;    // a material is KHR_materials_transmission or _volume (a forward pass)
  std::size_t largestId = 0;    // the ids target's largest value (largestId())
};

// material.exr's fourth channel, written only for scenes with an unlit
// material (so other scenes' files keep their three channels): 1 where the
// pixel's material is KHR_materials_unlit (lit = its albedo), else 0.
inline constexpr std::string_view kMaterialUnlitChannel = "material.unlit";
// `scene.lights` as drawn: with the default key light when the file has none.
SceneSummary summarizeScene(const Scene& scene);

// ---- SSGI methods: one row each ------------------------------------------------

// Which program draws a method: ssgi.frag's kernel (hemisphere, radiance) or
// ssgi_bitmask.frag.
enum class SsgiProgram { Kernel, Bitmask };

struct SsgiMethodTraits {
  SsgiMethod method;
  SsgiProgram program;
  std::string_view kernelDefine;  // ssgi.frag's #define for a kernel method ("" = none)
  bool readsDirectDiffuse;        // gathers the occluders' direct light (the direct pass's diffuse target)
  bool marchesBeyondRadius;       // ssgi-sky-steps applies
  bool accumulatesFrames;         // ssgi-frames applies (a running mean of rotated frames)
  float defaultIndirectStrength;  // ssgi-indirect-strength's auto value
};
const SsgiMethodTraits& ssgiMethodTraits(SsgiMethod method);

// ---- Fullscreen passes and their forms ---------------------------------------

// How a fullscreen pass runs (lib/passes/fullscreen.hpp): its body,
// `PassOutputs shadePixel(ivec2 pixel)`, under a fullscreen triangle's
// fragment shader or a compute dispatch.
enum class PassForm { Fragment, Compute };
std::string_view passFormName(PassForm form);  // "fragment", "compute"

// ---- Attachments -------------------------------------------------------------

// Every texture a frame may draw into. The frame's textures are an array
// indexed by this (lib/renderer.cpp).
enum class Attachment {
  GbufferPosition,
  GbufferNormal,
  GbufferAlbedo,
  GbufferMaterial,
  GbufferEmissive,
  // One per Lobe, in Lobe order (lobeAttachment): the lobe's values, as
  // frame_plan.cpp's row of it says.
  GbufferLobes,
  GbufferLobesEnd = GbufferLobes + int(kLobeCount),
  GbufferDepth = GbufferLobesEnd,
  DirectTowardEye,
  DirectDiffuse,
  SsgiRaw,          // the SSGI pass's output before the blur (its own resolution)
  SsgiRawSky,       // at the far field's resolution (SsgiStep::farDownsample)
  SsgiFarSky,       // the far field blurred at its own resolution, before the upsample; only when it has its own pass
  SsgiRawSpecular,  // at the far field's resolution, as the sky
  SsgiFarSpecular,  // the specular visibility blurred along rows at the far field's resolution, as SsgiFarSky
  Ssgi,             // after the blur: what the composite reads and ssgi.exr holds
  SsgiSky,
  SsgiSpecular,  // the specular lobe's sky visibility (R) and its weight (G, internal)
  Lit,
  BlendCoverage,    // the blend pass's accumulated alpha, 1 - prod(1 - a); only for scenes that blend
  Transmission,     // the transmission pass's throughput and path length; only for scenes that transmit
  SsgiSurface,      // the bitmask SSGI's marches' depth and view normal, one fetch a step (glsl/ssgi_surface.glsl)
  LitAccumulation,  // the running mean of lit's antialias samples; lit.exr's source when antialiased
  LitForeground,    // the running mean of their RGB x A and A (Frame::litForeground)
  GbufferIds,       // mesh instance, mesh, material and mesh primitive ids; only when the ids target is wanted
  Count
};
inline constexpr std::size_t kAttachmentCount = std::size_t(Attachment::Count);
// The G-buffer attachment that holds `lobe`'s values.
constexpr Attachment lobeAttachment(Lobe lobe) { return Attachment(int(Attachment::GbufferLobes) + int(lobe)); }

// AttachmentRow::gbufferLocation of an optional G-buffer attachment: the
// plan gives it the next location after those of the attachments before it.
inline constexpr int kAssignedLocation = -2;
// GL 4.5's guaranteed number of colour attachments: lobe attachments beyond
// it are skipped (and named) by the plan.
inline constexpr std::size_t kMaxGbufferColorAttachments = 8;

// Which resolution an attachment has: the image's, or the SSGI pass's
// (SsgiStep::downsample) or its far field's (SsgiStep::farDownsample).
enum class AttachmentScale { Image, SsgiNear, SsgiFar };

struct AttachmentRow {
  Attachment id;
  std::string_view name;  // in messages and --verbose
  GpuFormat format;
  // The G-buffer pass's colour attachment index (its fragment output's
  // location); -1 for the depth attachment and for the other passes' targets;
  // kAssignedLocation for an optional one.
  int gbufferLocation = -1;
  // An optional G-buffer attachment's name in gbuffer.frag: the plan defines
  // HAS_<gbufferDefine> and <gbufferDefine>_LOCATION (its location).
  std::string_view gbufferDefine{};
  AttachmentScale scale = AttachmentScale::Image;
  // The frame target it holds (several rows: channels 4k..4k+3 in the k-th);
  // null for internal attachments.
  ImageF Frame::*target = nullptr;
  // Holds light (HDR radiance): `format` is half float, and the frame's
  // radiance-precision may make it Rgba32F (FramePlan::format).
  bool radiance = false;
  // The lobe whose data it holds: allocated only when the scene uses the
  // lobe, and bound on `lobeUnit` (gpu::kUnit*Lobe) for the lighting passes.
  std::optional<Lobe> lobe = std::nullopt;
  int lobeUnit = -1;
};
// Every attachment, in Attachment order.
std::span<const AttachmentRow> attachmentRows();
const AttachmentRow& attachmentRow(Attachment id);

// ---- Passes and their variants -----------------------------------------------

struct GBufferVariant {
  std::vector<Attachment>
      colorAttachments;              // in location order (the index is the location); optional ones only when planned
  std::vector<std::string> defines;  // HAS_<gbufferDefine> and its _LOCATION, then lobeDefines(lobes)
  std::uint32_t lobes = 0;           // the lobes whose attachments are planned
  // The transmission pass runs: KHR_materials_transmission surfaces are left
  // out here and drawn into the G-buffer by that pass, after the composite
  // has lit the opaque image they refract.
  bool deferTransmissive = false;
};

// The shadow maps a lighting shader reads (HAS_PLANAR_SHADOWS,
// HAS_CUBE_SHADOWS, HAS_SHADOW_TRANSMITTANCE): the planar array for
// directional and spot casters, the cube array for point casters and, beside
// each, what transmissive casters let through (lib/passes/shadow.hpp).
struct ShadowLookups {
  bool planar = false, cube = false, transmittance = false;
  auto operator<=>(const ShadowLookups&) const = default;
};

struct DirectLightVariant {
  bool emissive = false;
  ShadowLookups shadows;
  bool diffuseTarget = false;
  std::uint32_t lobes = 0;  // the G-buffer's lobes (GBufferVariant::lobes)
  auto operator<=>(const DirectLightVariant&) const = default;
};

struct CompositeVariant {
  bool ssgi = false, sky = false;  // sky: the ambient term is drawn (from the sky's or the environment's tables)
  bool environment = false;  // the ambient and the background come from the environment map's tables
  std::uint32_t lobes = 0;   // the G-buffer's lobes (GBufferVariant::lobes)
  auto operator<=>(const CompositeVariant&) const = default;
};

// The forward pass of alphaMode BLEND surfaces over lit (lib/passes/blend.hpp):
// lit by the lights, shadows and sky the composite uses.
struct BlendVariant {
  ShadowLookups shadows;
  bool sky = false, environment = false;  // the composite's
  std::uint32_t lobes = 0;  // the scene's lobes (a blended material's own data; no G-buffer read)
  auto operator<=>(const BlendVariant&) const = default;
};

// The forward pass of KHR_materials_transmission surfaces over lit
// (lib/passes/transmission.hpp): lit by the lights, shadows and sky the
// composite uses, refracting the opaque lit image.
struct TransmissionVariant {
  ShadowLookups shadows;
  bool sky = false, environment = false;  // as BlendVariant's
  std::uint32_t lobes = 0;                // as BlendVariant's: every lobe lights a transmissive material too
  auto operator<=>(const TransmissionVariant&) const = default;
};

struct ShadowStep {
  int mapSize = 0;             // texels per side
  bool transmittance = false;  // transmissive casters tint and dim light (a map beside each depth map)
};

struct SsgiStep {
  const SsgiMethodTraits* method = nullptr;
  int frames = 1;      // accumulated frames (1 unless the method accumulates)
  int downsample = 1;  // the raw SSGI's divisor
  bool blur = false;   // SsgiRaw -> Ssgi through the blur; else the pass writes Ssgi directly
  // The far field's divisor (SsgiRawSky). Above `downsample` (bitmask with
  // sky steps and the blur on, ssgi-far-resolution coarser than
  // ssgi-resolution) the far field has its own pass and its own blur
  // (SsgiFarSky) before the upsample; else it is `downsample`.
  int farDownsample = 1;
  // The most virtual point lights the far field gathers its light from
  // beyond R from (lib/passes/virtual_lights.hpp); 0: the marches gather it.
  int virtualLights = 0;
  // The most probes of the light field (lib/passes/light_field.hpp) the far
  // field reads its light from beyond R in; 0: none. Only with virtual
  // lights, which fill it.
  int lightFieldProbes = 0;
  bool splitsFarField() const { return farDownsample > downsample; }
};

// A frame target and where it comes from.
struct TargetRead {
  const FrameTarget* target = nullptr;
  std::vector<Attachment> sources;  // empty: written as zeros (asked for by name, nothing draws it)
  // The EXR's channels: the target's, then material.unlit where the scene has unlit materials.
  std::vector<std::string> channels;
  // Read once the antialias samples are averaged (lit); every other target
  // is read after the centre sample, before a jittered one overwrites it.
  bool afterAntialias = false;
};

// ---- Fullscreen passes: what each declares ---------------------------------

// An attachment a pass reads, bound on texture unit `unit` (gpu::kUnit*, the
// binding its body's sampler declares) before the pass runs.
struct PassRead {
  Attachment attachment;
  int unit;
  auto operator<=>(const PassRead&) const = default;
};

// What one frame's run of a fullscreen pass reads and writes. The plan
// allocates what the frame's passes write; the runner binds what a pass
// reads and hands it only those attachments (PassAttachments,
// lib/passes/frame_pass.hpp). Every read is the G-buffer's or written by an
// earlier pass of the frame (checked by planFrame).
struct PassDeclaration {
  std::size_t row = 0;  // its FullscreenPassRow (fullscreenPassRows())
  std::vector<PassRead> reads;
  std::vector<Attachment> writes;
  bool readsAttachment(Attachment id) const;
  bool writesAttachment(Attachment id) const;
};

struct FramePlan;

// Antialiasing (RenderSettings::antialiasSamples, lib/frame/antialias.hpp):
// the frame is drawn at the pixel centre, and every target but lit read
// from that; then each sample draws the view again through a projection
// jittered by its sub-pixel offset: the G-buffer, the fullscreen passes that run per
// sample (FullscreenPassRow::perAntialiasSample: not the SSGI, whose centre
// output each sample's composite reads), transmission and blend. The
// `antialias` pass keeps the running mean of the samples' lit in
// lit.accumulation, which lit is read from.
struct AntialiasStep {
  int samples = 2;                           // jittered samples averaged (the centre's frame is not one)
  bool ssgiPerSample = false;                // antialias-ssgi: the SSGI passes are among perSamplePasses
  // The preview is shown over a colour or transparent: the foreground is
  // accumulated too (lit.foreground, read into Frame::litForeground).
  bool foreground = false;
  std::vector<std::size_t> perSamplePasses;  // indices into FramePlan::passes a jittered sample runs again
  PassDeclaration accumulate;  // the antialias pass: reads lit, writes lit.accumulation (and lit.foreground)
};

// One fullscreen pass: its name, the form auto picks for it on a software
// rasteriser (measured), and what it reads and writes in a plan. Its GL side
// is its FramePass (lib/passes/frame_passes.cpp makes it), or, for a pass
// with no GL code of its own, its body run as it is (GenericFramePass,
// lib/passes/frame_pass.hpp) with the row's defines and outputs. Adding such
// a pass is its body in glsl/ and one row (lib/frame/frame_plan.cpp).
struct FullscreenPassRow {
  std::string_view name;  // its PassTime::pass
  // Auto's form on a software rasteriser: the faster one measured on
  // llvmpipe (docs/BENCHMARKS.md, "Fullscreen forms").
  PassForm softwareForm;
  // What the pass reads and writes in a frame planned so far (the passes
  // before it declared); none: it does not run in that frame. Null for a
  // pass that is not one of the frame's (the sky tables, made on demand).
  std::optional<PassDeclaration> (*declare)(const FramePlan& plan) = nullptr;
  // A pass without GL code of its own: its body (glsl/), its #defines in a
  // plan (null: none) and the PassOutputs member each declared write takes,
  // in order.
  std::string_view body = {};
  std::vector<std::string> (*defines)(const FramePlan& plan) = nullptr;
  std::span<const std::string_view> outputs = {};
  // Runs again for each jittered antialias sample (AntialiasStep); false:
  // its output is the screen-space light, low in frequency, and the centre
  // sample's serves every sample.
  bool perAntialiasSample = true;
};
// Every fullscreen pass, in frame order.
std::span<const FullscreenPassRow> fullscreenPassRows();
// What `rows` declare for `plan` (its variants decided), in row order, each
// with its row index. Throws std::logic_error naming the pass and the
// attachment when a pass reads what neither the G-buffer nor an earlier
// pass writes.
std::vector<PassDeclaration> declareFullscreenPasses(const FramePlan& plan, std::span<const FullscreenPassRow> rows);
// The row named `name`; throws std::out_of_range for none.
std::size_t fullscreenPassIndex(std::string_view name);

// The forms of one frame's fullscreen passes, by row.
using PassForms = std::vector<PassForm>;
// What `setting` runs each pass as: fragment or compute as asked; auto:
// compute on a hardware GPU, the row's measured form on a software
// rasteriser.
PassForms choosePassForms(std::optional<FullscreenForm> setting, bool softwareRasterizer);
// GL_RENDERER names a CPU rasteriser (llvmpipe, softpipe, swrast, SwiftShader).
bool isSoftwareRasterizer(std::string_view glRenderer);

struct FramePlan {
  // Passes in frame order; a pass that does not run has no value.
  bool dropShadowMaps = false;  // shadows are off: the kept maps are released
  std::optional<ShadowStep> shadows;
  GBufferVariant gbuffer;
  std::optional<DirectLightVariant> direct;
  std::optional<SsgiStep> ssgi;
  bool skyTables = false;  // the sky's prefiltered tables are (made if needed and) read
  // The environment map's tables (its prefiltered levels, irradiance and
  // the map itself as the background) are (made if needed and) read: only
  // with an environment map, which then replaces the sky's tables.
  bool environmentTables = false;
  std::optional<CompositeVariant> composite;
  // The fullscreen passes that run after the G-buffer, in frame order, as
  // their rows declared them for this plan (direct, ssgi, ssgi-blur, composite).
  std::vector<PassDeclaration> passes;
  std::optional<TransmissionVariant> transmission;  // after the composite, before the blend pass
  std::optional<BlendVariant> blend;                // after the composite, over lit
  std::optional<AntialiasStep> antialias;           // after everything that writes lit

  std::array<bool, kAttachmentCount> allocate{};     // by Attachment
  std::array<GpuFormat, kAttachmentCount> format{};  // by Attachment: the row's, or Rgba32F for radiance in float
  std::vector<TargetRead> reads;                     // the targets read back, in frameTargets() order
  std::vector<SkippedWork> skipped;                  // the work left out, and why (--verbose)
  std::vector<std::string> unrendered;               // what the scene uses that this frame cannot draw (warned)

  bool allocates(Attachment id) const { return allocate[std::size_t(id)]; }
  // What an attachment's row's scale divides the image's size by (rounded up): 1, 2 or 4.
  int divisorOf(Attachment id) const;
  GpuFormat formatOf(Attachment id) const { return format[std::size_t(id)]; }
  std::vector<std::string_view> passNames() const;
};

// `settings` must be resolved (Renderer::resolve): every auto value set.
// `targets` names the frame targets wanted (empty: all of them).
FramePlan planFrame(const SceneSummary& scene, const RenderSettings& settings, std::span<const std::string> targets);

}  // namespace headlight

// The frame, top to bottom: shadows (once per scene and size) -> G-buffer ->
// direct light -> SSGI (-> blur) -> composite -> read back. Each pass is timed between glFinish calls
// and checked for GL errors.
#include "headlight/renderer.hpp"

#include <algorithm>
#include <bit>
#include <chrono>
#include <optional>
#include <span>
#include <vector>

#include "gl/objects.hpp"
#include "gl/readback.hpp"
#include "gl/target_formats.hpp"
#include "headlight/error.hpp"
#include "headlight/targets.hpp"
#include "passes/composite.hpp"
#include "passes/direct_light.hpp"
#include "passes/environment.hpp"
#include "passes/gbuffer.hpp"
#include "passes/shadow.hpp"
#include "passes/ssgi.hpp"
#include "passes/ssgi_blur.hpp"
#include "scene/gpu_scene.hpp"
#include "shared_layout.h"

namespace headlight {
namespace {

// Runs GL work between two glFinish calls, so the wall time is the GPU's
// (timer queries would exclude the CPU side that llvmpipe also spends), and
// reports the pass's GL errors by name.
class PassTimer {
 public:
  explicit PassTimer(Context& context) : context_(context) {}
  template <class Work>
  void run(const char* pass, Work&& work) {
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    work();
    glFinish();
    const auto end = std::chrono::steady_clock::now();
    context_.checkErrors(pass);
    times_.push_back({pass, std::chrono::duration<double, std::milli>(end - start).count()});
  }
  std::vector<PassTime> times() const { return times_; }

 private:
  Context& context_;
  std::vector<PassTime> times_;
};

int autoShadowMapSize(int width, int height) {
  return std::clamp(int(std::bit_ceil(unsigned(std::max(width, height)))), 512, 2048);
}

// A scene with no light of its own gets one sun from above, in front and to
// the left of the fitted camera's side (+Z), of about pi lux, so a white
// Lambertian surface facing it reflects a radiance near 1.
Light defaultKeyLight() {
  Light light;
  light.name = "default key light";
  light.type = Light::Type::Directional;
  light.direction = glm::normalize(glm::vec3(0.4f, -0.8f, -0.45f));
  light.intensity = 3.0f;
  light.castsShadows = true;
  return light;
}

// The bitmask SSGI's auto thickness: how deep the scene's objects typically
// are behind what the camera sees, taken as 2/3 of the median over
// instances of the smallest side of their world bounds (2/3: a sphere's mean
// depth over its outline is 2/3 of its diameter). Flat instances (a side under 1e-3 of the scene's diagonal:
// walls, floors) say nothing about depth and are left out. Held within
// [kAutoThicknessFraction / 10, 1] x the radius, and
// kAutoThicknessFraction x radius when every instance is flat.
float autoThickness(const Scene& scene, float diagonal, float radius) {
  std::vector<float> depths;
  for (const Instance& instance : scene.instances) {
    const Bounds bounds = scene.primitives[std::size_t(instance.primitive)].bounds.transformed(instance.worldFromLocal);
    if (bounds.empty()) continue;
    const glm::vec3 size = bounds.max - bounds.min;
    const float smallest = std::min({size.x, size.y, size.z});
    if (smallest > 1e-3f * diagonal) depths.push_back(smallest);
  }
  if (depths.empty()) return SsgiSettings::kAutoThicknessFraction * radius;
  std::nth_element(depths.begin(), depths.begin() + std::ptrdiff_t(depths.size() / 2), depths.end());
  return std::clamp(depths[depths.size() / 2] * (2.0f / 3.0f), 0.1f * SsgiSettings::kAutoThicknessFraction * radius,
                    radius);
}

gpu::FrameBlock makeFrameBlock(const CameraView& view, int width, int height) {
  gpu::FrameBlock block{};
  block.view = view.view;
  block.projection = view.projection;
  block.viewProjection = view.projection * view.view;
  block.cameraPosition = glm::vec4(view.position, view.orthographic ? 1.0f : 0.0f);
  block.viewport = glm::vec4(float(width), float(height), 1.0f / float(width), 1.0f / float(height));
  block.nearFar = glm::vec4(view.nearPlane, view.farPlane, 0.0f, 0.0f);
  return block;
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

// What decides which work a frame needs: the scene, the resolved settings
// and the targets asked for.
struct FrameFacts {
  bool wantLit = true;
  bool wantSsgi = true;
  bool ssgiOn = true;
  bool ssgiReadsDirect = true;  // the radiance and bitmask methods gather the occluders' direct light
  bool shadowsOn = true;        // --shadows
  bool shadowCasters = true;    // a light of the scene casts shadows
  bool skyLit = true;           // sky intensity > 0
  bool sceneEmits = true;       // a material has a non-zero emissiveFactor
};

bool ssgiRuns(const FrameFacts& f) { return f.ssgiOn && (f.wantLit || f.wantSsgi); }
bool directNeeded(const FrameFacts& f) { return f.wantLit || (ssgiRuns(f) && f.ssgiReadsDirect); }

// Work a frame can leave out, each named in --verbose.
enum class Work { Shadows, Direct, Ssgi, Composite, Sky, Emissive, Count };
constexpr std::string_view kWorkNames[] = {"shadows", "direct", "ssgi", "composite", "sky", "emissive"};
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
    {Work::Shadows, "--no-shadows", [](const FrameFacts& f) { return !f.shadowsOn; }},
    {Work::Shadows, "no light casts shadows", [](const FrameFacts& f) { return !f.shadowCasters; }},
    {Work::Shadows, "no direct light is drawn (only G-buffer targets asked for)",
     [](const FrameFacts& f) { return !directNeeded(f); }},
    {Work::Direct, "only G-buffer targets asked for", [](const FrameFacts& f) { return !directNeeded(f); }},
    {Work::Ssgi, "--no-ssgi", [](const FrameFacts& f) { return !f.ssgiOn; }},
    {Work::Ssgi, "neither ssgi nor lit asked for", [](const FrameFacts& f) { return !ssgiRuns(f); }},
    {Work::Composite, "lit not asked for", [](const FrameFacts& f) { return !f.wantLit; }},
    {Work::Sky, "sky intensity 0 (no sky tables, no sky term)", [](const FrameFacts& f) { return !f.skyLit; }},
    {Work::Sky, "lit not asked for", [](const FrameFacts& f) { return !f.wantLit; }},
    {Work::Emissive, "no material emits (no emissive target, no emission term)",
     [](const FrameFacts& f) { return !f.sceneEmits; }},
};

struct FramePlan {
  std::optional<std::string_view> skipReason[std::size_t(Work::Count)];
  bool runs(Work work) const { return !skipReason[std::size_t(work)]; }
  std::vector<SkippedWork> skipped() const {
    std::vector<SkippedWork> list;
    for (std::size_t w = 0; w < std::size_t(Work::Count); ++w)
      if (skipReason[w]) list.push_back({std::string(kWorkNames[w]), std::string(*skipReason[w])});
    return list;
  }
};

FramePlan planFrame(const FrameFacts& facts) {
  FramePlan plan;
  for (const SkipRule& rule : kSkipRules)
    if (!plan.skipReason[std::size_t(rule.work)] && rule.applies(facts))
      plan.skipReason[std::size_t(rule.work)] = rule.reason;
  return plan;
}

}  // namespace

struct Renderer::Impl {
  explicit Impl(Context& context) : context(context) { context.checkErrors("building the renderer"); }
  void loadScene(Scene newScene);  // Renderer::setScene's work

  Context& context;
  ResourceLimits limits;
  std::uint64_t sceneBytes = 0;  // estimateSceneBytes of the current scene
  EnvironmentPass environment;
  SsgiPass ssgi;
  SsgiBlurPass ssgiBlur;
  ShadowPass shadow;
  DirectLightPass directLight;
  CompositePass composite;
  gl::Buffer frameBlock = gl::Buffer::create(sizeof(gpu::FrameBlock));
  gl::Buffer lightingBlock = gl::Buffer::create(sizeof(gpu::LightingBlock));

  // Per scene.
  Scene scene;
  std::optional<GpuScene> gpuScene;
  std::optional<GBufferPass> gbufferPass;
  gl::Buffer lightBuffer;  // scene.lights packed, with the shadow slots of shadowMaps
  ShadowMaps shadowMaps;   // kept across views: they do not depend on the camera
  int shadowMapSize = 0;   // what shadowMaps were made with; 0 = none yet

  // Per image size.
  GBuffer gbuffer;
  DirectLightTargets direct;
  // The SSGI pass's two outputs (SsgiTextures) before the blur, and after:
  // what composite reads and ssgi.exr holds.
  gl::Texture ssgiRaw, ssgiRawSky;
  gl::Texture ssgiTarget, ssgiSkyTarget;
  gl::Texture litTarget;

  // Which targets a frame needs besides the G-buffer, direct light and lit.
  struct TargetNeeds {
    bool directDiffuse;  // SSGI on with the radiance or bitmask method
    bool ssgi;           // SSGI on
    bool ssgiRaw;        // SSGI on with the blur
    int ssgiDownsample;  // the raw SSGI's divisor
    bool emissive;       // the G-buffer's emissive target (the scene emits)
  };

  // Targets follow the image size; the SSGI ones exist only while SSGI (and
  // its blur, or its radiance method) is on.
  void ensureTargets(int width, int height, const TargetNeeds& needs) {
    auto ensure = [&](gl::Texture& texture, bool wanted, GLenum format, int divisor = 1) {
      const int w = (width + divisor - 1) / divisor, h = (height + divisor - 1) / divisor;
      if (!wanted)
        texture = gl::Texture();
      else if (texture.width() != w || texture.height() != h)
        texture = gl::Texture::create2D(format, w, h);
    };
    if (gbuffer.width != width || gbuffer.height != height || bool(gbuffer.emissive) != needs.emissive)
      gbuffer = makeGBuffer(width, height, needs.emissive);
    // Direct light is internal (no frame target): half float holds HDR radiance.
    ensure(direct.towardEye, true, GL_RGBA16F);
    ensure(direct.diffuse, needs.directDiffuse, GL_RGBA16F);
    // The raw SSGI is what the blur turns into the ssgi target: the same format.
    ensure(ssgiRaw, needs.ssgiRaw, gl::targetFormat(&Frame::ssgi), needs.ssgiDownsample);
    ensure(ssgiRawSky, needs.ssgiRaw, gl::targetFormat(&Frame::ssgi), needs.ssgiDownsample);
    ensure(ssgiTarget, needs.ssgi, gl::targetFormat(&Frame::ssgi));
    ensure(ssgiSkyTarget, needs.ssgi, gl::targetFormat(&Frame::ssgi));
    ensure(litTarget, true, gl::targetFormat(&Frame::lit));
  }

  bool hasShadowCasters() const {
    return std::any_of(scene.lights.begin(), scene.lights.end(), [](const Light& l) { return l.castsShadows; });
  }

  // The light buffer: the scene's lights, each with its slot in the shadow
  // maps (none without slots).
  void uploadLights(std::span<const ShadowSlot> slots) {
    const std::vector<gpu::GpuLight> lights = packLights(scene.lights, slots);
    lightBuffer.update(lights.data(), lights.size() * sizeof(gpu::GpuLight));
  }

  void renderShadows(int size) {
    ShadowOutputs shadows = shadow.run(*gpuScene, scene.lights, size);
    shadowMaps = std::move(shadows.maps);
    shadowMapSize = size;
    uploadLights(shadows.slots);
  }

  void dropShadows() {
    if (shadowMapSize == 0) return;
    shadowMaps = ShadowMaps{};
    shadowMapSize = 0;
    uploadLights({});
  }

  // The block the direct-light and composite passes read, and the lights.
  void bindLighting(float skyIntensity, float pcfRadius) {
    gpu::LightingBlock block{};
    block.skyIntensity = skyIntensity;
    block.lightCount = int(scene.lights.size());
    block.pcfRadius = pcfRadius;
    // 1.5 texels of normal offset: enough to clear acne at the PCF radius's
    // default without visibly detaching shadows.
    block.shadowNormalOffset = 1.5f;
    block.shadowMapSize = shadowMaps.size;
    lightingBlock.update(block);
    lightingBlock.bindUniform(gpu::LightingBlock::kBinding);
    lightBuffer.bindStorage(gpu::LightBuffer::kBinding);
  }

  const Camera& chooseCamera(const RenderSettings& settings, const Camera* override, Camera& fitted) const {
    if (override) return *override;
    if (settings.camera) {
      if (std::size_t(*settings.camera) >= scene.cameras.size())
        throw SettingsError("--camera " + std::to_string(*settings.camera) + ": " + scene.source + " has " +
                            std::to_string(scene.cameras.size()) + " camera(s)");
      return scene.cameras[std::size_t(*settings.camera)];
    }
    if (!scene.cameras.empty()) return scene.cameras.front();
    fitted = fitCamera(scene.worldBounds(), float(settings.width) / float(settings.height));
    return fitted;
  }

  // The GPU textures each frame target is read from (several for a target
  // of more than 4 channels); an empty first texture (no emissive target,
  // SSGI off) leaves the target empty.
  std::vector<const gl::Texture*> sourcesOf(const FrameTarget& target) const {
    const std::pair<ImageF Frame::*, std::vector<const gl::Texture*>> sources[] = {
        {&Frame::position, {&gbuffer.position}},
        {&Frame::normal, {&gbuffer.normal}},
        {&Frame::albedo, {&gbuffer.albedo}},
        {&Frame::material, {&gbuffer.material}},
        {&Frame::depth, {&gbuffer.depth}},
        {&Frame::emissive, {&gbuffer.emissive}},
        {&Frame::ssgi, {&ssgiTarget, &ssgiSkyTarget}},
        {&Frame::lit, {&litTarget}}};
    for (const auto& [image, textures] : sources)
      if (image == target.image) return textures;
    throw GlError("renderer: no GPU source for frame target '" + std::string(target.name) + "'");
  }

  void readTargets(Frame& frame, bool withSsgi, const TargetWanted& wanted) const {
    for (const FrameTarget& target : frameTargets()) {
      const std::vector<const gl::Texture*> sources = sourcesOf(target);
      if (target.image == &Frame::emissive && !*sources.front() && wanted.named(target.name)) {
        // Asked for by name in a scene with no emission: what it would hold.
        ImageF& zeros = frame.*target.image;
        zeros.width = gbuffer.width;
        zeros.height = gbuffer.height;
        zeros.channels.assign(target.channels.begin(), target.channels.end());
        zeros.pixels.assign(std::size_t(zeros.width) * std::size_t(zeros.height) * zeros.channels.size(), 0.0f);
        continue;
      }
      if (!*sources.front() || (target.image == &Frame::ssgi && !withSsgi) || !wanted(target.name)) continue;
      const std::vector<std::string> channels(target.channels.begin(), target.channels.end());
      frame.*target.image = target.gpuFormat == GpuFormat::Depth32F
                                ? readViewDepth(*sources.front(), frame.view, channels.front())
                                : readColor(sources, channels);
    }
  }
};

// Every entry point checks that its context is current on the calling thread:
// a GL call through another thread's context (or none) would crash or draw
// into the wrong context.
Renderer::Renderer(Context& context)
    : impl_((context.requireCurrent("headlight::Renderer"), context.lockBackend(), std::make_unique<Impl>(context))) {}
// The GL objects are deleted in their own context: a renderer destroyed on a
// thread where another context is current makes its own current first (and
// leaves it current); if that fails, the names are left to the context's
// destruction rather than deleted in the wrong context.
Renderer::~Renderer() {
  if (!impl_) return;
  auto lock = impl_->context.lockBackend();
  if (!impl_->context.isCurrent()) {
    try {
      impl_->context.makeCurrent();
    } catch (const ContextError&) {
      gladSetCurrentGLContext(nullptr);  // deletions below become no-ops (gl/objects.cpp)
    }
  }
  impl_.reset();  // under the lock
}

void Renderer::setScene(Scene scene) {
  Impl& impl = *impl_;
  impl.context.requireCurrent("Renderer::setScene");
  auto lock = impl.context.lockBackend();
  impl.gbufferPass.reset();
  impl.gpuScene.reset();
  impl.gbuffer = GBuffer{};  // its emissive target depends on the scene
  try {
    impl.loadScene(std::move(scene));
  } catch (...) {
    // No half-set scene: render() refuses until a setScene succeeds.
    impl.gbufferPass.reset();
    impl.gpuScene.reset();
    throw;
  }
}

void Renderer::setLimits(const ResourceLimits& limits) { impl_->limits = limits; }

void Renderer::Impl::loadScene(Scene newScene) {
  Impl& impl = *this;
  checkSceneRanges(newScene);
  checkDrawBudget(newScene, impl.limits);
  impl.sceneBytes = estimateSceneBytes(newScene);
  if (impl.sceneBytes > maxMemoryBytes(impl.limits))
    throw LimitError(newScene.source + ": the scene needs about " + std::to_string(impl.sceneBytes >> 20) +
                     " MiB, more than --max-memory allows (" + std::to_string(maxMemoryBytes(impl.limits) >> 20) +
                     " MiB)");
  impl.scene = std::move(newScene);
  if (impl.scene.lights.empty()) impl.scene.lights.push_back(defaultKeyLight());
  impl.gpuScene.emplace(uploadScene(impl.scene));
  impl.gbufferPass.emplace(*impl.gpuScene);
  // At least one element: a zero-sized buffer cannot be bound.
  impl.lightBuffer = gl::Buffer::create(std::max<std::size_t>(1, impl.scene.lights.size()) * sizeof(gpu::GpuLight));
  impl.uploadLights({});
  impl.shadowMaps = ShadowMaps{};
  impl.shadowMapSize = 0;
  // The default settings' variants, so the first frame times shading, not compiling.
  const RenderSettings defaults;
  impl.directLight.prepare(DirectLightPass::variantFor(impl.gpuScene->hasEmissive,
                                                       countShadowCasters(impl.scene.lights),
                                                       defaults.ssgi.method != SsgiMethod::Hemisphere));
  impl.ssgi.prepare(defaults.ssgi.method);
  impl.composite.prepare({true, impl.scene.sky.intensity > 0.0f});
  impl.context.checkErrors("uploading " + impl.scene.source);
}

const Scene& Renderer::scene() const { return impl_->scene; }

RenderSettings Renderer::resolve(const RenderSettings& settings) const {
  settings.validate();
  RenderSettings used = settings;
  // An empty scene has no size; 1 keeps every derived value finite.
  const float sceneRadius = impl_->scene.worldBounds().radius();
  const float diagonal = sceneRadius > 0.0f ? 2.0f * sceneRadius : 1.0f;
  if (!used.ssgi.radius) used.ssgi.radius = std::max(used.ssgi.radiusFraction * diagonal, 1e-30f);
  if (!used.ssgi.bias) used.ssgi.bias = SsgiSettings::kAutoBiasFraction * *used.ssgi.radius;
  if (!used.ssgi.thickness) used.ssgi.thickness = autoThickness(impl_->scene, diagonal, *used.ssgi.radius);
  if (!used.lighting.shadowMapSize) used.lighting.shadowMapSize = autoShadowMapSize(used.width, used.height);
  if (!used.lighting.skyIntensity) used.lighting.skyIntensity = impl_->scene.sky.intensity;
  if (!used.ssgi.indirectStrength)
    used.ssgi.indirectStrength = used.ssgi.method == SsgiMethod::Hemisphere ? 0.5f : 1.0f;
  return used;
}

Frame Renderer::render(const RenderSettings& settings, const Camera* camera, std::span<const std::string> targets) {
  Impl& impl = *impl_;
  impl.context.requireCurrent("Renderer::render");
  auto lock = impl.context.lockBackend();
  if (!impl.gpuScene || !impl.gbufferPass) throw SettingsError("Renderer::render: no scene (call setScene first)");
  Frame frame;
  frame.settings = resolve(settings);
  const RenderSettings& used = frame.settings;
  // Before any target of this size is allocated.
  checkFrameFits(used.width, used.height, impl.sceneBytes, impl.limits);
  Camera fitted;
  frame.view =
      makeCameraView(impl.chooseCamera(used, camera, fitted), impl.scene.worldBounds(), used.width, used.height);

  // The resolved settings, copied into the plain values each pass takes.
  const bool ssgiOn = used.ssgi.enabled;
  const bool ssgiBlur = used.ssgi.enabled && used.ssgi.blur;
  SsgiInputs ssgiInputs{impl.gbuffer, nullptr};
  ssgiInputs.method = used.ssgi.method;
  ssgiInputs.sampleCount = used.ssgi.sampleCount;
  ssgiInputs.seed = used.ssgi.seed;
  ssgiInputs.radiusWorld = *used.ssgi.radius;
  ssgiInputs.biasWorld = *used.ssgi.bias;
  ssgiInputs.intensity = used.ssgi.intensity;
  ssgiInputs.indirectStrength = *used.ssgi.indirectStrength;
  ssgiInputs.downsample = ssgiDivisor(used.ssgi.resolution);
  ssgiInputs.sliceCount = used.ssgi.sliceCount;
  ssgiInputs.stepCount = used.ssgi.stepCount;
  ssgiInputs.thicknessWorld = *used.ssgi.thickness;
  ssgiInputs.skyStepCount = used.ssgi.skyStepCount;
  const bool shadows = used.lighting.shadows;
  const int shadowMapSize = *used.lighting.shadowMapSize;
  const float skyIntensity = *used.lighting.skyIntensity;
  const float pcfRadius = used.lighting.pcfRadius;

  // Passes the scene, the settings or the wanted targets do not need are
  // skipped (kSkipRules): the G-buffer targets alone need neither light nor
  // SSGI; ssgi alone needs no composite; no shadow-casting light, no shadow maps.
  const TargetWanted wanted{targets};
  FrameFacts facts;
  facts.wantLit = wanted("lit");
  facts.wantSsgi = wanted("ssgi");
  facts.ssgiOn = ssgiOn;
  facts.ssgiReadsDirect = ssgiInputs.method != SsgiMethod::Hemisphere;
  facts.shadowsOn = shadows;
  facts.shadowCasters = impl.hasShadowCasters();
  facts.skyLit = skyIntensity > 0.0f;
  facts.sceneEmits = impl.gpuScene->hasEmissive;
  const FramePlan plan = planFrame(facts);
  frame.skipped = plan.skipped();
  const bool runSsgi = plan.runs(Work::Ssgi);

  impl.ensureTargets(
      used.width, used.height,
      {ssgiOn && facts.ssgiReadsDirect, ssgiOn, ssgiBlur, ssgiInputs.downsample, plan.runs(Work::Emissive)});
  impl.frameBlock.update(makeFrameBlock(frame.view, used.width, used.height));
  impl.frameBlock.bindUniform(gpu::FrameBlock::kBinding);

  PassTimer timer(impl.context);
  // Shadow maps are (re)made when the size changes or shadows are turned
  // on; with shadows off the lights read "no map" and nothing is allocated.
  if (!shadows) impl.dropShadows();
  if (plan.runs(Work::Shadows) && impl.shadowMapSize != shadowMapSize)
    timer.run("shadows", [&] { impl.renderShadows(shadowMapSize); });
  impl.bindLighting(skyIntensity, pcfRadius);
  timer.run("gbuffer", [&] { impl.gbufferPass->run(*impl.gpuScene, impl.gbuffer); });
  if (plan.runs(Work::Direct))
    timer.run("direct", [&] { impl.directLight.run({impl.gbuffer, impl.shadowMaps}, impl.direct); });
  if (runSsgi) {
    ssgiInputs.directDiffuse = impl.direct.diffuse ? &impl.direct.diffuse : nullptr;
    const SsgiTextures ssgiOutput =
        ssgiBlur ? SsgiTextures{impl.ssgiRaw, impl.ssgiRawSky} : SsgiTextures{impl.ssgiTarget, impl.ssgiSkyTarget};
    // Accumulated bitmask frames: a running mean of rotated slice sets.
    const int ssgiFrames = ssgiInputs.method == SsgiMethod::Bitmask ? used.ssgi.frames : 1;
    timer.run("ssgi", [&] {
      for (int index = 0; index < ssgiFrames; ++index) {
        ssgiInputs.frameIndex = index;
        ssgiInputs.accumulateWeight = index == 0 ? 0.0f : 1.0f / float(index + 1);
        impl.ssgi.run(ssgiInputs, ssgiOutput);
      }
    });
    const SsgiBlurInputs blurInputs{
        impl.gbuffer, {impl.ssgiRaw, impl.ssgiRawSky}, ssgiInputs.radiusWorld, ssgiInputs.downsample};
    if (ssgiBlur) timer.run("ssgi-blur", [&] { impl.ssgiBlur.run(blurInputs, {impl.ssgiTarget, impl.ssgiSkyTarget}); });
  }
  // The sky tables are made on the first frame that needs them (and again
  // only when the sky's colours change).
  if (plan.runs(Work::Sky) && !impl.environment.holds(impl.scene.sky))
    timer.run("sky", [&] { impl.environment.updateSky(impl.scene.sky); });
  const std::optional<SsgiTextures> compositeSsgi =
      ssgiOn ? std::optional<SsgiTextures>(SsgiTextures{impl.ssgiTarget, impl.ssgiSkyTarget}) : std::nullopt;
  const CompositeInputs compositeInputs{impl.gbuffer, impl.direct.towardEye, compositeSsgi ? &*compositeSsgi : nullptr,
                                        impl.environment.tables(), plan.runs(Work::Sky)};
  if (plan.runs(Work::Composite)) timer.run("composite", [&] { impl.composite.run(compositeInputs, impl.litTarget); });
  timer.run("readback", [&] { impl.readTargets(frame, runSsgi, wanted); });
  glBindFramebuffer(GL_FRAMEBUFFER, 0);

  frame.timings = timer.times();
  frame.glRenderer = impl.context.renderer();
  frame.glVersion = impl.context.version();
  frame.backend = std::string(backendName(impl.context.backend())) + ": " + impl.context.description();
  frame.sceneSource = impl.scene.source;
  frame.sceneHash = impl.scene.sourceHash;
  return frame;
}

}  // namespace headlight

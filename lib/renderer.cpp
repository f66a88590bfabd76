// The frame, top to bottom: shadows (once per scene and size) -> the ambient
// tables (on demand) -> G-buffer -> the fullscreen passes the plan declared
// (direct light -> SSGI (-> blur) -> composite; lib/passes/frame_passes.cpp)
// -> transmission (scenes with KHR_materials_transmission) -> blend (scenes
// with alphaMode BLEND) -> read back every target but lit -> with
// antialiasing, each jittered sample's G-buffer, direct light, composite,
// transmission and blend again, averaged into lit (frame/antialias.hpp) ->
// read back lit. What runs, with which shader variant
// and into which attachments, is the frame plan's (frame/frame_plan.hpp);
// this file executes it. Each pass is timed between
// glFinish calls and checked for GL errors.
#include "headlight/renderer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <deque>
#include <memory>
#include <optional>
#include <span>
#include <vector>

#include "context/context_access.hpp"
#include "frame/antialias.hpp"
#include "frame/frame_plan.hpp"
#include "frame/resolve.hpp"
#include "gl/gpu_scene.hpp"
#include "gl/objects.hpp"
#include "gl/readback.hpp"
#include "gl/target_formats.hpp"
#include "headlight/error.hpp"
#include "headlight/targets.hpp"
#include "image_io/environment_decode.hpp"
#include "passes/blend.hpp"
#include "passes/environment.hpp"
#include "passes/frame_block.hpp"
#include "passes/frame_pass.hpp"
#include "passes/gbuffer.hpp"
#include "passes/shadow.hpp"
#include "passes/transmission.hpp"
#include "passes/virtual_lights.hpp"
#include "scene/ids.hpp"
#include "shared_layout.h"

namespace headlight {
namespace {

// Times each pass and reports its GL errors by name. Synchronous (render()):
// each pass runs between two glFinish calls, so its wall time is the GPU's
// plus the CPU side that llvmpipe also spends (and a first frame's shader
// compiles), and inside a GL_TIME_ELAPSED query read at once. Pipelined
// (submit()): no glFinish, so the GPU runs on while the CPU queues the next
// pass or frame; the wall time is the CPU's queueing, and the queries are
// read when the frame is collected.
class PassTimer {
 public:
  PassTimer(Context& context, bool synchronous) : context_(context), synchronous_(synchronous) {}
  // `form`: a fullscreen pass's, recorded with its time.
  template <class Work>
  void run(std::string_view pass, Work&& work, std::optional<PassForm> form = std::nullopt) {
    if (synchronous_) glFinish();
    // Synchronous: one query, read at once; pipelined: one a pass, read at collection.
    gl::Query query = synchronous_ && reusable_ ? std::move(reusable_) : gl::Query::create(GL_TIME_ELAPSED);
    const auto start = std::chrono::steady_clock::now();
    glBeginQuery(GL_TIME_ELAPSED, query.id());
    work();
    glEndQuery(GL_TIME_ELAPSED);
    if (synchronous_) glFinish();
    const auto end = std::chrono::steady_clock::now();
    context_.checkErrors(std::string(pass));
    const double wall = std::chrono::duration<double, std::milli>(end - start).count();
    times_.push_back({std::string(pass), wall, -1, form ? std::string(passFormName(*form)) : std::string(), {}});
    queries_.push_back(std::move(query));
    if (synchronous_) resolve(times_.size() - 1, wall * 1.5 + 1.0);
  }
  // Records `pass` as taking `milliseconds` of wall time, with no GPU time (the readback's wait).
  void record(std::string_view pass, double milliseconds) {
    times_.push_back({std::string(pass), milliseconds, -1, {}, {}});
    queries_.emplace_back();
  }
  // Says what the last pass made (PassTime::detail).
  void describeLast(std::string detail) { times_.back().detail = std::move(detail); }
  // The pipelined passes' GPU times, once the frame's work is done; none
  // may exceed `frameMilliseconds`, the wall time from submission to collection.
  std::vector<PassTime> collect(double frameMilliseconds) {
    if (!synchronous_)
      for (std::size_t i = 0; i < times_.size(); ++i) resolve(i, frameMilliseconds);
    return times_;
  }

 private:
  // The query's work lies within `bound` (the wall time around it), so a
  // longer answer is the driver's, not the GPU's (llvmpipe answers a
  // context's first query with its clock since start, ~2e6 ms), and is
  // reported as unknown. Loose: the two clocks differ by a little on tiny passes.
  void resolve(std::size_t index, double bound) {
    if (!queries_[index]) return;
    const double gpu = double(queries_[index].result()) * 1e-6;
    times_[index].gpuMilliseconds = gpu > bound ? -1 : gpu;
    reusable_ = std::move(queries_[index]);
  }

  Context& context_;
  const bool synchronous_;
  std::vector<PassTime> times_;
  std::vector<gl::Query> queries_;  // by times_ index; empty once read
  gl::Query reusable_;              // a read query, for the next pass
};

// A frame between submit() and collect(): everything but its targets' pixels
// and its GPU times, which the GPU is still producing.
struct PendingFrame {
  Frame frame;
  std::vector<std::pair<ImageF Frame::*, PendingImage>> images;  // the targets read back
  std::unique_ptr<PassTimer> timer;
  gl::Fence fence;             // after the last copy
  double readbackQueueMs = 0;  // the CPU's time queueing the copies
  std::chrono::steady_clock::time_point submitted;
};

// The most frames submitted and not yet collected: enough for frame N+1's
// GPU work to overlap frame N's readback, and a bound on the pixel buffers held.
constexpr std::size_t kMaxPendingFrames = 2;

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

}  // namespace

struct Renderer::Impl {
  explicit Impl(Context& context) : context(context), softwareRasterizer(isSoftwareRasterizer(context.renderer())) {
    context.checkErrors("building the renderer");
  }
  void loadScene(Scene newScene);  // Renderer::setScene's work

  Context& context;
  const bool softwareRasterizer;  // llvmpipe and the like: fullscreen-form auto's per-pass choice
  ResourceLimits limits;
  std::uint64_t sceneBytes = 0;  // estimateSceneBytes of the current scene
  EnvironmentPass environment;
  // The fullscreen passes' GL sides, by row (fullscreenPassRows()), made
  // when a frame first runs them.
  std::vector<std::unique_ptr<FramePass>> framePasses{fullscreenPassRows().size()};
  ShadowPass shadow;
  BlendPass blend;
  TransmissionPass transmission;
  VirtualLightPass virtualLightPass;
  LightFieldPass lightFieldPass;
  gl::Buffer frameBlock = gl::Buffer::create(sizeof(gpu::FrameBlock));
  gl::Buffer lightingBlock = gl::Buffer::create(sizeof(gpu::LightingBlock));

  // Per scene.
  Scene scene;
  SceneSummary summary;
  std::shared_ptr<const IdNames> idNames;  // made for the first frame with ids
  std::optional<GpuScene> gpuScene;
  std::optional<GBufferPass> gbufferPass;
  gl::Buffer lightBuffer;                 // scene.lights packed, with the shadow slots of shadowMaps
  ShadowMaps shadowMaps;                  // kept across views: they do not depend on the camera
  int shadowMapSize = 0;                  // what shadowMaps were made with; 0 = none yet
  std::vector<glm::vec4> shadowCoverage;  // and what the directional ones cover
  // The bitmask SSGI's virtual lights: the scene's, not the view's, so made
  // once per scene and budget (0 = none yet).
  VirtualLights virtualLights;
  int virtualLightBudget = 0;
  // The light field they fill: also the scene's (0: none yet).
  LightField lightField;
  int lightFieldBudget = 0;

  // Per image size: the plan's attachments (attachmentRows()), by Attachment.
  FrameTextures textures;
  int width = 0, height = 0;

  const gl::Texture& texture(Attachment id) const { return textures[std::size_t(id)]; }

  FramePass& framePass(std::size_t row) {
    std::unique_ptr<FramePass>& pass = framePasses[row];
    if (!pass) pass = makeFramePass(row);
    return *pass;
  }

  // Allocates what the plan draws into and releases what it does not.
  void ensureAttachments(const FramePlan& plan, int imageWidth, int imageHeight) {
    width = imageWidth;
    height = imageHeight;
    for (const AttachmentRow& row : attachmentRows()) {
      gl::Texture& texture = textures[std::size_t(row.id)];
      const int divisor = plan.divisorOf(row.id);
      const int w = (width + divisor - 1) / divisor, h = (height + divisor - 1) / divisor;
      if (!plan.allocates(row.id))
        texture = gl::Texture();
      else if (const GLenum format = gl::internalFormat(plan.formatOf(row.id));
               texture.width() != w || texture.height() != h || texture.internalFormat() != format)
        texture = gl::Texture::create2D(format, w, h);
    }
  }

  // What the G-buffer pass draws into: its colour attachments by location.
  GBufferTargets gbufferTargets(const GBufferVariant& variant) const {
    GBufferTargets targets{{}, &texture(Attachment::GbufferDepth), width, height};
    for (Attachment id : variant.colorAttachments) targets.colors.push_back(&texture(id));
    return targets;
  }

  // The light buffer: the scene's lights, each with its slot in the shadow
  // maps (none without slots).
  void uploadLights(std::span<const ShadowSlot> slots) {
    const std::vector<gpu::GpuLight> lights = packLights(scene.lights, slots);
    lightBuffer.update(lights.data(), lights.size() * sizeof(gpu::GpuLight));
  }

  void renderShadows(const ShadowStep& step, const CameraView& view) {
    ShadowOutputs shadows = shadow.run(*gpuScene, scene.lights, step.mapSize, &view, step.transmittance);
    const int size = step.mapSize;
    shadowMaps = std::move(shadows.maps);
    shadowMapSize = size;
    shadowCoverage = directionalCoverage(scene.lights, gpuScene->bounds, &view);
    uploadLights(shadows.slots);
  }

  // The maps are kept across views unless their size or a directional
  // light's fit to the view would change.
  bool shadowsCurrent(const ShadowStep& step, const CameraView& view) const {
    return shadowMapSize == step.mapSize && shadowMaps.transmittance() == step.transmittance &&
           directionalCoverage(scene.lights, gpuScene->bounds, &view) == shadowCoverage;
  }

  // Each light's views drawn into small G-buffers and read back as virtual
  // lights; the frame block is the frame's again afterwards.
  void makeVirtualLights(int budget, const GBufferVariant& variant, const gpu::FrameBlock& frame) {
    virtualLights = virtualLightPass.run(
        *gpuScene, *gbufferPass, variant, scene.lights, budget,
        [&](const CameraView& view, int size) { frameBlock.update(makeFrameBlock(view, size, size)); });
    virtualLightBudget = budget;
    lightFieldBudget = 0;  // filled from the lights it had
    frameBlock.update(frame);
  }

  // The light field's probes drawn and filled from the virtual lights; the
  // frame block is the frame's again afterwards.
  void makeLightField(int budget, const GBufferVariant& variant, const gpu::FrameBlock& frame) {
    const int probes = lightFieldProbeBudget(budget, scene.instances.size(), scene.triangleCount(), limits);
    lightField = lightFieldPass.run(
        *gpuScene, *gbufferPass, variant, virtualLights.entries, probes,
        [&](const CameraView& view, int size) { frameBlock.update(makeFrameBlock(view, size, size)); });
    lightField.requested = budget;
    lightFieldBudget = budget;
    frameBlock.update(frame);
  }

  void dropShadows() {
    if (shadowMapSize == 0) return;
    shadowMaps = ShadowMaps{};
    shadowMapSize = 0;
    uploadLights({});
  }

  // The block the direct-light and composite passes read, and the lights.
  // The ambient's intensity is the environment map's when there is one
  // (it replaces the sky), else the sky's.
  void bindLighting(const LightingSettings& lighting) {
    gpu::LightingBlock block{};
    const float pcfRadius = lighting.pcfRadius;
    block.skyIntensity = scene.environment ? lighting.environmentIntensity : *lighting.skyIntensity;
    const float turn = glm::radians(lighting.environmentRotation);
    block.environmentRotationCos = std::cos(turn);
    block.environmentRotationSin = std::sin(turn);
    block.environmentBackground = lighting.environmentBackground ? 1 : 0;
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
        throw SettingsError("camera " + std::to_string(*settings.camera) + ": " + scene.source + " has " +
                                std::to_string(scene.cameras.size()) + " camera(s)",
                            {"camera"});
      return scene.cameras[std::size_t(*settings.camera)];
    }
    if (!scene.cameras.empty()) return scene.cameras.front();
    fitted = fitCamera(scene.worldBounds(), float(settings.width) / float(settings.height));
    return fitted;
  }

  // Starts reading each planned target whose afterAntialias is `antialiased`
  // from its attachments (depth as view depth); a target with no source is
  // zeros of the image's size at once.
  void startReads(const FramePlan& plan, PendingFrame& pending, bool antialiased) {
    Frame& frame = pending.frame;
    for (const TargetRead& read : plan.reads) {
      if (read.afterAntialias != antialiased) continue;
      const FrameTarget& target = *read.target;
      const std::vector<std::string>& channels = read.channels;
      if (read.sources.empty()) {
        ImageF& image = frame.*target.image;
        image.width = width;
        image.height = height;
        image.channels = channels;
        image.pixels.assign(std::size_t(width) * std::size_t(height) * channels.size(), 0.0f);
        continue;
      }
      std::vector<const gl::Texture*> sources;
      for (Attachment id : read.sources) sources.push_back(&texture(id));
      // Through pixel buffers on a GPU; directly on a software rasteriser, which copies at the call anyway.
      const ReadPath path = softwareRasterizer ? ReadPath::Direct : ReadPath::PixelBuffer;
      pending.images.emplace_back(target.image, attachmentRow(read.sources.front()).format == GpuFormat::Depth32F
                                                    ? PendingImage::viewDepth(*sources.front(), frame.view,
                                                                              channels.front(), path, &readbackBuffers)
                                                    : PendingImage::color(sources, channels, path, &readbackBuffers));
    }
  }

  // Draws `view` (whose frame block is bound): the G-buffer, the plan's
  // fullscreen passes at `passes` (indices into plan.passes), transmission
  // and blend. `run(name, work, form)` runs each step: timed apart for the
  // centre's view, as they are inside the antialias entry for a jittered one.
  template <class Run>
  void drawView(const FramePlan& plan, const FrameInputs& inputs, const PassForms& forms, const CameraView& view,
                std::span<const std::size_t> passes, Run&& run) {
    run(
        "gbuffer", [&] { gbufferPass->run(*gpuScene, gbufferTargets(plan.gbuffer), plan.gbuffer); }, std::nullopt);
    // The fullscreen passes, as the plan declared them: each binds what it
    // reads and writes what it declared.
    for (std::size_t index : passes) {
      const PassDeclaration& pass = plan.passes[index];
      const PassForm form = forms[pass.row];
      run(
          fullscreenPassRows()[pass.row].name, [&] { runFramePass(framePass(pass.row), pass, inputs, textures, form); },
          form);
    }
    if (plan.transmission) {
      const GBufferTargets targets = gbufferTargets(plan.gbuffer);
      const TransmissionInputs transmissionInputs{*gpuScene,    *gbufferPass, targets,
                                                  plan.gbuffer, shadowMaps,   environment.tables()};
      const TransmissionTargets outputs{texture(Attachment::Lit), texture(Attachment::Transmission), width, height};
      run(
          "transmission", [&] { transmission.run(transmissionInputs, outputs, *plan.transmission); }, std::nullopt);
    }
    if (plan.blend) {
      const BlendInputs blendInputs{*gpuScene, view, texture(Attachment::GbufferDepth), shadowMaps,
                                    environment.tables()};
      const BlendTargets outputs{texture(Attachment::Lit), texture(Attachment::BlendCoverage), width, height};
      run(
          "blend", [&] { blend.run(blendInputs, outputs, *plan.blend); }, std::nullopt);
    }
  }

  // Queues one frame: its passes, then the copies of its targets.
  PendingFrame submitFrame(const RenderSettings& settings, const Camera* camera, std::span<const std::string> targets,
                           bool synchronous);
  // Waits for a submitted frame's copies and finishes it.
  Frame collectFrame(PendingFrame pending);

  // Pixel buffers for the next frame's copies (GPU path; the direct path needs none).
  ReadbackBuffers readbackBuffers;
  // Frames submitted and not yet collected, oldest first.
  std::deque<PendingFrame> pending;
};

// Every entry point checks that its context is current on the calling thread:
// a GL call through another thread's context (or none) would crash or draw
// into the wrong context.
Renderer::Renderer(Context& context)
    : impl_((context.requireCurrent("headlight::Renderer"), detail::ContextAccess::lockBackend(context),
             std::make_unique<Impl>(context))) {}
// The GL objects are deleted in their own context: a renderer destroyed on a
// thread where another context is current makes its own current first (and
// leaves it current); if that fails, the names are left to the context's
// destruction rather than deleted in the wrong context.
Renderer::~Renderer() {
  if (!impl_) return;
  auto lock = detail::ContextAccess::lockBackend(impl_->context);
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
  auto lock = detail::ContextAccess::lockBackend(impl.context);
  impl.gbufferPass.reset();
  impl.gpuScene.reset();
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
  if (newScene.environment)
    impl.sceneBytes += std::uint64_t(newScene.environment->width) * std::uint64_t(newScene.environment->height) *
                       detail::kEnvironmentBytesPerTexel;
  if (impl.sceneBytes > maxMemoryBytes(impl.limits))
    throw LimitError(newScene.source + ": the scene needs about " + std::to_string(impl.sceneBytes >> 20) +
                         " MiB, more than max-memory allows (" + std::to_string(maxMemoryBytes(impl.limits) >> 20) +
                         " MiB)",
                     {"max-memory"});
  impl.scene = std::move(newScene);
  if (impl.scene.lights.empty()) impl.scene.lights.push_back(defaultKeyLight());
  impl.gpuScene.emplace(uploadScene(impl.scene));
  impl.summary = summarizeScene(impl.scene);
  impl.idNames.reset();
  // The default settings' G-buffer variant, for the G-buffer pass's draw groups.
  const FramePlan plan = planFrame(impl.summary, resolveSettings(RenderSettings{}, impl.scene), {});
  impl.gbufferPass.emplace(*impl.gpuScene, plan.gbuffer);
  // At least one element: a zero-sized buffer cannot be bound.
  impl.lightBuffer = gl::Buffer::create(std::max<std::size_t>(1, impl.scene.lights.size()) * sizeof(gpu::GpuLight));
  impl.uploadLights({});
  impl.shadowMaps = ShadowMaps{};
  impl.shadowMapSize = 0;
  impl.virtualLights = VirtualLights{};
  impl.virtualLightBudget = 0;
  impl.lightField = LightField{};
  impl.lightFieldBudget = 0;
  // A map's tables are kept across scenes that share it (a batch); a scene
  // without one releases them.
  if (!impl.scene.environment) impl.environment.dropEnvironment();
  // The other passes' programs are built when a frame first runs them: a
  // frame compiles only what its plan draws (--targets depth: no lighting).
  impl.context.checkErrors("uploading " + impl.scene.source);
}

const Scene& Renderer::scene() const { return impl_->scene; }

RenderSettings Renderer::resolve(const RenderSettings& settings) const {
  return resolveSettings(settings, impl_->scene);
}

PendingFrame Renderer::Impl::submitFrame(const RenderSettings& settings, const Camera* camera,
                                         std::span<const std::string> targets, bool synchronous) {
  Impl& impl = *this;
  if (!impl.gpuScene || !impl.gbufferPass) throw SettingsError("Renderer::render: no scene (call setScene first)");
  PendingFrame pending;
  pending.submitted = std::chrono::steady_clock::now();
  Frame& frame = pending.frame;
  frame.settings = resolveSettings(settings, impl.scene);
  const RenderSettings& used = frame.settings;
  // Before any target of this size is allocated.
  // A scene that transmits also holds lit's mip-mapped copy and the transmission target.
  const std::uint64_t transmissionBytes =
      impl.summary.transmission ? std::uint64_t(used.width) * std::uint64_t(used.height) * kTransmissionBytesPerPixel
                                : 0;
  // And the lights' shadow maps: a file's many point lights would hold 24 MiB each at 2048.
  std::uint64_t shadowBytes = 0;
  if (used.lighting.shadows) {
    const ShadowCasters casters{impl.summary.planarShadowCasters, impl.summary.cubeShadowCasters};
    const int size = used.lighting.shadowMapSize.value_or(0);
    shadowBytes = checkShadowMapsFit(impl.scene.source, casters, size, impl.summary.transmission,
                                     estimateFrameBytes(used.width, used.height) + impl.sceneBytes + transmissionBytes,
                                     impl.limits);
  }
  checkFrameFits(used.width, used.height, impl.sceneBytes + transmissionBytes + shadowBytes, impl.limits);
  Camera fitted;
  frame.view =
      makeCameraView(impl.chooseCamera(used, camera, fitted), impl.scene.worldBounds(), used.width, used.height);

  const FramePlan plan = planFrame(impl.summary, used, targets);
  // Each antialias sample draws the view again: bounded like the rest, before any of it.
  const int viewDraws = plan.antialias ? 1 + plan.antialias->samples : 1;
  if (plan.antialias) checkDrawBudget(impl.scene, impl.limits, viewDraws);
  if (plan.blend) checkBlendBudget(impl.scene, frame.view, used.width, used.height, viewDraws, impl.limits);
  frame.skipped = plan.skipped;
  impl.ensureAttachments(plan, used.width, used.height);
  const gpu::FrameBlock frameBlock = makeFrameBlock(frame.view, used.width, used.height);
  impl.frameBlock.update(frameBlock);
  impl.frameBlock.bindUniform(gpu::FrameBlock::kBinding);

  // How each fullscreen pass runs this frame (fragment or compute), by row.
  const PassForms forms = choosePassForms(used.fullscreenForm, impl.softwareRasterizer);
  const PassForm tableForm = forms[fullscreenPassIndex("sky")];
  pending.timer = std::make_unique<PassTimer>(impl.context, synchronous);
  PassTimer& timer = *pending.timer;
  // Shadow maps are remade only when their size or what the directional
  // ones cover changes; with shadows off the lights read "no map".
  if (plan.dropShadowMaps) impl.dropShadows();
  if (plan.shadows && !impl.shadowsCurrent(*plan.shadows, frame.view))
    timer.run("shadows", [&] { impl.renderShadows(*plan.shadows, frame.view); });
  if (plan.ssgi && plan.ssgi->virtualLights > 0 && impl.virtualLightBudget != plan.ssgi->virtualLights)
    timer.run("virtual-lights", [&] { impl.makeVirtualLights(plan.ssgi->virtualLights, plan.gbuffer, frameBlock); });
  if (plan.ssgi && plan.ssgi->lightFieldProbes > 0 && impl.lightFieldBudget != plan.ssgi->lightFieldProbes) {
    timer.run("light-field", [&] { impl.makeLightField(plan.ssgi->lightFieldProbes, plan.gbuffer, frameBlock); });
    timer.describeLast(describeLightField(impl.lightField));
  }
  // The split-sum BRDF table once per renderer, the sky tables on the first
  // frame that needs them (and again only when the sky's colours change),
  // the environment's once per map: ahead of the passes that read them.
  if ((plan.composite || plan.transmission || plan.blend) && !impl.environment.hasBrdfTable())
    timer.run(
        "brdf-table", [&] { impl.environment.makeBrdfTable(tableForm); }, tableForm);
  if (plan.skyTables && !impl.environment.holds(impl.scene.sky))
    timer.run(
        "sky", [&] { impl.environment.updateSky(impl.scene.sky, tableForm); }, tableForm);
  if (plan.environmentTables && !impl.environment.holdsEnvironment(*impl.scene.environment))
    timer.run("environment", [&] { impl.environment.updateEnvironment(*impl.scene.environment); });
  impl.bindLighting(used.lighting);
  // The view at the pixel centres: every pass, each timed apart.
  const FrameInputs inputs{plan, used, impl.shadowMaps, impl.environment.tables(), impl.virtualLights, impl.lightField};
  std::vector<std::size_t> allPasses(plan.passes.size());
  for (std::size_t index = 0; index < allPasses.size(); ++index) allPasses[index] = index;
  impl.drawView(plan, inputs, forms, frame.view, allPasses,
                [&](std::string_view pass, auto&& work, std::optional<PassForm> form) { timer.run(pass, work, form); });
  // Every target but lit is the centre's: read before a jittered sample overwrites it.
  const auto readStart = std::chrono::steady_clock::now();
  impl.startReads(plan, pending, false);
  double readQueueMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - readStart).count();
  if (plan.antialias) {
    // Each sample's view drawn again, timed as one entry: what antialiasing costs.
    const std::size_t accumulateRow = fullscreenPassIndex("antialias");
    timer.run("antialias", [&] {
      for (int sample = 0; sample < plan.antialias->samples; ++sample) {
        const CameraView view =
            jitteredView(frame.view, antialiasOffset(sample, plan.antialias->samples), used.width, used.height);
        impl.frameBlock.update(makeFrameBlock(view, used.width, used.height));
        // A sample's own SSGI gets its own noise: the seed moved past the frames' rotations.
        RenderSettings sampleSettings = used;
        sampleSettings.ssgi.seed += unsigned((sample + 1) * used.ssgi.frames);
        FrameInputs sampleInputs{
            plan,  sampleSettings, impl.shadowMaps, impl.environment.tables(), impl.virtualLights, impl.lightField,
            sample};
        impl.drawView(plan, sampleInputs, forms, view, plan.antialias->perSamplePasses,
                      [](std::string_view, auto&& work, std::optional<PassForm>) { work(); });
        runFramePass(impl.framePass(accumulateRow), plan.antialias->accumulate, sampleInputs, impl.textures,
                     forms[accumulateRow]);
      }
      impl.frameBlock.update(frameBlock);
    });
  }
  // The copies are queued behind the passes; the pixels come back in
  // collectFrame, whose "readback" time includes this queueing.
  const auto antialiasedReadStart = std::chrono::steady_clock::now();
  impl.startReads(plan, pending, true);
  if (plan.antialias && plan.antialias->foreground) {
    const gl::Texture* foreground[] = {&impl.texture(Attachment::LitForeground)};
    pending.images.emplace_back(
        &Frame::litForeground,
        PendingImage::color(foreground, {"R", "G", "B", "A"},
                            impl.softwareRasterizer ? ReadPath::Direct : ReadPath::PixelBuffer, &impl.readbackBuffers));
  }
  impl.context.checkErrors("readback");
  readQueueMs +=
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - antialiasedReadStart).count();
  pending.readbackQueueMs = readQueueMs;
  if (!synchronous) {
    pending.fence = gl::Fence::insert();
    glFlush();  // the GPU starts on this frame while the CPU goes on
  }
  glBindFramebuffer(GL_FRAMEBUFFER, 0);

  frame.glRenderer = impl.context.renderer();
  frame.glVersion = impl.context.version();
  frame.backend = std::string(backendName(impl.context.backend())) + ": " + impl.context.description();
  frame.sceneSource = impl.scene.source;
  frame.sceneHash = impl.scene.sourceHash;
  frame.scenePose = impl.scene.poseDescription();
  if (plan.allocates(Attachment::GbufferIds)) {
    if (!impl.idNames) impl.idNames = std::make_shared<const IdNames>(makeIdNames(impl.scene));
    frame.idNames = impl.idNames;
  }
  for (const IgnoredFeature& feature : impl.scene.ignored) frame.ignored.push_back(feature.describe());
  frame.ignored.insert(frame.ignored.end(), plan.unrendered.begin(), plan.unrendered.end());
  return pending;
}

Frame Renderer::Impl::collectFrame(PendingFrame pending) {
  const auto start = std::chrono::steady_clock::now();
  pending.fence.wait();
  for (auto& [member, image] : pending.images) pending.frame.*member = image.finish();
  readbackBuffers.trim();
  context.checkErrors("readback");
  const auto end = std::chrono::steady_clock::now();
  pending.timer->record("readback",
                        pending.readbackQueueMs + std::chrono::duration<double, std::milli>(end - start).count());
  pending.frame.timings =
      pending.timer->collect(std::chrono::duration<double, std::milli>(end - pending.submitted).count());
  return std::move(pending.frame);
}

Frame Renderer::render(const RenderSettings& settings, const Camera* camera, std::span<const std::string> targets) {
  Impl& impl = *impl_;
  impl.context.requireCurrent("Renderer::render");
  auto lock = detail::ContextAccess::lockBackend(impl.context);
  return impl.collectFrame(impl.submitFrame(settings, camera, targets, true));
}

void Renderer::submit(const RenderSettings& settings, const Camera* camera, std::span<const std::string> targets) {
  Impl& impl = *impl_;
  impl.context.requireCurrent("Renderer::submit");
  auto lock = detail::ContextAccess::lockBackend(impl.context);
  if (impl.pending.size() >= kMaxPendingFrames)
    throw SettingsError("Renderer::submit: " + std::to_string(impl.pending.size()) +
                        " frames are submitted and not collected (at most " + std::to_string(kMaxPendingFrames) +
                        "): collect() first");
  // On a software rasteriser the passes stay bounded by glFinish: llvmpipe
  // renders on the CPU's cores, which the next frame's queueing would only
  // contend for (a batch of 20 views at 640x480 took 1.06-1.26x as long
  // without; docs/BENCHMARKS.md, "Readback and pipelined frames").
  impl.pending.push_back(impl.submitFrame(settings, camera, targets, impl.softwareRasterizer));
}

Frame Renderer::collect() {
  Impl& impl = *impl_;
  impl.context.requireCurrent("Renderer::collect");
  auto lock = detail::ContextAccess::lockBackend(impl.context);
  if (impl.pending.empty()) throw SettingsError("Renderer::collect: no frame submitted");
  PendingFrame oldest = std::move(impl.pending.front());
  impl.pending.pop_front();
  return impl.collectFrame(std::move(oldest));
}

std::size_t Renderer::submitted() const { return impl_->pending.size(); }

}  // namespace headlight

// The frame, top to bottom: shadows (once per scene and size) -> the ambient
// tables (on demand) -> G-buffer -> the fullscreen passes the plan declared
// (direct light -> SSGI (-> blur) -> composite; lib/passes/frame_passes.cpp)
// -> transmission (scenes with KHR_materials_transmission) -> blend (scenes
// with alphaMode BLEND) -> read back. What runs, with which shader variant
// and into which attachments, is the frame plan's (frame/frame_plan.hpp);
// this file executes it. Each pass is timed between
// glFinish calls and checked for GL errors.
#include "headlight/renderer.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <chrono>
#include <cmath>
#include <optional>
#include <span>
#include <vector>

#include "context/context_access.hpp"
#include "frame/frame_plan.hpp"
#include "frame/resolve.hpp"
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
#include "scene/gpu_scene.hpp"
#include "shared_layout.h"

namespace headlight {
namespace {

// Runs GL work between two glFinish calls, so the wall time is the GPU's
// plus the CPU side that llvmpipe also spends (and a first frame's shader
// compiles), and inside a GL_TIME_ELAPSED query, which times the GPU's own
// work as the GPU sees it; reports the pass's GL errors by name.
class PassTimer {
 public:
  explicit PassTimer(Context& context) : context_(context), query_(gl::Query::create(GL_TIME_ELAPSED)) {}
  // `form`: a fullscreen pass's, recorded with its time.
  template <class Work>
  void run(std::string_view pass, Work&& work, std::optional<PassForm> form = std::nullopt) {
    glFinish();
    const auto start = std::chrono::steady_clock::now();
    glBeginQuery(GL_TIME_ELAPSED, query_.id());
    work();
    glEndQuery(GL_TIME_ELAPSED);
    glFinish();
    const auto end = std::chrono::steady_clock::now();
    context_.checkErrors(std::string(pass));
    const double wall = std::chrono::duration<double, std::milli>(end - start).count();
    // The query's work lies between the two glFinish calls, so it cannot take
    // longer than they are apart: a longer answer is the driver's, not the
    // GPU's (llvmpipe answers a context's first query with its clock since
    // start, ~2e6 ms), and is reported as unknown.
    double gpu = double(query_.result()) * 1e-6;
    if (gpu > wall * 1.5 + 1.0) gpu = -1;  // loose: the two clocks differ by a little on tiny passes
    times_.push_back({std::string(pass), wall, gpu, form ? std::string(passFormName(*form)) : std::string()});
  }
  std::vector<PassTime> times() const { return times_; }

 private:
  Context& context_;
  gl::Query query_;  // one at a time: passes are not nested
  std::vector<PassTime> times_;
};

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
  gl::Buffer frameBlock = gl::Buffer::create(sizeof(gpu::FrameBlock));
  gl::Buffer lightingBlock = gl::Buffer::create(sizeof(gpu::LightingBlock));

  // Per scene.
  Scene scene;
  SceneSummary summary;
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

  void renderShadows(int size, const CameraView& view) {
    ShadowOutputs shadows = shadow.run(*gpuScene, scene.lights, size, &view);
    shadowMaps = std::move(shadows.maps);
    shadowMapSize = size;
    shadowCoverage = directionalCoverage(scene.lights, gpuScene->bounds, &view);
    uploadLights(shadows.slots);
  }

  // The maps are kept across views unless their size or a directional
  // light's fit to the view would change.
  bool shadowsCurrent(int size, const CameraView& view) const {
    return shadowMapSize == size && directionalCoverage(scene.lights, gpuScene->bounds, &view) == shadowCoverage;
  }

  // Each light's views drawn into small G-buffers and read back as virtual
  // lights; the frame block is the frame's again afterwards.
  void makeVirtualLights(int budget, const GBufferVariant& variant, const gpu::FrameBlock& frame) {
    virtualLights = virtualLightPass.run(
        *gpuScene, *gbufferPass, variant, scene.lights, budget,
        [&](const CameraView& view, int size) { frameBlock.update(makeFrameBlock(view, size, size)); });
    virtualLightBudget = budget;
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

  // Reads each planned target from its attachments (depth as view depth; a
  // target with no source as zeros of the image's size).
  void readTargets(const FramePlan& plan, Frame& frame) const {
    for (const TargetRead& read : plan.reads) {
      const FrameTarget& target = *read.target;
      ImageF& image = frame.*target.image;
      const std::vector<std::string>& channels = read.channels;
      if (read.sources.empty()) {
        image.width = width;
        image.height = height;
        image.channels = channels;
        image.pixels.assign(std::size_t(width) * std::size_t(height) * channels.size(), 0.0f);
        continue;
      }
      std::vector<const gl::Texture*> sources;
      for (Attachment id : read.sources) sources.push_back(&texture(id));
      image = attachmentRow(read.sources.front()).format == GpuFormat::Depth32F
                  ? readViewDepth(*sources.front(), frame.view, channels.front())
                  : readColor(sources, channels);
    }
  }
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

Frame Renderer::render(const RenderSettings& settings, const Camera* camera, std::span<const std::string> targets) {
  Impl& impl = *impl_;
  impl.context.requireCurrent("Renderer::render");
  auto lock = detail::ContextAccess::lockBackend(impl.context);
  if (!impl.gpuScene || !impl.gbufferPass) throw SettingsError("Renderer::render: no scene (call setScene first)");
  Frame frame;
  frame.settings = resolve(settings);
  const RenderSettings& used = frame.settings;
  // Before any target of this size is allocated.
  // A scene that transmits also holds lit's mip-mapped copy and the transmission target.
  const std::uint64_t transmissionBytes =
      impl.summary.transmission ? std::uint64_t(used.width) * std::uint64_t(used.height) * kTransmissionBytesPerPixel
                                : 0;
  checkFrameFits(used.width, used.height, impl.sceneBytes + transmissionBytes, impl.limits);
  Camera fitted;
  frame.view =
      makeCameraView(impl.chooseCamera(used, camera, fitted), impl.scene.worldBounds(), used.width, used.height);

  const FramePlan plan = planFrame(impl.summary, used, targets);
  frame.skipped = plan.skipped;
  impl.ensureAttachments(plan, used.width, used.height);
  const gpu::FrameBlock frameBlock = makeFrameBlock(frame.view, used.width, used.height);
  impl.frameBlock.update(frameBlock);
  impl.frameBlock.bindUniform(gpu::FrameBlock::kBinding);

  // How each fullscreen pass runs this frame (fragment or compute), by row.
  const PassForms forms = choosePassForms(used.fullscreenForm, impl.softwareRasterizer);
  const PassForm tableForm = forms[fullscreenPassIndex("sky")];
  PassTimer timer(impl.context);
  // Shadow maps are remade only when their size or what the directional
  // ones cover changes; with shadows off the lights read "no map".
  if (plan.dropShadowMaps) impl.dropShadows();
  if (plan.shadows && !impl.shadowsCurrent(plan.shadows->mapSize, frame.view))
    timer.run("shadows", [&] { impl.renderShadows(plan.shadows->mapSize, frame.view); });
  if (plan.ssgi && plan.ssgi->virtualLights > 0 && impl.virtualLightBudget != plan.ssgi->virtualLights)
    timer.run("virtual-lights", [&] { impl.makeVirtualLights(plan.ssgi->virtualLights, plan.gbuffer, frameBlock); });
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
  timer.run("gbuffer", [&] { impl.gbufferPass->run(*impl.gpuScene, impl.gbufferTargets(plan.gbuffer), plan.gbuffer); });
  // The fullscreen passes, as the plan declared them: each binds what it
  // reads and writes what it declared.
  const FrameInputs inputs{plan, used, impl.shadowMaps, impl.environment.tables(), impl.virtualLights};
  for (const PassDeclaration& pass : plan.passes) {
    const PassForm form = forms[pass.row];
    timer.run(
        fullscreenPassRows()[pass.row].name,
        [&] { runFramePass(impl.framePass(pass.row), pass, inputs, impl.textures, form); }, form);
  }
  if (plan.transmission) {
    const GBufferTargets gbufferTargets = impl.gbufferTargets(plan.gbuffer);
    const TransmissionInputs inputs{*impl.gpuScene, *impl.gbufferPass, gbufferTargets,
                                    plan.gbuffer,   impl.shadowMaps,   impl.environment.tables()};
    const TransmissionTargets targets{impl.texture(Attachment::Lit), impl.texture(Attachment::Transmission), impl.width,
                                      impl.height};
    timer.run("transmission", [&] { impl.transmission.run(inputs, targets, *plan.transmission); });
  }
  if (plan.blend) {
    const BlendInputs inputs{*impl.gpuScene, frame.view, impl.texture(Attachment::GbufferDepth), impl.shadowMaps,
                             impl.environment.tables()};
    const BlendTargets targets{impl.texture(Attachment::Lit), impl.texture(Attachment::BlendCoverage), impl.width,
                               impl.height};
    timer.run("blend", [&] { impl.blend.run(inputs, targets, *plan.blend); });
  }
  timer.run("readback", [&] { impl.readTargets(plan, frame); });
  glBindFramebuffer(GL_FRAMEBUFFER, 0);

  frame.timings = timer.times();
  frame.glRenderer = impl.context.renderer();
  frame.glVersion = impl.context.version();
  frame.backend = std::string(backendName(impl.context.backend())) + ": " + impl.context.description();
  frame.sceneSource = impl.scene.source;
  frame.sceneHash = impl.scene.sourceHash;
  for (const IgnoredFeature& feature : impl.scene.ignored) frame.ignored.push_back(feature.describe());
  frame.ignored.insert(frame.ignored.end(), plan.unrendered.begin(), plan.unrendered.end());
  return frame;
}

}  // namespace headlight

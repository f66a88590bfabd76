#pragma once
// The deferred renderer. Make it once per context; give it a scene once;
// render as many views and sizes as you like into memory. Shaders are built
// when the renderer and the scene are set (a settings change that needs
// another variant, such as SSGI off, builds it once, on first use).
//
//   headlight::Context context;                    // EGL or OSMesa, 4.5 core
//   headlight::Renderer renderer(context);
//   renderer.setScene(headlight::loadScene("builtin:cornell"));
//   headlight::Frame frame = renderer.render(settings);   // float buffers
//   headlight::writeFrame(frame, "out/");                  // optional
#include <memory>
#include <span>
#include <string>

#include "headlight/context.hpp"
#include "headlight/export.hpp"
#include "headlight/frame.hpp"
#include "headlight/limits.hpp"
#include "headlight/scene.hpp"
#include "headlight/settings.hpp"

namespace headlight HEADLIGHT_PUBLIC {

class Renderer {
 public:
  // The context must outlive the renderer and be current on this thread.
  explicit Renderer(Context& context);
  ~Renderer();
  Renderer(const Renderer&) = delete;
  Renderer& operator=(const Renderer&) = delete;

  // Uploads the scene (a copy is kept for cameras, lights and bounds). A
  // scene without lights gets a default key light (a directional "sun").
  // Throws SceneError for values where float rendering would not stay
  // finite (checkSceneRanges) and LimitError for a scene over the limits.
  void setScene(Scene scene);

  // What setScene and render may use (default: ResourceLimits{}, so
  // max-memory's auto). render() refuses an image size whose estimated
  // memory (estimateFrameBytes) and the scene's do not fit, before allocating.
  void setLimits(const ResourceLimits& limits);
  const Scene& scene() const;

  // Renders one frame of the scene. `camera` overrides settings.camera.
  // `targets` names the frame targets (frameTargets(), headlight/targets.hpp)
  // to read back; passes that only other targets need are skipped (empty:
  // every target). Throws SettingsError for bad settings (or a camera index
  // the scene lacks) and GlError for GL errors under GlErrorPolicy::Throw.
  Frame render(const RenderSettings& settings, const Camera* camera = nullptr,
               std::span<const std::string> targets = {});

  // Pipelined rendering of many views: submit() queues one frame (its
  // passes, then the copy of its targets into pixel buffers) and returns
  // without waiting for the GPU; collect() returns the oldest submitted
  // frame, waiting only for its copies. Submit frame N+1 before collecting
  // frame N and the GPU draws N+1 while N's pixels come back. At most two
  // frames are submitted and not collected (SettingsError beyond). A
  // submitted frame's pass times are the CPU's queueing (no glFinish between
  // passes; GPU times from timer queries); render() is submit + collect with
  // every pass bounded by glFinish, and so is submit() on a software
  // rasteriser (llvmpipe), where the CPU renders and nothing overlaps. A frame's scene is the one set when it
  // was submitted. Errors are thrown by the call that meets them.
  void submit(const RenderSettings& settings, const Camera* camera = nullptr,
              std::span<const std::string> targets = {});
  Frame collect();
  std::size_t submitted() const;  // frames submitted and not yet collected

  // The settings render() would use: auto radius, bias and shadow-map size
  // resolved from the scene and image size.
  RenderSettings resolve(const RenderSettings& settings) const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace HEADLIGHT_PUBLIC

#pragma once
// Ray-traced ground truth (Embree 3) for what the SSGI pass approximates,
// pixel-aligned with a rendered Frame: the shading points are the G-buffer's
// positions and normals, so differences are the method's, not the
// rasteriser's. docs/ACCURACY.md defines every quantity with formulas.
#include <functional>
#include <span>
#include <string>

#include "headlight/export.hpp"
#include "headlight/frame.hpp"
#include "headlight/options.hpp"
#include "headlight/scene.hpp"

namespace headlight HEADLIGHT_PUBLIC {

struct ReferenceSettings {
  // Cosine-weighted hemisphere rays per pixel. 4096 keeps the mean AO
  // standard error under 0.005 on the built-ins at 128x96 (docs/ACCURACY.md).
  int samplesPerPixel = 4096;
  float radius = 0.0f;  // world units, > 0: the R of "within R" (pass the SSGI radius the frame used)
  unsigned seed = 1;    // per-pixel random streams derive from it: results do not depend on threads
  int threads = 0;      // 0 = all hardware threads
  // Within R, only surfaces the frame shows (in its view and not hidden
  // behind another) occlude and send light; a ray meeting a hidden one
  // there counts as open within R and brings no light. What a method that
  // reads only the screen could find at best: the screen-space bound
  // (docs/ACCURACY.md §2.5). Off: the truth.
  bool screenBound = false;
};

// The user-settable rows of ReferenceSettings (`reference` and `bench` read them).
std::span<const Option<ReferenceSettings>> referenceOptions();

struct ReferenceImages {
  // ao.Y: cosine-weighted fraction of the hemisphere with no geometry within
  // R (background counts as open); 1 on background pixels.
  // sky.Y: cosine-weighted fraction of the hemisphere whose rays escape the
  // scene (sky visibility at any distance, <= ao.Y); 1 on background pixels.
  ImageF ao;
  // indirectR.R/G/B: one-bounce indirect diffuse radiance gathered within R;
  // indirect.R/G/B: the same, unlimited distance. 0 on background.
  ImageF indirect;
  // R/G/B/A: direct light with shadow rays + sky ambient with true visibility
  // + one-bounce indirect (unlimited) + emission; A = coverage.
  ImageF lit;
  int samplesPerPixel = 0;
  bool screenBound = false;        // traced as the screen-space bound (ReferenceSettings::screenBound), not the truth
  double aoMeanStandardError = 0;  // mean over geometry pixels of sqrt(p(1-p)/(n-1))
  double aoMaxStandardError = 0;
  double indirectMeanStandardError = 0;  // of indirect (unlimited), mean over pixels and channels
  double seconds = 0;                    // wall time of the trace
};

// True when this build has Embree; traceReference throws otherwise.
bool referenceAvailable();

// Traces the reference for every geometry pixel of `frame`. `scene` must be
// the scene the frame was rendered from as the renderer holds it
// (Renderer::scene(), which includes the default key light if it added one).
// Throws SettingsError for bad settings, Error if Embree is missing or fails.
// `progress`, if given, is called on the calling thread about five times a
// second and once at the end with (rows started, rows): a 640x480 trace at
// 4096 rays takes minutes (`headlight reference` draws it as a bar with ETA).
ReferenceImages traceReference(const Scene& scene, const Frame& frame, const ReferenceSettings& settings,
                               const std::function<void(int rowsStarted, int rows)>& progress = {});

}  // namespace HEADLIGHT_PUBLIC

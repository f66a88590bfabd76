#pragma once
// Resource limits: how much a scene file and a render may ask for before
// anything is allocated. A file of a few kilobytes can otherwise claim
// gigabytes (an accessor of count 2^31, a node tree listed 100,000 times,
// 16384^2 textures); the loader and the renderer check these first and throw
// LimitError naming the file, the element, the limit and the setting that
// raises it (Error::settings()).
//
// Every field is a row of limitOptions() (max-memory, ...; the CLI's flags), with
// in-class defaults; docs/RELIABILITY.md gives the measured costs behind them.
#include <cstdint>
#include <optional>
#include <span>

#include "headlight/camera.hpp"
#include "headlight/export.hpp"
#include "headlight/options.hpp"
#include "headlight/scene.hpp"

namespace headlight HEADLIGHT_PUBLIC {

struct ResourceLimits {
  std::optional<std::int64_t>
      maxMemoryMiB;  // MiB, 64..2^30; auto: half of physical memory or of RLIMIT_AS, the smaller
  std::int64_t maxInstances = 1'000'000;           // drawn mesh primitives (node x primitive), 1..2^31
  std::int64_t maxTriangles = 10'000'000;          // decoded triangles, all primitives together, 1..2^31
  std::int64_t maxTexels = std::int64_t(1) << 28;  // decoded texels, all images together (1 GiB as RGBA8)
  // What one frame draws (drawPassCount passes over the scene), so that a
  // small file of many instances cannot take minutes a frame. Measured on
  // llvmpipe, 2 cores (docs/RELIABILITY.md): about 5 us a draw in the
  // G-buffer and 48 in a shadow view; 0.075 and 0.12 us a triangle.
  std::int64_t maxDraws = 150'000;              // instances x passes per frame, 1..2^40
  std::int64_t maxDrawnTriangles = 50'000'000;  // triangles x passes per frame, 1..2^40
  // The blend pass's fill: alphaMode BLEND instances x the pixels their
  // screen rectangles cover x views (checkBlendBudget). About 80 ns a pixel
  // on llvmpipe, 2 cores, draws included (docs/RELIABILITY.md).
  std::int64_t maxBlendedFragments = 100'000'000;  // 1..2^50
  // Punctual lights a scene places (node x KHR_lights_punctual light): the
  // lighting passes loop over every light at every pixel, so a file of
  // thousands of lights multiplies a frame's cost by thousands (4,000 point
  // lights, no shadows, 320x240 at 9 antialias views: 11.5 s on llvmpipe).
  std::int64_t maxLights = 1024;  // 1..2^24
};

// The rows: max-memory, max-instances, max-triangles, max-texels, max-draws,
// max-drawn-triangles, max-blended-fragments, max-lights.
std::span<const Option<ResourceLimits>> limitOptions();

// Physical memory in bytes (sysconf), or 0 where it cannot be read.
std::uint64_t physicalMemoryBytes();
// maxMemoryMiB in bytes; auto is half of physical memory (8 GiB where unknown), or half of
// the address-space limit (RLIMIT_AS, `ulimit -v`) where that is less.
std::uint64_t maxMemoryBytes(const ResourceLimits& limits);

// Peak memory a render of width x height costs beyond the scene, in bytes:
// kFrameBytesPerPixel per pixel (measured: docs/RELIABILITY.md) plus a fixed
// base. An estimate for refusing sizes that cannot fit, not an accounting.
inline constexpr std::uint64_t kFrameBytesPerPixel = 240;  // measured 227 (1024^2 to 2048^2), plus margin
inline constexpr std::uint64_t kFrameBaseBytes = std::uint64_t(256)
                                                 << 20;  // measured 245 MiB at 0 pixels (extrapolated)
std::uint64_t estimateFrameBytes(int width, int height);

// Throws LimitError when a width x height render plus `sceneBytes` would not
// fit in maxMemoryBytes(limits); says the estimate and the setting to raise.
void checkFrameFits(int width, int height, std::uint64_t sceneBytes, const ResourceLimits& limits);

// Where float rendering stays finite. Float holds 3.4e38; shading squares
// distances and multiplies light by BRDF and area terms, so world
// coordinates, transform entries, camera planes and extents stay within
// 1e12, and light values (colour x intensity, emissive x strength, sky, an
// environment map's texels) too: about 1e14 of headroom under float's range.
inline constexpr double kMaxWorldMagnitude = 1e12;
inline constexpr double kMaxLightValue = 1e12;

// Throws SceneError "<scene.source>: <element> ..." for a value outside those
// ranges or not finite: instance transforms and world bounds, cameras,
// lights, emissive and base colour factors, the sky, the environment map's
// texels (an EXT_lights_image_based intensity included); for a primitive that
// breaks Primitive's contract (an attribute count other than its positions',
// an index past them); for an instance naming a primitive or material the
// scene lacks, a material texture naming a missing image, and an image whose
// RGBA8 bytes are not width x height. loadGltf, Renderer::setScene and the
// reference's trace call it, so built and loaded scenes get the same rules.
void checkSceneRanges(const Scene& scene);

// Passes that draw the whole scene in one frame, at most: the G-buffer, one
// per directional or spot light casting shadows, six per point light (a cube
// map); a scene without lights gets the renderer's default key light (one).
int drawPassCount(const Scene& scene);

// Throws LimitError "<scene.source>: ..." when a frame's draws (instances x
// shadow views, plus instances and transmission redraws x `viewDraws`)
// exceed maxDraws, or its triangles counted alike exceed maxDrawnTriangles,
// or the scene has more lights than maxLights,
// naming the counts, the limit and the flag that raises it. `viewDraws`: how
// often the view's own passes (G-buffer, transmission, blend) draw the
// scene, 1 + the antialias samples when antialiased. Renderer::setScene and
// the CLI (before it creates a context) call it with 1, the least any frame
// draws; Renderer::render again with the frame's count.
void checkDrawBudget(const Scene& scene, const ResourceLimits& limits, int viewDraws = 1);

// Throws LimitError when the blend pass would shade more than
// maxBlendedFragments pixels in a frame: for each alphaMode BLEND instance
// the rectangle its world bounds project to through `view` (clipped to the
// width x height image; all of it where a corner is behind the eye), summed,
// times `viewDraws` as for checkDrawBudget. Renderer::render calls it once
// the camera is known, before drawing.
void checkBlendBudget(const Scene& scene, const CameraView& view, int width, int height, int viewDraws,
                      const ResourceLimits& limits);

// Bytes the scene holds on the CPU and the GPU together (vertices, indices,
// textures with mipmaps, instances); an estimate for max-memory.
std::uint64_t estimateSceneBytes(const Scene& scene);

}  // namespace headlight

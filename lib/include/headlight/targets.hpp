#pragma once
// The one table of frame targets: what each output is, how its EXR stores it
// and how a regression diff judges it. The renderer's readback, writeFrame,
// headlight diff's defaults, its directory mode and the tests all read this
// table; adding a target is one row here, a Frame member, the GPU format of
// its texture (lib/gl/target_formats.hpp) and the pass that draws it
// (docs/PIPELINE.md, "Adding a target").
#include <limits>
#include <span>
#include <string_view>

#include "headlight/export.hpp"
#include "headlight/frame.hpp"

namespace headlight HEADLIGHT_PUBLIC {

// How a pixel's error is measured by headlight diff. Every metric is turned
// into images EA and EB whose absolute difference is the error, so
// OpenImageIO's compare does the counting for all of them.
enum class DiffMetric {
  Absolute,         // |a - b|
  RelativeToScene,  // |a - b| / scale, scale = A's headlight:far (see DiffResult::scaleSource);
                    // a coverage channel ("A") stays absolute
  RelativeToValue,  // |a - b| / max(1, |a|): absolute below 1, relative above (HDR radiance)
  AngleDegrees,     // angle between the 3-channel vectors of A and B, in degrees; one channel
                    // "<prefix>.angle"; 0 when both are zero vectors, 180 when only one is
  Flip,             // perceived difference of the R, G, B channels (lib/diff/flip.hpp), one channel
                    // "flip" in 0..1: HDR-FLIP of float images, LDR-FLIP of integer (sRGB-encoded)
                    // ones; other channels (coverage A) compared absolutely
  Mismatch,         // 1 where a != b, else 0, per channel: labels (the ids), where no value is nearer than another
};

// idiff's options and idiff's defaults, plus a bound on the mean error. Units
// are the metric's.
struct DiffThresholds {
  double fail = 1e-6;                                         // >= 0; a pixel fails when any channel's error > fail
  double failPercent = 0;                                     // 0..100; FAIL when more than this % of pixels fail
  double hardFail = std::numeric_limits<double>::infinity();  // >= 0; FAIL when any error > hardFail
  // FAIL when any channel's mean error over all pixels exceeds this: the
  // failPercent allowance lets a few pixels differ, this bounds by how much
  // (0.5 % of pixels each wrong by E raise the mean by E / 200).
  double failMean = std::numeric_limits<double>::infinity();
  double warn = 1e-6;                                         // >= 0
  double warnPercent = 0;                                     // 0..100
  double hardWarn = std::numeric_limits<double>::infinity();  // >= 0
};

// What the EXR stores: float32 where half's 11 bits are too few; light is
// half, or float32 when the frame's radiance-precision is float.
// HalfWhereItFits: half, or float32 for a frame whose image holds a finite
// value beyond half's 65504 (transmission's path lengths: a volume's thickness
// is unbounded), so nothing saturates or turns into inf in the file.
// Uint32: integers (the ids), written as EXR's UINT channels.
enum class ExrStorage { Half, Float, Radiance, HalfWhereItFits, Uint32 };

// How a target looks as an 8-bit PNG (render --png; OutputOptions::pngTargets).
enum class PngLook {
  Radiance,  // light: tone mapped like preview.png (the frame's exposure and tonemap), sRGB
  Color,     // a linear 0..1 colour (the first three channels), sRGB-encoded
  Signed,    // unit vectors, -1..1 -> 0..255 per component as normal maps are shown; zero vectors black
  Range,     // the first three channels, each stretched over its range on geometry pixels; background black
  Depth,     // viridis, near (yellow) to far (purple) over the geometry's depths; background black
  Grey,      // the first channel, 0..1, as grey (ssgi: ambient occlusion)
  Values,    // the first three channels, 0..1, as they are (material: metallic, roughness, occlusion)
  Labels,    // the first channel's integers as distinct colours (ids: one per mesh instance); 0 black
};

struct FrameTarget {
  std::string_view name;                       // file stem (<name>.exr), and headlight diff's row name
  ImageF Frame::*image = nullptr;              // where a Frame keeps it; null for the diff fallback row
  std::span<const std::string_view> channels;  // EXR channel names, in order
  ExrStorage storage = ExrStorage::Half;
  DiffMetric metric = DiffMetric::Absolute;
  DiffThresholds thresholds;
  std::string_view reason;  // why this storage, metric and these thresholds (diff --help, docs/DIFF.md)
  PngLook png = PngLook::Values;
};

// Every target a frame can have, in output order.
std::span<const FrameTarget> frameTargets();
// The row named `name`, or nullptr.
const FrameTarget* findFrameTarget(std::string_view name);
// The row headlight diff uses for a file that is no headlight target:
// idiff's defaults (absolute, warn = fail = 1e-6, no allowance).
const FrameTarget& unknownTargetRow();
// headlight diff's row for preview.png, which is no frame target (the
// renderer writes it from lit; image null): LDR-FLIP.
const FrameTarget& previewTargetRow();

}  // namespace HEADLIGHT_PUBLIC

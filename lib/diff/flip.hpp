#pragma once
// FLIP, the perceptual difference of two images as an observer flipping
// between them sees it (per pixel, 0 = indistinguishable, 1 = as different as
// green and blue), written from the papers:
//  - LDR-FLIP: Andersson, Nilsson, Akenine-Möller, Oskarsson, Åström,
//    Fairchild, "FLIP: A Difference Evaluator for Alternating Images", HPG 2020;
//  - HDR-FLIP: Andersson, Nilsson, Shirley, Akenine-Möller, "Visualizing Errors
//    in Rendered High Dynamic Range Images", Eurographics 2021.
// Pure math on float buffers (no image library): the diff command, the bench
// and the tests feed it what they read. docs/ACCURACY.md ("FLIP") has the
// validation against NVIDIA's published tool (v1.6).
//
// LDR-FLIP, per image pair:
//  colour: linear RGB -> YCxCz; each channel blurred by the contrast
//    sensitivity filter of its opponent channel (sums of Gaussians in visual
//    degrees); back to linear RGB clamped to [0, 1]; CIELAB with the Hunt
//    adjustment (a, b scaled by L / 100); HyAB distance, raised to 0.7 and
//    redistributed so that 40 % of the largest distance maps to 0.95.
//  features: the luminance's edges (first Gaussian derivative) and points
//    (second derivative), 0.082 degrees peak to trough; the larger of the
//    edge and point magnitude differences, / sqrt(2), to the power 0.5.
//  FLIP = colour ^ (1 - features).
// HDR-FLIP: the per-pixel maximum of LDR-FLIP over exposures 2^e of both
// images tone mapped with ACES, e from start to stop in max(2, ceil(stop -
// start)) even steps, chosen from the reference: at the start exposure its
// brightest luminance, at the stop exposure its median, tone maps to 0.85.
//
// Images: the filters reach beyond the border; edge pixels are repeated
// (clamp to edge), as the published tool does.
#include <cstddef>
#include <vector>

namespace headlight::flip {

// Pixels per degree of visual angle for an observer `distanceMetres` from a
// display `displayWidthMetres` wide showing `displayWidthPixels`.
double pixelsPerDegree(double distanceMetres, double displayWidthMetres, double displayWidthPixels);
// The papers' default: 0.7 m from a 0.7 m wide 4K (3840 px) display, 67.02.
double defaultPixelsPerDegree();

// Read-only RGB pixels: pixel p's R, G, B at pixels[p * stride + 0..2].
// `stride` >= 3 (4 for RGBA; the other channels are ignored).
struct RgbView {
  const float* pixels = nullptr;
  int width = 0;
  int height = 0;
  int stride = 3;
};

// The per-pixel error map (row-major, top row first) and its summaries.
struct FlipResult {
  int width = 0;
  int height = 0;
  std::vector<float> error;  // width * height values in [0, 1]
  double mean = 0;
  float minimum = 0, maximum = 0;
  // HDR-FLIP only: the exposures used (log2 of the factor on radiance).
  double startExposure = 0, stopExposure = 0;
  int exposureCount = 0;
};

// LDR-FLIP of two linear-RGB images (values outside [0, 1] clamped, NaN as 0). Throws
// std::invalid_argument when the sizes differ, are zero, or stride < 3.
FlipResult ldrFlip(const RgbView& reference, const RgbView& test, double pixelsPerDegree = defaultPixelsPerDegree());

struct ExposureRange {
  double start = 0, stop = 0;
  int count = 2;
};
// HDR-FLIP's exposures for `reference` (linear radiance). A black reference
// gives start = stop = 0. When more than half its pixels are black the median
// is taken over the non-black ones (the published tool's stop would be
// infinite there).
ExposureRange hdrExposureRange(const RgbView& reference);

// HDR-FLIP of two linear HDR radiance images (negative, NaN and infinite
// values taken as 0).
// Throws like ldrFlip.
FlipResult hdrFlip(const RgbView& reference, const RgbView& test, double pixelsPerDegree = defaultPixelsPerDegree());
// The same over the given exposures (e.g. a range chosen elsewhere).
FlipResult hdrFlip(const RgbView& reference, const RgbView& test, const ExposureRange& exposures,
                   double pixelsPerDegree = defaultPixelsPerDegree());

// (sRGB's transfer curve, which LDR-FLIP's 8-bit inputs are decoded by, is
// lib/color/srgb.hpp's.)

// The ACES filmic curve HDR-FLIP tone maps with (Narkowicz's fit, with the
// 0.6 pre-exposure the papers use), not clamped.
float acesToneMap(float radiance);

}  // namespace headlight::flip

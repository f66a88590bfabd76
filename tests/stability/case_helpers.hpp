#pragma once
// What the stability cases share (stability_cases.cpp, stability_cases_inputs.cpp):
// the small renders they make, reading frames pixel by pixel, the reference,
// the checks and the pictures' panels.
#include <algorithm>
#include <cmath>
#include <string>

#include <glm/glm.hpp>

#include "headlight/reference.hpp"
#include "stability/stability.hpp"
#include "support/images.hpp"
#include "tooling/bench.hpp"

namespace headlight::stability::cases {

// ---- Rendering and reading frames ---------------------------------------------

inline RenderSettings caseSettings(SsgiMethod method, int width, int height) {
  RenderSettings settings;
  settings.width = width;
  settings.height = height;
  settings.ssgi.method = method;
  return settings;
}

inline RenderSettings withSeedRadius(RenderSettings settings) {
  applyPreset(settings, "seed");
  return settings;
}

inline bool isGeometry(const Frame& frame, int x, int y) { return frame.position.at(x, y, 3) != 0.0f; }
inline glm::vec3 worldPosition(const Frame& frame, int x, int y) {
  return {frame.position.at(x, y, 0), frame.position.at(x, y, 1), frame.position.at(x, y, 2)};
}
inline float ssgiAo(const Frame& frame, int x, int y) { return frame.ssgi.at(x, y, 0); }
inline float luminance(const ImageF& rgb, int x, int y) {
  return 0.2126f * rgb.at(x, y, 0) + 0.7152f * rgb.at(x, y, 1) + 0.0722f * rgb.at(x, y, 2);
}

// Calls `visit(x, y)` for every geometry pixel at least `margin` pixels
// from the image border.
template <class Visit>
inline void forGeometryPixels(const Frame& frame, int margin, Visit&& visit) {
  for (int y = margin; y < frame.position.height - margin; ++y)
    for (int x = margin; x < frame.position.width - margin; ++x)
      if (isGeometry(frame, x, y)) visit(x, y);
}

inline ReferenceImages traceTruth(const Renderer& renderer, const Frame& frame) {
  ReferenceSettings settings;
  settings.samplesPerPixel = kReferenceSamples;
  settings.radius = *frame.settings.ssgi.radius;  // "within R" of the SSGI the frame used
  return traceReference(renderer.scene(), frame, settings);
}

// An image of the frame's size with one channel, zero everywhere.
inline ImageF blankImage(const Frame& frame, const std::string& channel) {
  return test::makeImage(frame.position.width, frame.position.height, {channel});
}
inline float& pixelOf(ImageF& image, int x, int y) {
  return image.pixels[std::size_t(y) * std::size_t(image.width) + std::size_t(x)];
}

// RMSE and mean signed error (SSGI minus reference) of AO over chosen pixels.
struct AoError {
  double squared = 0, signedSum = 0;
  long long pixels = 0;
  long long overDarkened = 0;  // SSGI below the reference by more than 0.1 (5 reference standard errors)
  void add(double ssgi, double reference) {
    squared += (ssgi - reference) * (ssgi - reference);
    signedSum += ssgi - reference;
    overDarkened += ssgi < reference - 0.1;
    ++pixels;
  }
  double rmse() const { return pixels ? std::sqrt(squared / double(pixels)) : 0.0; }
  double meanSigned() const { return pixels ? signedSum / double(pixels) : 0.0; }
};

// ssgi AO - reference AO per pixel, 0 on background.
inline ImageF aoSignedError(const Frame& frame, const ReferenceImages& truth) {
  ImageF error = blankImage(frame, "ao.error");
  forGeometryPixels(frame, 0, [&](int x, int y) { pixelOf(error, x, y) = ssgiAo(frame, x, y) - truth.ao.at(x, y, 0); });
  return error;
}

inline Check atMost(std::string quantity, double measured, double bound) {
  return {std::move(quantity), measured, Relation::AtMost, bound, {}};
}
inline Check atLeast(std::string quantity, double measured, double bound) {
  return {std::move(quantity), measured, Relation::AtLeast, bound, {}};
}
// Kept for the next bug found: marks a check that must fail until it is fixed.
[[maybe_unused]] inline Check knownToFail(Check check, std::string bug) {
  check.knownBug = std::move(bug);
  return check;
}

// Where the methods differ: the indirect term (the hemisphere method's is
// occluder albedo, not light, so its error against the reference's radiance
// is large by design) and the lit image. Relative RMSE over geometry pixels.
inline void addShadingNotes(CaseResult& result, const Frame& frame, const ReferenceImages& truth) {
  // Absolute: the reference's indirect within R is near 0 on open walls.
  const ColorErrorStats indirect = maskedColorError(frame.ssgi, 1, truth.indirect, 0, frame.position);
  const ColorErrorStats lit = maskedColorError(frame.lit, 0, truth.lit, 0, frame.position);
  result.notes.push_back({"indirect RMSE vs reference (within R)", indirect.rmse});
  result.notes.push_back({"lit relative RMSE vs reference", lit.relativeRmse});
}

inline CaseResult startCase(const char* id, const char* failureMode, SsgiMethod method) {
  CaseResult result;
  result.id = id;
  result.failureMode = failureMode;
  result.method = std::string(ssgiMethodName(method));
  return result;
}

// AO is 1 on background too: the frame's coverage keeps open geometry and
// sky apart in the picture.
inline Panel aoPanel(std::string label, const ImageF& image, const Frame& frame) {
  return {std::move(label), image, 0, Panel::Kind::Grey, 1, frame.position};
}
inline Panel litPanel(std::string label, const ImageF& image) {
  return {std::move(label), image, 0, Panel::Kind::Tonemapped, 1, {}};
}
inline Panel errorPanel(std::string label, ImageF image, float fullScale) {
  return {std::move(label), std::move(image), 0, Panel::Kind::Signed, fullScale, {}};
}

struct AoStats {
  double minimum = 1, mean = 0;
  long long pixels = 0;
};
inline AoStats aoStats(const Frame& frame, int margin) {
  AoStats stats;
  double sum = 0;
  forGeometryPixels(frame, margin, [&](int x, int y) {
    stats.minimum = std::min<double>(stats.minimum, ssgiAo(frame, x, y));
    sum += ssgiAo(frame, x, y);
    ++stats.pixels;
  });
  stats.mean = stats.pixels ? sum / double(stats.pixels) : 0.0;
  return stats;
}

}  // namespace headlight::stability::cases

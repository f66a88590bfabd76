// Ray-traced ground truth with Embree 3 (docs/ACCURACY.md defines every
// quantity). Top to bottom: check the inputs, flatten the scene into one
// Embree triangle geometry per instance (traced_scene.cpp), then trace every
// geometry pixel of the frame on worker threads (tracer.cpp), each pixel
// with its own random stream, and reduce the standard errors.
#include "headlight/reference.hpp"

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "headlight/error.hpp"
#include "headlight/targets.hpp"
#include "settings/option_binding.hpp"

#ifndef HEADLIGHT_HAS_EMBREE
#define HEADLIGHT_HAS_EMBREE 0
#endif

#if HEADLIGHT_HAS_EMBREE
#include "reference/traced_scene.hpp"
#include "reference/tracer.hpp"
#endif

namespace headlight {

std::span<const Option<ReferenceSettings>> referenceOptions() {
  static const Option<ReferenceSettings> rows[] = {
      bindOption<ReferenceSettings>(
          {"reference-samples", OptionType::Int, "reference rays per pixel (cosine-weighted hemisphere)", 1, 1 << 20},
          [](auto& s) -> auto& { return s.samplesPerPixel; }),
      bindOption<ReferenceSettings>(
          {"reference-screen-bound", OptionType::Bool,
           "within R, only surfaces the frame shows occlude and send light: the best a screen-space method can do"},
          [](auto& s) -> auto& { return s.screenBound; }),
  };
  return rows;
}

#if !HEADLIGHT_HAS_EMBREE

bool referenceAvailable() { return false; }

ReferenceImages traceReference(const Scene&, const Frame&, const ReferenceSettings&,
                               const std::function<void(int, int)>&) {
  throw Error("headlight was built without Embree (meson -Dembree=enabled)");
}

#else

namespace {

using namespace reference;

// Specular ambient: a quarter as many GGX rays as cosine rays, at least 16
// (below that the split-sum weights kd are too noisy for a 1-spp preview).
constexpr int kMinSpecularSamples = 16;

// ---- Inputs ------------------------------------------------------------------

std::string sizeText(const ImageF& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height) + "x" + std::to_string(image.channelCount());
}

void checkImage(const ImageF& image, const char* name, int width, int height, int minChannels) {
  const bool ok = image.width == width && image.height == height && image.channelCount() >= minChannels &&
                  image.pixels.size() == std::size_t(width) * std::size_t(height) * image.channels.size();
  if (!ok)
    throw SettingsError("traceReference: frame." + std::string(name) + " is " + sizeText(image) + " with " +
                        std::to_string(image.pixels.size()) + " floats; expected " + std::to_string(width) + "x" +
                        std::to_string(height) + " with at least " + std::to_string(minChannels) + " channels");
}

void validate(const Frame& frame, const ReferenceSettings& settings) {
  for (const Option<ReferenceSettings>& option : referenceOptions())
    checkOptionValue(option.spec, option.get(settings));
  if (!(settings.radius > 0.0f) || !std::isfinite(settings.radius))
    throw SettingsError("traceReference: radius must be a finite number > 0 (world units), got " +
                        std::to_string(settings.radius));
  if (settings.threads < 0)
    throw SettingsError("traceReference: threads must be >= 0 (0 = all hardware threads), got " +
                        std::to_string(settings.threads));
  const int width = frame.position.width, height = frame.position.height;
  if (frame.position.empty() || width <= 0 || height <= 0)
    throw SettingsError("traceReference: frame.position is empty (" + sizeText(frame.position) +
                        "); expected a rendered frame's G-buffer");
  checkImage(frame.position, "position", width, height, 4);
  checkImage(frame.normal, "normal", width, height, 3);
  checkImage(frame.albedo, "albedo", width, height, 3);
  checkImage(frame.material, "material", width, height, 2);
  // Every other target the frame holds (emission, the lobes' targets the
  // pixels read), whole, as its row of frameTargets() has it.
  for (const FrameTarget& target : frameTargets()) {
    if (!target.image || target.image == &Frame::position || target.image == &Frame::normal ||
        target.image == &Frame::albedo || target.image == &Frame::material || (frame.*target.image).empty())
      continue;
    checkImage(frame.*target.image, std::string(target.name).c_str(), width, height, int(target.channels.size()));
  }
}

ImageF makeImage(int width, int height, std::vector<std::string> channels) {
  ImageF image;
  image.width = width;
  image.height = height;
  image.pixels.assign(std::size_t(width) * std::size_t(height) * channels.size(), 0.0f);
  image.channels = std::move(channels);
  return image;
}

// How far ray origins leave their surface, along the G-buffer normal (and a
// hit's face normal for its shadow rays): 2e-5 of the scene's diagonal plus
// its largest coordinate. Both the G-buffer's interpolated positions and
// Embree's hit points are off their triangle's plane by a few float ulps of
// the triangle's coordinates (1.2e-7 relative each), bounded by the scene's
// largest coordinate; 2e-5 is some 170 such ulps, and still a ninth of the
// Cornell lamp's 1 mm gap under the ceiling (0.11 mm there). A larger
// offset would bias AO in creases: the origin would leave the corner.
float rayEpsilon(const Scene& scene) {
  const Bounds bounds = scene.worldBounds();
  if (bounds.empty()) return 1e-6f;
  const glm::vec3 largest = glm::max(glm::abs(bounds.min), glm::abs(bounds.max));
  const float epsilon = 2e-5f * (2.0f * bounds.radius() + std::max({largest.x, largest.y, largest.z}));
  return std::max(epsilon, std::numeric_limits<float>::min());
}

}  // namespace

bool referenceAvailable() { return true; }

ReferenceImages traceReference(const Scene& scene, const Frame& frame, const ReferenceSettings& settings,
                               const std::function<void(int, int)>& progress) {
  validate(frame, settings);
  const auto start = std::chrono::steady_clock::now();
  const int width = frame.position.width, height = frame.position.height;
  const int hardware = int(std::max(1u, std::thread::hardware_concurrency()));
  const int threads = std::clamp(settings.threads > 0 ? settings.threads : hardware, 1, height);

  const TracedScene traced = buildScene(scene, settings.threads);

  ReferenceImages images;
  images.samplesPerPixel = settings.samplesPerPixel;
  images.screenBound = settings.screenBound;
  images.ao = makeImage(width, height, {"ao.Y", "sky.Y", "specular.Y"});
  images.indirect =
      makeImage(width, height, {"indirectR.R", "indirectR.G", "indirectR.B", "indirect.R", "indirect.G", "indirect.B"});
  images.lit = makeImage(width, height, {"R", "G", "B", "A"});
  const std::size_t pixelCount = std::size_t(width) * std::size_t(height);
  std::vector<double> aoStandardError(pixelCount, std::numeric_limits<double>::quiet_NaN());
  std::vector<double> indirectStandardError(pixelCount, std::numeric_limits<double>::quiet_NaN());

  // An environment map replaces the sky, with its own intensity (as the renderer's composite).
  std::optional<EnvironmentLight> environmentLight;
  const LightingSettings& lighting = frame.settings.lighting;
  if (scene.environment) {
    environment::EquirectImage map{scene.environment->width, scene.environment->height, scene.environment->rgb};
    const float turn = lighting.environmentRotation * 3.14159265358979f / 180.0f;
    environmentLight.emplace(EnvironmentLight{map, environment::EnvironmentSampler(map), std::cos(turn), std::sin(turn),
                                              lighting.environmentBackground});
  }
  const TraceInputs inputs{
      scene,
      frame,
      settings,
      traced.scene.get(),
      traced.hasBlended ? traced.blended.get() : nullptr,
      traced.instances,
      rayEpsilon(scene),
      environmentLight ? lighting.environmentIntensity : lighting.skyIntensity.value_or(scene.sky.intensity),
      std::max(kMinSpecularSamples, settings.samplesPerPixel / 4),
      environmentLight ? &*environmentLight : nullptr,
      std::any_of(scene.materials.begin(), scene.materials.end(),
                  [](const Material& material) { return material.transmissive(); })};
  const Outputs outputs{images, aoStandardError, indirectStandardError};

  // Rows handed out one at a time: a row's cost varies with what it sees.
  std::atomic<int> nextRow{0};
  std::exception_ptr failure;
  std::mutex failureMutex;
  auto work = [&] {
    try {
      traceRows(inputs, outputs, nextRow);
    } catch (...) {
      std::lock_guard<std::mutex> lock(failureMutex);
      if (!failure) failure = std::current_exception();
      nextRow = height;
    }
  };
  std::vector<std::thread> workers;
  if (!progress) {
    for (int i = 1; i < threads; ++i) workers.emplace_back(work);
    work();
    for (std::thread& worker : workers) worker.join();
  } else {
    // Every thread a worker; this one reports the rows handed out until they all are.
    std::atomic<int> running{threads};
    for (int i = 0; i < threads; ++i)
      workers.emplace_back([&] {
        work();
        --running;
      });
    while (running > 0) {
      progress(std::min(int(nextRow), height), height);
      for (int tick = 0; tick < 20 && running > 0; ++tick) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    for (std::thread& worker : workers) worker.join();
    if (!failure) progress(height, height);
  }
  if (failure) std::rethrow_exception(failure);

  // Reduced in pixel order, so the means are the same for any thread count.
  double aoSum = 0.0, aoMax = 0.0, indirectSum = 0.0;
  std::size_t geometryPixels = 0;
  for (std::size_t i = 0; i < pixelCount; ++i) {
    if (frame.position.pixels[i * frame.position.channels.size() + 3] == 0.0f) continue;
    ++geometryPixels;
    aoSum += aoStandardError[i];
    aoMax = std::max(aoMax, aoStandardError[i]);
    indirectSum += indirectStandardError[i];
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const bool spread = settings.samplesPerPixel > 1 && geometryPixels > 0;
  images.aoMeanStandardError = spread ? aoSum / double(geometryPixels) : (geometryPixels ? nan : 0.0);
  images.aoMaxStandardError = spread ? aoMax : (geometryPixels ? nan : 0.0);
  images.indirectMeanStandardError = spread ? indirectSum / double(geometryPixels) : (geometryPixels ? nan : 0.0);
  images.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return images;
}

#endif  // HEADLIGHT_HAS_EMBREE

}  // namespace headlight
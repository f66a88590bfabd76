#include "headlight/settings.hpp"

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <vector>

#include "headlight/error.hpp"
#include "io/bounded_read.hpp"
#include "settings/option_binding.hpp"
#include "settings/preview_background.hpp"
#include "settings/setting_fields.hpp"
#include "shared_layout.h"

namespace headlight {
namespace {

// Choice names, in the order of the enums' enumerators.
constexpr std::string_view kSsgiMethodNames[] = {"hemisphere", "radiance", "bitmask"};
constexpr std::string_view kSsgiResolutionNames[] = {"full", "half", "quarter"};
constexpr std::string_view kTonemapNames[] = {"aces", "reinhard"};
constexpr std::string_view kRadiancePrecisionNames[] = {"half", "float"};
constexpr std::string_view kFullscreenFormNames[] = {"fragment", "compute"};
constexpr std::string_view kPresetNames[] = {"fast", "default", "high", "seed"};

// The largest image side; width x height is further bounded in validate().
constexpr double kMaxImageSide = 16384;

using Row = Option<RenderSettings>;

template <class Access>
Row row(OptionSpec spec, Access access) {
  return bindOption<RenderSettings>(spec, access);
}

const std::vector<Row>& table() {
  using T = OptionType;
  static const std::vector<Row> rows{
      row(
          {.name = "width", .type = T::Int, .help = "image width in pixels", .minimum = 1, .maximum = kMaxImageSide},
          [](auto& s) -> auto& { return s.width; }),
      row(
          {.name = "height", .type = T::Int, .help = "image height in pixels", .minimum = 1, .maximum = kMaxImageSide},
          [](auto& s) -> auto& { return s.height; }),
      row(
          {.name = "camera",
           .type = T::Int,
           .help = "glTF camera index",
           .maximum = 1 << 20,
           .autoMeaning = "the scene's first camera, else one fitted to the bounds"},
          [](auto& s) -> auto& { return s.camera; }),
      row(
          {.name = "antialias",
           .type = T::Int,
           .help = "lit and preview.png: the mean of this many samples jittered over each pixel (1: off, the "
                   "pixel centre); every other target keeps the pixel centre's",
           .minimum = 1,
           .maximum = 64},
          [](auto& s) -> auto& { return s.antialiasSamples; }),
      row(
          {.name = "antialias-ssgi",
           .type = T::Bool,
           .help = "every antialias sample runs the SSGI pass too, with its own noise (off: each reads the pixel "
                   "centre's SSGI; on costs the SSGI's time per sample)"},
          [](auto& s) -> auto& { return s.antialiasSsgi; }),
      row(
          {.name = "ssgi", .type = T::Bool, .help = "the SSGI pass (off: no ssgi.exr; ambient is unoccluded)"},
          [](auto& s) -> auto& { return s.ssgi.enabled; }),
      row(
          {.name = "ssgi-method",
           .type = T::Choice,
           .help =
               "SSGI method: the seed's kernel with occluder albedo (hemisphere), the same kernel gathering occluders' "
               "direct light (radiance), or screen-space slices with a visibility bitmask (bitmask)",
           .choices = kSsgiMethodNames},
          [](auto& s) -> auto& { return s.ssgi.method; }),
      row(
          {.name = "ssgi-samples",
           .type = T::Int,
           .help = "SSGI kernel samples per pixel",
           .minimum = 1,
           .maximum = gpu::kMaxKernelSamples},
          [](auto& s) -> auto& { return s.ssgi.sampleCount; }),
      row(
          {.name = "ssgi-slices",
           .type = T::Int,
           .help = "bitmask SSGI: screen-space directions per pixel (each also marched the opposite way)",
           .minimum = 1,
           .maximum = 32},
          [](auto& s) -> auto& { return s.ssgi.sliceCount; }),
      row(
          {.name = "ssgi-steps",
           .type = T::Int,
           .help = "bitmask SSGI: depth samples per direction out to the radius's footprint on screen",
           .minimum = 1,
           .maximum = 64},
          [](auto& s) -> auto& { return s.ssgi.stepCount; }),
      row(
          {.name = "ssgi-thickness",
           .type = T::Float,
           .help = "bitmask SSGI: how deep every visible surface is taken to be at least, world units (deeper where "
                   "the steps within the radius are sparse)",
           .maximum = 1e9,
           .autoMeaning = "2/3 of the median over objects of their bounds' smallest side, flat ones left out, within "
                          "0.05..1 x the radius (half the radius if all are flat)"},
          [](auto& s) -> auto& { return s.ssgi.thickness; }),
      row(
          {.name = "ssgi-sky-steps",
           .type = T::Int,
           .help = "bitmask SSGI: depth samples per direction beyond the radius, out to the screen edge, for the sky "
                   "visibility that occludes ambient light and the light gathered from beyond the radius (0: neither; "
                   "the AO within the radius occludes ambient light)",
           .maximum = 32},
          [](auto& s) -> auto& { return s.ssgi.skyStepCount; }),
      row(
          {.name = "ssgi-frames",
           .type = T::Int,
           .help = "bitmask SSGI: frames averaged, each with rotated slices and jittered steps",
           .minimum = 1,
           .maximum = 256},
          [](auto& s) -> auto& { return s.ssgi.frames; }),
      row(
          {.name = "ssgi-radius",
           .type = T::Float,
           .help = "SSGI radius in world units",
           .minimum = 1e-9,
           .maximum = 1e9,
           .autoMeaning = "ssgi-radius-fraction x the scene's bounding-box diagonal"},
          [](auto& s) -> auto& { return s.ssgi.radius; }),
      row(
          {.name = "ssgi-radius-fraction",
           .type = T::Float,
           .help = "auto SSGI radius as a fraction of the scene's bounding-box diagonal",
           .minimum = 1e-6,
           .maximum = 10},
          [](auto& s) -> auto& { return s.ssgi.radiusFraction; }),
      row(
          {.name = "ssgi-bias",
           .type = T::Float,
           .help = "SSGI depth bias in world units",
           .maximum = 1e9,
           .autoMeaning = "5% of the radius"},
          [](auto& s) -> auto& { return s.ssgi.bias; }),
      row(
          {.name = "ssgi-intensity", .type = T::Float, .help = "SSGI occlusion intensity", .maximum = 4},
          [](auto& s) -> auto& { return s.ssgi.intensity; }),
      row(
          {.name = "ssgi-indirect",
           .type = T::Float,
           .help = "SSGI one-bounce indirect strength",
           .maximum = 4,
           .autoMeaning = "0.5 hemisphere, 1 radiance"},
          [](auto& s) -> auto& { return s.ssgi.indirectStrength; }),
      row(
          {.name = "ssgi-seed", .type = T::Int, .help = "random seed of the SSGI kernel and noise", .maximum = 1 << 30},
          [](auto& s) -> auto& { return s.ssgi.seed; }),
      row(
          {.name = "ssgi-blur",
           .type = T::Bool,
           .help = "average out the SSGI pass's noise (a depth- and normal-aware 7x7 blur)"},
          [](auto& s) -> auto& { return s.ssgi.blur; }),
      row(
          {.name = "ssgi-resolution",
           .type = T::Choice,
           .help = "resolution the SSGI pass runs at (the blur upsamples)",
           .choices = kSsgiResolutionNames},
          [](auto& s) -> auto& { return s.ssgi.resolution; }),
      row(
          {.name = "ssgi-far-resolution",
           .type = T::Choice,
           .help = "bitmask SSGI: resolution the far field (sky visibility, light from beyond the radius) runs at, "
                   "in its own pass the blur upsamples; never finer than ssgi-resolution (there: one pass for both)",
           .choices = kSsgiResolutionNames},
          [](auto& s) -> auto& { return s.ssgi.farResolution; }),
      row(
          {.name = "ssgi-far-slices",
           .type = T::Int,
           .help = "bitmask SSGI: screen-space directions per pixel of the far field's own pass (below "
                   "ssgi-resolution; else ssgi-slices serves both)",
           .minimum = 1,
           .maximum = 32},
          [](auto& s) -> auto& { return s.ssgi.farSliceCount; }),
      row(
          {.name = "ssgi-virtual-lights",
           .type = T::Int,
           .help = "bitmask SSGI: the light from beyond the radius as one bounce of the punctual lights off the "
                   "surfaces they light, from at most this many virtual point lights (texels of each light's view "
                   "of the scene; 0: gathered by the screen-space marches instead)",
           .minimum = 0,
           .maximum = 65536},
          [](auto& s) -> auto& { return s.ssgi.virtualLightCount; }),
      row(
          {.name = "ssgi-light-field",
           .type = T::Int,
           .help = "bitmask SSGI with virtual lights: the most probes of a world-space light field over the scene "
                   "(irradiance and what each probe sees, made once per scene from the virtual lights), from which "
                   "the far field takes the light the screen does not show (0: none)",
           .minimum = 0,
           .maximum = 4096},
          [](auto& s) -> auto& { return s.ssgi.lightFieldProbes; }),
      row(
          {.name = "shadows", .type = T::Bool, .help = "shadow maps for the lights that cast shadows"},
          [](auto& s) -> auto& { return s.lighting.shadows; }),
      row(
          {.name = "shadow-map-size",
           .type = T::Int,
           .help = "shadow map texels per side (a point light's cube faces: half)",
           .minimum = 64,
           .maximum = 8192,
           .autoMeaning = "4x the longer image side to the next power of two, 1024..2048"},
          [](auto& s) -> auto& { return s.lighting.shadowMapSize; }),
      row(
          {.name = "shadow-pcf-radius",
           .type = T::Float,
           .help = "shadow filter radius in shadow-map texels",
           .maximum = 8},
          [](auto& s) -> auto& { return s.lighting.pcfRadius; }),
      row(
          {.name = "sky-intensity",
           .type = T::Float,
           .help = "sky (ambient) intensity (an environment map replaces the sky: --environment-intensity)",
           .maximum = 1000,
           .autoMeaning = "the scene's"},
          [](auto& s) -> auto& { return s.lighting.skyIntensity; }),
      row(
          {.name = "environment-intensity",
           .type = T::Float,
           .help = "multiplies the environment map's radiance (ambient and background; with --environment)",
           .maximum = 1e6},
          [](auto& s) -> auto& { return s.lighting.environmentIntensity; }),
      row(
          {.name = "environment-rotation",
           .type = T::Float,
           .help = "turns the environment map about +Y, in degrees (right-handed: at 90 the map's -Z lies at -X)",
           .minimum = -360,
           .maximum = 360},
          [](auto& s) -> auto& { return s.lighting.environmentRotation; }),
      row(
          {.name = "environment-background",
           .type = T::Bool,
           .help = "show the environment map behind the scene in lit and preview.png (off: black, alpha 0)"},
          [](auto& s) -> auto& { return s.lighting.environmentBackground; }),
      row(
          {.name = "tonemap",
           .type = T::Choice,
           .help = "tone curve for preview.png (lit.exr stays linear)",
           .choices = kTonemapNames},
          [](auto& s) -> auto& { return s.tonemap; }),
      row(
          {.name = "exposure",
           .type = T::Float,
           .help = "exposure for preview.png in stops (EV)",
           .minimum = -20,
           .maximum = 20},
          [](auto& s) -> auto& { return s.exposure; }),
      row(
          {.name = "preview-background",
           .type = T::Text,
           .help = "what preview.png shows where no geometry is: sky (what lit.exr has there), transparent "
                   "(alpha = coverage), or a display colour #rrggbb or R,G,B in 0..1",
           .valueName = "sky|transparent|COLOUR",
           .checkText = [](std::string_view text) { parsePreviewBackground(text); },
           .example = "#3060a0"},
          [](auto& s) -> auto& { return s.previewBackground; }),
      row(
          {.name = "radiance-precision",
           .type = T::Choice,
           .help = "storage of lit, emissive and ssgi, on the GPU and in the EXRs (half holds up to 65504)",
           .choices = kRadiancePrecisionNames,
           .autoMeaning = "float when the scene's lights or emitters may exceed half's range"},
          [](auto& s) -> auto& { return s.radiancePrecision; }),
      row(
          {.name = "fullscreen-form",
           .type = T::Choice,
           .help = "how the fullscreen passes (direct light, SSGI, blur, composite, sky tables) run: as a fullscreen "
                   "triangle's fragment shader or a compute dispatch; the pixels are the same",
           .choices = kFullscreenFormNames,
           .autoMeaning = "per pass: compute on a GPU, on llvmpipe the form measured faster"},
          [](auto& s) -> auto& { return s.fullscreenForm; }),
  };
  return rows;
}

}  // namespace

int ssgiDivisor(SsgiResolution resolution) { return 1 << int(resolution); }

std::span<const Option<RenderSettings>> settingOptions() { return table(); }
std::span<const std::string_view> presetNames() { return kPresetNames; }

std::string_view ssgiMethodName(SsgiMethod method) { return kSsgiMethodNames[std::size_t(method)]; }

std::map<std::string, std::string> settingsAsText(const RenderSettings& settings) {
  std::map<std::string, std::string> values;
  for (const Row& option : settingOptions())
    values[std::string(option.spec.name)] = formatOptionValue(option.spec, option.get(settings));
  return values;
}

double settingNumber(const RenderSettings& settings, std::string_view name) {
  const Row& option = findOption(settingOptions(), name);
  const OptionValue value = option.get(settings);
  if (const auto* number = std::get_if<double>(&value)) return *number;
  if (const auto* integer = std::get_if<std::int64_t>(&value)) return double(*integer);
  if (const auto* flag = std::get_if<bool>(&value)) return *flag ? 1.0 : 0.0;
  throw SettingsError(std::string(name) + ": " +
                          (std::holds_alternative<AutoValue>(value) ? "still auto where a shader needs its value"
                                                                    : "not a number a shader can take"),
                      {std::string(name)});
}

void applySettingsText(RenderSettings& settings, const std::map<std::string, std::string>& values) {
  for (const auto& [name, text] : values) {
    const Row& option = findOption(settingOptions(), name);
    option.set(settings, parseOptionValue(option.spec, text));
  }
}

namespace {

// The image's size, the view and its antialiasing belong to each render,
// not to the scene's model: a file tuned at 128 x 128 without antialiasing
// is meant for any size, camera and sample count.
constexpr std::string_view kRowsNotInSettingsFiles[] = {"width", "height", "camera", "antialias", "antialias-ssgi"};

std::string_view trimmed(std::string_view text) {
  const auto first = text.find_first_not_of(" \t\r");
  if (first == std::string_view::npos) return {};
  return text.substr(first, text.find_last_not_of(" \t\r") - first + 1);
}

}  // namespace

std::string settingsFileText(const RenderSettings& settings, std::span<const std::string> comments) {
  std::string text;
  for (const std::string& comment : comments) text += "# " + comment + "\n";
  for (const Row& option : settingOptions()) {
    if (std::find(std::begin(kRowsNotInSettingsFiles), std::end(kRowsNotInSettingsFiles), option.spec.name) !=
        std::end(kRowsNotInSettingsFiles))
      continue;
    text += std::string(option.spec.name) + " = " + formatOptionValue(option.spec, option.get(settings)) + "\n";
  }
  return text;
}

void applySettingsFileText(RenderSettings& settings, std::string_view text, const std::string& name) {
  std::map<std::string, int> seenOnLine;
  int lineNumber = 0;
  for (std::size_t start = 0; start <= text.size();) {
    const std::size_t end = std::min(text.find('\n', start), text.size());
    const std::string_view line = trimmed(text.substr(start, end - start));
    start = end + 1;
    ++lineNumber;
    if (line.empty() || line.front() == '#') continue;
    const std::string where = name + ":" + std::to_string(lineNumber) + ": ";
    // A NUL would end every message that quotes the line at the NUL.
    if (line.find('\0') != std::string_view::npos)
      throw SettingsError(where + "holds a NUL byte (not a settings file?)");
    const auto equals = line.find('=');
    const std::string key(trimmed(line.substr(0, equals == std::string_view::npos ? 0 : equals)));
    // The line itself is not echoed: a file given by mistake (/etc/passwd)
    // should not have its contents printed.
    if (equals == std::string_view::npos || key.empty())
      throw SettingsError(where + "expected NAME = VALUE (NAME a render setting's name), got a line " +
                          (equals == std::string_view::npos ? "without '='" : "with nothing before '='") +
                          " (not a settings file?)");
    if (const auto seen = seenOnLine.find(key); seen != seenOnLine.end())
      throw SettingsError(where + "'" + key + "' is already set on line " + std::to_string(seen->second));
    seenOnLine.emplace(key, lineNumber);
    try {
      applySettingsText(settings, {{key, std::string(trimmed(line.substr(equals + 1)))}});
    } catch (const SettingsError& error) {
      throw SettingsError(where + error.what());
    }
  }
}

void applySettingsFile(RenderSettings& settings, const std::filesystem::path& path) {
  std::string text;
  try {
    // A regular file of at most 1 MiB: a folder, /dev/zero or a FIFO is refused, not read.
    text = detail::readRegularFile(path, detail::kMaxSettingsFileBytes, "the settings file");
  } catch (const IoError& error) {
    throw SettingsError(error.what());
  }
  applySettingsFileText(settings, text, path.string());
}

void applyPreset(RenderSettings& settings, std::string_view preset) {
  const RenderSettings defaults;
  if (preset == "default") {
    settings.ssgi = defaults.ssgi;
    settings.lighting = defaults.lighting;
  } else if (preset == "fast") {
    // The bitmask method's cheapest point on the bench's front
    // (docs/BENCHMARKS.md, "Current state"): 1 slice of 8 steps at half
    // resolution, 0.40 to 0.60x the hemisphere's SSGI time at 256x256, AO
    // RMSE 0.053 to 0.131 (the default's: 0.038 to 0.127).
    settings.ssgi = defaults.ssgi;
    settings.ssgi.sliceCount = 1;
    settings.ssgi.stepCount = 8;
    settings.ssgi.skyStepCount = 8;  // the default's before issue 16: fast keeps its cost
    settings.ssgi.resolution = SsgiResolution::Half;
    settings.ssgi.blur = true;
    settings.lighting.shadowMapSize = 1024;
    settings.lighting.pcfRadius = 1.0f;
  } else if (preset == "high") {
    settings.ssgi = defaults.ssgi;
    settings.ssgi.sliceCount = 4;
    settings.ssgi.stepCount = 24;
    settings.ssgi.farSliceCount = 4;
    settings.lighting.shadowMapSize = 4096;
    settings.lighting.pcfRadius = 2.0f;
  } else if (preset == "seed") {
    // The seed spec's method and numbers, for scenes of the size it was
    // written for.
    settings.ssgi = defaults.ssgi;
    settings.ssgi.method = SsgiMethod::Hemisphere;
    settings.ssgi.sampleCount = 64;
    settings.ssgi.radius = 0.5f;
    settings.ssgi.bias = 0.025f;
  } else {
    std::string known;
    for (std::string_view name : presetNames()) (known += known.empty() ? "" : ", ") += name;
    throw SettingsError("preset: expected one of " + known + ", got '" + std::string(preset) + "'", {"preset"});
  }
}

void RenderSettings::validate() const {
  for (const Row& option : settingOptions()) checkOptionValue(option.spec, option.get(*this));
  // Readback sizes are GLsizei (32-bit) byte counts: 2^26 RGBA float pixels
  // is the most one texture read can hold (an 8192 x 8192 image).
  if (std::int64_t(width) * height > (std::int64_t(1) << 26))
    throw SettingsError("width " + std::to_string(width) + " x height " + std::to_string(height) +
                            ": at most 67108864 pixels (8192 x 8192)",
                        {"width", "height"});
  if (ssgi.resolution != SsgiResolution::Full && !ssgi.blur)
    throw SettingsError("ssgi-blur off needs ssgi-resolution full: below full resolution the blur pass upsamples",
                        {"ssgi-blur", "ssgi-resolution"});
}

}  // namespace headlight

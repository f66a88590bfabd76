#include "headlight/settings.hpp"

#include <array>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <sstream>

#include "headlight/error.hpp"

namespace headlight {
namespace {

std::string formatFloat(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

int parseInt(std::string_view name, std::string_view text, int low, int high) {
  int value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size())
    throw SettingsError("--" + std::string(name) + ": expected an integer, got '" + std::string(text) + "'");
  if (value < low || value > high)
    throw SettingsError("--" + std::string(name) + ": must be in " + std::to_string(low) + ".." +
                        std::to_string(high) + ", got " + std::to_string(value));
  return value;
}

float parseFloat(std::string_view name, std::string_view text, float low, float high) {
  // std::from_chars for float is in libstdc++ 11+, and takes no locale.
  float value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || !std::isfinite(value))
    throw SettingsError("--" + std::string(name) + ": expected a number, got '" + std::string(text) + "'");
  if (value < low || value > high)
    throw SettingsError("--" + std::string(name) + ": must be in " + formatFloat(low) + ".." + formatFloat(high) +
                        ", got " + std::string(text));
  return value;
}

// "auto" is stored as 0 for the settings whose 0 means auto.
float parseAutoFloat(std::string_view name, std::string_view text, float low, float high) {
  return text == "auto" ? 0.0f : parseFloat(name, text, low, high);
}
std::string formatAuto(float value) { return value == 0.0f ? "auto" : formatFloat(value); }

std::string_view tonemapName(Tonemap tonemap) { return tonemap == Tonemap::Aces ? "aces" : "reinhard"; }

const std::array<SettingOption, 19>& optionTable() {
  static const std::array<SettingOption, 19> table{{
      {"width", "N", "image width in pixels (1..16384)",
       [](RenderSettings& s, std::string_view v) { s.width = parseInt("width", v, 1, 16384); },
       [](const RenderSettings& s) { return std::to_string(s.width); }},
      {"height", "N", "image height in pixels (1..16384)",
       [](RenderSettings& s, std::string_view v) { s.height = parseInt("height", v, 1, 16384); },
       [](const RenderSettings& s) { return std::to_string(s.height); }},
      {"camera", "auto|N", "glTF camera index (default: the scene's first camera, else one fitted to the bounds)",
       [](RenderSettings& s, std::string_view v) { s.camera = v == "auto" ? -1 : parseInt("camera", v, 0, 1 << 20); },
       [](const RenderSettings& s) { return s.camera < 0 ? std::string("auto") : std::to_string(s.camera); }},
      {"no-ssgi", "", "skip the SSGI pass (no ssgi.exr; ambient is unoccluded)",
       [](RenderSettings& s, std::string_view) { s.ssgi.enabled = false; },
       [](const RenderSettings& s) { return std::string(s.ssgi.enabled ? "false" : "true"); }},
      {"ssgi-samples", "N", "SSGI kernel samples per pixel (1..64)",
       [](RenderSettings& s, std::string_view v) { s.ssgi.sampleCount = parseInt("ssgi-samples", v, 1, 64); },
       [](const RenderSettings& s) { return std::to_string(s.ssgi.sampleCount); }},
      {"ssgi-radius", "auto|FLOAT", "SSGI radius in world units (auto: 15% of the scene's bounding-box diagonal)",
       [](RenderSettings& s, std::string_view v) { s.ssgi.radius = parseAutoFloat("ssgi-radius", v, 1e-9f, 1e9f); },
       [](const RenderSettings& s) { return formatAuto(s.ssgi.radius); }},
      {"ssgi-bias", "auto|FLOAT", "SSGI depth bias in world units (auto: 5% of the radius)",
       [](RenderSettings& s, std::string_view v) { s.ssgi.bias = parseAutoFloat("ssgi-bias", v, 0.0f, 1e9f); },
       [](const RenderSettings& s) { return formatAuto(s.ssgi.bias); }},
      {"ssgi-intensity", "FLOAT", "SSGI occlusion intensity (0..4)",
       [](RenderSettings& s, std::string_view v) { s.ssgi.intensity = parseFloat("ssgi-intensity", v, 0, 4); },
       [](const RenderSettings& s) { return formatFloat(s.ssgi.intensity); }},
      {"ssgi-method", "hemisphere|radiance",
       "SSGI indirect term: the seed's occluder albedo (hemisphere) or occluders' direct light (radiance)",
       [](RenderSettings& s, std::string_view v) { s.ssgi.method = parseSsgiMethod(v); },
       [](const RenderSettings& s) { return std::string(ssgiMethodName(s.ssgi.method)); }},
      {"ssgi-indirect", "auto|FLOAT", "SSGI one-bounce indirect strength (0..4; auto: 0.5 hemisphere, 1 radiance)",
       [](RenderSettings& s, std::string_view v) {
         s.ssgi.indirectStrength = v == "auto" ? -1.0f : parseFloat("ssgi-indirect", v, 0, 4);
       },
       [](const RenderSettings& s) {
         return s.ssgi.indirectStrength < 0 ? std::string("auto") : formatFloat(s.ssgi.indirectStrength);
       }},
      {"ssgi-seed", "N", "random seed of the SSGI kernel and noise",
       [](RenderSettings& s, std::string_view v) { s.ssgi.seed = unsigned(parseInt("ssgi-seed", v, 0, 1 << 30)); },
       [](const RenderSettings& s) { return std::to_string(s.ssgi.seed); }},
      {"no-ssgi-blur", "", "keep the SSGI pass's 4x4 noise pattern (no denoise)",
       [](RenderSettings& s, std::string_view) { s.ssgi.blur = false; },
       [](const RenderSettings& s) { return std::string(s.ssgi.blur ? "false" : "true"); }},
      {"ssgi-resolution", "full|half|quarter", "resolution the SSGI pass runs at (the blur upsamples)",
       [](RenderSettings& s, std::string_view v) {
         if (v == "full") s.ssgi.downsample = 1;
         else if (v == "half") s.ssgi.downsample = 2;
         else if (v == "quarter") s.ssgi.downsample = 4;
         else throw SettingsError("--ssgi-resolution: expected full, half or quarter, got '" + std::string(v) + "'");
       },
       [](const RenderSettings& s) {
         return std::string(s.ssgi.downsample == 1 ? "full" : s.ssgi.downsample == 2 ? "half" : "quarter");
       }},
      {"no-shadows", "", "skip shadow maps",
       [](RenderSettings& s, std::string_view) { s.lighting.shadows = false; },
       [](const RenderSettings& s) { return std::string(s.lighting.shadows ? "false" : "true"); }},
      {"shadow-map-size", "auto|N", "shadow map texels per side (64..8192; auto: from the image size, 512..2048)",
       [](RenderSettings& s, std::string_view v) {
         s.lighting.shadowMapSize = v == "auto" ? 0 : parseInt("shadow-map-size", v, 64, 8192);
       },
       [](const RenderSettings& s) {
         return s.lighting.shadowMapSize == 0 ? std::string("auto") : std::to_string(s.lighting.shadowMapSize);
       }},
      {"shadow-pcf-radius", "FLOAT", "shadow filter radius in shadow-map texels (0..8)",
       [](RenderSettings& s, std::string_view v) { s.lighting.pcfRadius = parseFloat("shadow-pcf-radius", v, 0, 8); },
       [](const RenderSettings& s) { return formatFloat(s.lighting.pcfRadius); }},
      {"sky-intensity", "auto|FLOAT", "sky (ambient) intensity (auto: the scene's; 0..1000)",
       [](RenderSettings& s, std::string_view v) {
         s.lighting.skyIntensity = v == "auto" ? -1.0f : parseFloat("sky-intensity", v, 0, 1000);
       },
       [](const RenderSettings& s) {
         return s.lighting.skyIntensity < 0 ? std::string("auto") : formatFloat(s.lighting.skyIntensity);
       }},
      {"tonemap", "aces|reinhard", "tone curve for preview.png (lit.exr stays linear)",
       [](RenderSettings& s, std::string_view v) {
         if (v != "aces" && v != "reinhard")
           throw SettingsError("--tonemap: expected aces or reinhard, got '" + std::string(v) + "'");
         s.tonemap = v == "aces" ? Tonemap::Aces : Tonemap::Reinhard;
       },
       [](const RenderSettings& s) { return std::string(tonemapName(s.tonemap)); }},
      {"exposure", "EV", "exposure for preview.png in stops (-20..20)",
       [](RenderSettings& s, std::string_view v) { s.exposure = parseFloat("exposure", v, -20, 20); },
       [](const RenderSettings& s) { return formatFloat(s.exposure); }},
  }};
  return table;
}

constexpr std::array<std::string_view, 4> kPresetNames{"fast", "default", "high", "seed"};

}  // namespace

std::string_view ssgiMethodName(SsgiMethod method) {
  return method == SsgiMethod::Hemisphere ? "hemisphere" : "radiance";
}

SsgiMethod parseSsgiMethod(std::string_view name) {
  if (name == "hemisphere") return SsgiMethod::Hemisphere;
  if (name == "radiance") return SsgiMethod::Radiance;
  throw SettingsError("--ssgi-method: expected hemisphere or radiance, got '" + std::string(name) + "'");
}

std::span<const SettingOption> settingOptions() { return optionTable(); }
std::span<const std::string_view> presetNames() { return kPresetNames; }

void applyPreset(RenderSettings& settings, std::string_view preset) {
  const RenderSettings defaults;
  if (preset == "default") {
    settings.ssgi = defaults.ssgi;
    settings.lighting = defaults.lighting;
  } else if (preset == "fast") {
    // On the bench's front for lit error at about half the seed's time
    // (docs/BENCHMARKS.md): the radiance method, 16 samples, SSGI at half
    // resolution.
    settings.ssgi.method = SsgiMethod::Radiance;
    settings.ssgi.sampleCount = 16;
    settings.ssgi.downsample = 2;
    settings.ssgi.blur = true;
    settings.lighting.shadowMapSize = 1024;
    settings.lighting.pcfRadius = 1.0f;
  } else if (preset == "high") {
    settings.ssgi.method = SsgiMethod::Radiance;
    settings.ssgi.sampleCount = 64;
    settings.ssgi.downsample = 1;
    settings.lighting.shadowMapSize = 4096;
    settings.lighting.pcfRadius = 2.0f;
  } else if (preset == "seed") {
    // The seed spec's numbers, for scenes of the size it was written for.
    settings.ssgi = defaults.ssgi;
    settings.ssgi.radius = 0.5f;
    settings.ssgi.bias = 0.025f;
  } else {
    std::string known;
    for (std::string_view name : presetNames()) (known += known.empty() ? "" : ", ") += name;
    throw SettingsError("--preset: expected one of " + known + ", got '" + std::string(preset) + "'");
  }
}

void RenderSettings::validate() const {
  // Round-trip every value through the table's own parser, so the ranges live
  // in one place.
  RenderSettings scratch = *this;
  for (const SettingOption& option : settingOptions())
    if (!option.valueName.empty()) option.parse(scratch, option.format(*this));
  // Readback sizes are GLsizei (32-bit) byte counts: 2^26 RGBA float pixels
  // is the most one texture read can hold (an 8192 x 8192 image).
  if (std::int64_t(width) * height > (std::int64_t(1) << 26))
    throw SettingsError("--width " + std::to_string(width) + " x --height " + std::to_string(height) +
                        ": at most 67108864 pixels (8192 x 8192)");
  if (ssgi.downsample != 1 && ssgi.downsample != 2 && ssgi.downsample != 4)
    throw SettingsError("ssgi.downsample: must be 1, 2 or 4, got " + std::to_string(ssgi.downsample));
  if (ssgi.downsample > 1 && !ssgi.blur)
    throw SettingsError("--no-ssgi-blur needs --ssgi-resolution full: below full resolution the blur pass upsamples");
}

}  // namespace headlight

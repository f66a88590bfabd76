#pragma once
// Render settings: plain structs with in-class defaults and a range comment.
// Every setting a user can change is also a row of settingOptions(), the one
// table that the CLI's flags, its --help and the EXR metadata all read.
#include <functional>
#include <span>
#include <string>
#include <string_view>

namespace headlight {

enum class SsgiMethod {
  Hemisphere,  // the seed's: indirect = occluders' albedo x range weight (not light)
  Radiance,    // the same occlusion test, gathering the occluders' direct Lambertian radiance
};

struct SsgiSettings {
  bool enabled = true;
  SsgiMethod method = SsgiMethod::Hemisphere;
  int sampleCount = 64;          // kernel samples per pixel, 1..64 (the seed's 64)
  float radius = 0.0f;           // world units, > 0; 0 = auto: kAutoRadiusFraction x scene diagonal
  float bias = 0.0f;             // world units, >= 0; 0 = auto: kAutoBiasFraction x radius
  float intensity = 1.0f;        // 0..~4: occlusion is multiplied by this before 1 - x
  float indirectStrength = -1;   // 0..4: the one-bounce term is multiplied by this; -1 = auto:
                                 // the seed's 0.5 for hemisphere, 1 (the estimator itself) for radiance
  unsigned seed = 1;             // kernel and noise random seed (fixed: renders are repeatable)
  bool blur = true;              // average out the 4x4 noise tile (a depth- and normal-aware 4x4 box)
  int downsample = 1;            // SSGI resolution divisor per side: 1 full, 2 half, 4 quarter; below
                                 // full resolution the blur pass is also the (depth-aware) upsample

  // The seed's fixed 0.5 assumed a scene a few units across; a radius that
  // follows the scene works from millimetres to kilometres. 0.15 of the
  // diagonal gives 0.52 on the Cornell box, the seed's value for that size.
  static constexpr float kAutoRadiusFraction = 0.15f;
  // The seed's ratio of bias to radius (0.025 / 0.5).
  static constexpr float kAutoBiasFraction = 0.05f;
};

struct LightingSettings {
  bool shadows = true;     // shadow maps for lights that cast shadows
  int shadowMapSize = 0;   // texels per side, 64..8192; 0 = auto: longer image side to the next power of two, 512..2048
  float pcfRadius = 1.5f;  // shadow filter radius in texels, 0..8
  float skyIntensity = -1.0f;  // >= 0 overrides the scene's sky intensity; -1 = the scene's
};

enum class Tonemap { Aces, Reinhard };

struct RenderSettings {
  int width = 640;    // pixels, 1..16384, width x height at most 2^26
  int height = 480;   // pixels, 1..16384
  int camera = -1;    // glTF camera index; -1 = the scene's first camera, or one fitted to the bounds
  SsgiSettings ssgi;
  LightingSettings lighting;
  Tonemap tonemap = Tonemap::Aces;  // preview.png only; lit.exr stays linear
  float exposure = 0.0f;            // EV, preview.png only

  // Throws SettingsError naming the setting, the allowed range and the value.
  void validate() const;
};

std::string_view ssgiMethodName(SsgiMethod method);  // "hemisphere", "radiance"
SsgiMethod parseSsgiMethod(std::string_view name);   // throws SettingsError

// One user-settable setting. `parse` throws SettingsError for a bad value.
struct SettingOption {
  std::string_view name;       // CLI flag without the leading "--"
  std::string_view valueName;  // e.g. "N", "auto|FLOAT"; empty for a switch
  std::string_view help;
  std::function<void(RenderSettings&, std::string_view value)> parse;
  std::function<std::string(const RenderSettings&)> format;
};
std::span<const SettingOption> settingOptions();

// Named presets: "fast" (radiance, 16 samples, SSGI at half resolution),
// "default", "high" (radiance, 64 samples, larger shadow maps), "seed" (the
// seed spec's fixed radius 0.5 and bias 0.025). Throws SettingsError for an unknown name.
void applyPreset(RenderSettings& settings, std::string_view preset);
std::span<const std::string_view> presetNames();

}  // namespace headlight

#pragma once
// Render settings: plain structs with in-class defaults. Each field a user
// can set is one row of settingOptions() (settings.cpp), which holds its
// flag name, type, range, help and whether it may be "auto"; the CLI's flags
// and --help, bench sweeps, the EXR metadata and embedding code all read
// that table. A setting that may be "auto" is a std::optional: std::nullopt
// is resolved from the scene or the image by Renderer::resolve, and a frame's
// settings have every optional filled in.
#include <filesystem>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <string_view>

#include "headlight/export.hpp"
#include "headlight/options.hpp"

namespace headlight HEADLIGHT_PUBLIC {

enum class SsgiMethod {
  Hemisphere,  // the seed's: indirect = occluders' albedo x range weight (not light)
  Radiance,    // the same occlusion test, gathering the occluders' direct Lambertian radiance
  Bitmask,     // screen-space slices with a 32-sector visibility mask (docs/ACCURACY.md §3.3)
};

// The resolution the SSGI pass runs at; below full, the blur pass is also a
// depth-aware upsample.
enum class SsgiResolution { Full, Half, Quarter };
int ssgiDivisor(SsgiResolution resolution);  // 1, 2, 4

struct SsgiSettings {
  bool enabled = true;
  SsgiMethod method = SsgiMethod::Bitmask;  // the seed's was Hemisphere (--preset seed)
  int sampleCount = 64;  // kernel samples per pixel (the seed's 64; at most the shader's kMaxKernelSamples)
  // World units. Auto: radiusFraction x the scene's bounding-box diagonal.
  std::optional<float> radius;
  // The seed's fixed 0.5 assumed a scene a few units across; a radius that
  // follows the scene works from millimetres to kilometres. 0.15 gives 0.52
  // on the Cornell box, the seed's value for that size.
  float radiusFraction = 0.15f;
  std::optional<float> bias;  // world units; auto: kAutoBiasFraction x radius
  float intensity = 1.0f;     // occlusion is multiplied by this before 1 - x
  // The one-bounce term is multiplied by this; auto: the seed's 0.5 for
  // hemisphere, 1 (the estimator itself) for radiance.
  std::optional<float> indirectStrength;
  unsigned seed = 1;  // kernel and noise random seed (fixed: renders are repeatable)
  bool blur = true;   // average out the SSGI noise (a depth- and normal-aware 7x7 Gaussian)
  SsgiResolution resolution = SsgiResolution::Full;
  // The bitmask method's: directions per pixel, depth samples per direction
  // and side, and the depth assumed behind every visible surface (world
  // units; auto: the scene's objects' typical depth, Renderer::resolve).
  int sliceCount = 2;
  // 2 x 8: the cheapest configuration on the bench's front that meets every
  // issue-11 target 2 x 16 meets, at 0.5 to 0.8 its SSGI time
  // (docs/BENCHMARKS.md, "Issue 11's targets"); thin slats want 16 (--preset high).
  int stepCount = 8;
  std::optional<float> thickness;
  // Bitmask: samples per direction and side beyond R, spaced geometrically
  // out to the screen edge, for the sky visibility the ambient term is
  // occluded by and the indirect light from beyond R (0: neither; the sky
  // visibility is the AO within R, as the kernel methods have it).
  // 16: twice the samples of the light from beyond R took cornell's HDR-FLIP
  // from 0.281 to 0.230 and its indirect error from 0.58 to 0.46 (issue 16;
  // docs/BENCHMARKS.md, "Sky steps").
  int skyStepCount = 16;
  // Bitmask: the far field (sky visibility and light from beyond R, the
  // `sky` half of ssgi.exr) is low-frequency: its own pass runs at this
  // resolution (never finer than `resolution`) with `farSliceCount`
  // directions, and the blur upsamples it; the near field (AO and light
  // within R) keeps `resolution`. At `resolution`, one pass draws both.
  // docs/BENCHMARKS.md, "Two resolutions".
  // Half and 2: cornell / slats / spheres / MetalRoughSpheres HDR-FLIP
  // 0.2429 / 0.0623 / 0.0497 / 0.0459 -> 0.2295 / 0.0626 / 0.0497 / 0.0468
  // and cornell's SSGI time 2.04x -> 1.64x hemisphere-64's; quarter and 3:
  // 1.47-1.55x at 0.2422 / 0.0625 / 0.0500 / 0.0470 (docs/BENCHMARKS.md).
  SsgiResolution farResolution = SsgiResolution::Half;
  int farSliceCount = 2;
  // Bitmask: the light from beyond R as one bounce of the punctual lights
  // off what each light sees, at most this many virtual point lights (a
  // few texels of each light's view of the scene, lib/passes/virtual_lights.hpp),
  // instead of what the screen-space marches find beyond R (0: the marches).
  // 1024: cornell's HDR-FLIP 0.2295 -> 0.131 and its indirect error 0.427 ->
  // 0.211 for 14-17 % more SSGI time (the other scenes up to 7 %); 2048 bought
  // 0.001 on cornell and lost it on slats; 512 lost 0.0006 on slats
  // (docs/BENCHMARKS.md, "Virtual lights").
  int virtualLightCount = 1024;
  // Bitmask with virtual lights: the most probes of a world-space light
  // field over the scene (lib/passes/light_field.hpp), made once per scene,
  // from which the far field takes the light the screen does not hold
  // (0: none; the virtual lights are gathered directly).
  int lightFieldProbes = 0;
  // Bitmask frames averaged, each with rotated slices and jittered steps
  // (with a still camera, exact temporal accumulation).
  int frames = 1;

  // The seed's ratio of bias to radius (0.025 / 0.5).
  static constexpr float kAutoBiasFraction = 0.05f;
  static constexpr float kAutoThicknessFraction = 0.5f;
};

struct LightingSettings {
  bool shadows = true;  // shadow maps for lights that cast shadows
  // Texels per side (point lights' cube faces: half); auto: 4x the longer
  // image side to the next power of two, 1024..2048.
  std::optional<int> shadowMapSize;
  float pcfRadius = 1.5f;             // shadow filter radius in texels
  std::optional<float> skyIntensity;  // auto: the scene's sky intensity
  // With an environment map (Scene::environment), which replaces the sky:
  float environmentIntensity = 1.0f;  // multiplies its radiance, 0..1e6
  float environmentRotation = 0.0f;   // degrees about +Y, -360..360 (right-handed: at 90 the map's -Z lies at -X)
  bool environmentBackground = true;  // shown behind the scene (off: background 0, alpha 0 as always)
};

enum class Tonemap { Aces, Reinhard };

// How the light images (lit, emissive, ssgi, and the direct light they are
// made from) are stored, on the GPU and in the EXRs: half float holds values
// up to 65504 at 2^-11 relative precision and halves memory, bandwidth and
// file size; float holds any light a scene can give.
enum class RadiancePrecision { Half, Float };

// How the fullscreen passes (direct light, SSGI and its blur, composite, the
// sky tables) run: as a fullscreen triangle's fragment shader or as a compute
// dispatch over the same per-pixel body. Auto chooses per pass: compute on a
// hardware GPU (data-centre GPUs starve fragment shading: 11-33x), and on a
// software rasteriser (llvmpipe) the form measured faster for that pass
// (docs/BENCHMARKS.md, "Fullscreen forms"). Both forms give the same pixels.
enum class FullscreenForm { Fragment, Compute };

struct RenderSettings {
  int width = 640;            // pixels; width x height at most 2^26
  int height = 480;           // pixels
  std::optional<int> camera;  // glTF camera index; auto: the scene's first camera, or one fitted to the bounds
  // lit (and preview.png, made from it): the mean of this many samples
  // jittered over the pixel (lib/frame/antialias.hpp); 1: the pixel centre
  // only. The other targets are the centre's: an average of normals or
  // depths across an edge is no surface's. 8: cornell 640x480's lit FLIP
  // against 16 samples 0.0090 -> 0.0024 (0.27x; 4: 0.55x, 6: 0.43x) for
  // 8 more draws of the G-buffer, direct light and composite
  // (docs/BENCHMARKS.md, "Antialiasing").
  int antialiasSamples = 8;
  // Each antialias sample runs the SSGI too, its noise turned (the seed
  // moved); off: each sample's composite reads the centre's SSGI, light low
  // in frequency whose per-sample cost is most of a frame's on llvmpipe.
  bool antialiasSsgi = false;
  SsgiSettings ssgi;
  LightingSettings lighting;
  Tonemap tonemap = Tonemap::Aces;  // preview.png only; lit.exr stays linear
  float exposure = 0.0f;            // EV, preview.png only
  // What preview.png shows where no geometry is: "sky" (the sky or
  // environment behind, as lit.exr has it), "transparent" (alpha = lit's
  // coverage) or a display colour, "#rrggbb" or "R,G,B" in 0..1.
  std::string previewBackground = "sky";
  // Auto: float when the scene has a light or an emitter bright enough that
  // half may clamp (resolve: autoRadiancePrecision), else half.
  std::optional<RadiancePrecision> radiancePrecision;
  // Auto chooses per pass, so it stays auto in a frame's settings; each
  // pass's form as it ran is in Frame::timings (PassTime::form).
  std::optional<FullscreenForm> fullscreenForm;

  // Checks every row's range and the rules between settings; throws
  // SettingsError naming the setting, the allowed range and the value.
  void validate() const;
};

// The one table: every user-settable field of RenderSettings, in help order.
std::span<const Option<RenderSettings>> settingOptions();

std::string_view ssgiMethodName(SsgiMethod method);  // "hemisphere", "radiance", "bitmask" (the table's choice names)

// Every setting as text, by row name ("ssgi-radius" -> "0.52"): what the EXR
// metadata records (as headlight:setting:<name>) and bench rows carry.
std::map<std::string, std::string> settingsAsText(const RenderSettings& settings);
// The inverse: applies each named value onto `settings` (unknown names are
// an error, so a typo in a settings file is not silently ignored).
void applySettingsText(RenderSettings& settings, const std::map<std::string, std::string>& values);

// A settings file (`headlight tune` writes one, `render --settings FILE`
// reads it): one `name = value` a line, names and values as the flags take
// them (the table's rows, through applySettingsText); blank lines and lines
// starting with '#' are ignored. settingsFileText writes every row but the
// image's and the view's (width, height, camera, antialias, antialias-ssgi:
// a render's, not the scene's), after `comments`, each as a '#' line.
std::string settingsFileText(const RenderSettings& settings, std::span<const std::string> comments = {});
// Applies the file's lines in order. Throws SettingsError "NAME:LINE: ..."
// for a malformed line, an unknown setting, a bad value or a setting given
// twice; `name` is the file's name for the messages.
void applySettingsFileText(RenderSettings& settings, std::string_view text, const std::string& name);
// Reads `path`, then applySettingsFileText; SettingsError naming the file if
// it cannot be read.
void applySettingsFile(RenderSettings& settings, const std::filesystem::path& path);

// Named presets: "fast" (bitmask, 1 slice of 8 steps, SSGI at half
// resolution), "default" (bitmask, 2 slices of 8 steps), "high" (bitmask,
// 4 slices of 24 steps, larger shadow maps), "seed" (the seed spec's method
// and constants: hemisphere, 64 samples, radius 0.5, bias 0.025). Throws
// SettingsError for an unknown name.
void applyPreset(RenderSettings& settings, std::string_view preset);
std::span<const std::string_view> presetNames();

}  // namespace HEADLIGHT_PUBLIC

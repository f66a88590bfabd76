#pragma once
// `headlight tune SCENE --max-ao-error E | --max-flip F`: the scene's own
// speed/accuracy front, measured at a small size against the ray-traced
// reference with the bench's machinery (measureConfigs), and a settings file
// holding the cheapest configuration whose AO RMSE is at most E and/or whose
// lit's mean HDR-FLIP against lit_ref is at most F (render --settings FILE).
#include <optional>
#include <string>
#include <vector>

#include "bench_command.hpp"

namespace headlight::cli {

// Exit code when no configuration reaches the bound: nothing is written.
constexpr int kExitTuneUnmet = 3;

struct TuneCommand {
  std::string scene = "builtin:cornell";
  // --out FILE: the settings file to write (the member's name is the one
  // commonCommandOptions binds --out to).
  std::string outDir = "headlight.settings";
  double maxAoError = -1;             // --max-ao-error E; < 0: not given
  double maxFlip = -1;                // --max-flip F (lit's mean HDR-FLIP); < 0: not given. One of the two is required
  RenderSettings base = smallBase();  // what every configuration starts from; 128 x 128
  std::vector<SettingSweep> sweeps;   // empty: defaultTuneSweeps()
  ReferenceSettings reference = tuneReference();
  int repetitions = 2;  // timed frames per configuration
  int warmup = 1;
  Verbosity verbosity = Verbosity::Normal;
  bool help = false;
  ContextOptions context;
  SceneLoadOptions sceneLoad;  // as render's (sceneInputOptions): --allow-external-paths, --strict-gltf, --scene
  std::vector<std::string> settingsFiles;  // every --settings FILE read: --out may not be one of them
  ResourceLimits limits;                   // --max-memory, --max-instances, --max-triangles, --max-texels

  // 128 x 128: each configuration's frames take tens of milliseconds on
  // llvmpipe, and the reference a few seconds (docs/BENCHMARKS.md, "tune").
  // Antialiasing off: the reference traces the pixel centres, and the
  // configurations' lit is judged against it pixel for pixel (an
  // antialiased edge would count as error in every one alike); the file
  // written leaves antialiasing to the render that reads it.
  static RenderSettings smallBase() {
    RenderSettings settings;
    settings.width = 128;
    settings.height = 128;
    settings.antialiasSamples = 1;
    return settings;
  }
  // 1024 rays: the reference's own AO noise (mean standard error about 0.01
  // on the built-ins) adds under 0.001 to an RMSE of 0.05 (in quadrature).
  static ReferenceSettings tuneReference() {
    ReferenceSettings reference;
    reference.samplesPerPixel = 1024;
    return reference;
  }
};

// Throws SettingsError for a bad flag or value, or when neither
// --max-ao-error nor --max-flip is given.
TuneCommand parseTuneArgs(const std::vector<std::string>& args);
std::string tuneHelp();

// The candidates when no --sweep is given: the bitmask method's slices,
// steps, thickness (auto, and half and twice `autoThickness`, the scene's
// resolved auto value), SSGI resolution and accumulated frames.
std::vector<SettingSweep> defaultTuneSweeps(float autoThickness);

// The row to write: the one with the least median frame time among those
// whose AO RMSE is at most `maxAoError` and whose lit HDR-FLIP (BenchRow::
// litFlip) is at most `maxFlip` (a bound not given: no limit); nullopt when
// none is.
std::optional<std::size_t> cheapestWithin(const std::vector<BenchRow>& rows, std::optional<double> maxAoError,
                                          std::optional<double> maxFlip = std::nullopt);

// Runs the whole command; returns the exit code.
int runTuneCommand(const std::vector<std::string>& args);

}  // namespace headlight::cli

#pragma once
// `headlight bench`: SSGI configurations timed and compared with the
// ray-traced reference, on each scene and resolution; writes bench.csv,
// bench.json and the chart (bench.png, bench.svg). Every configuration is
// the base settings (any render flag) with one combination of the --sweep
// values: any row of the setting table can be swept.
#include <string>
#include <utility>
#include <vector>

#include "cli_options.hpp"
#include "headlight/context.hpp"
#include "headlight/reference.hpp"
#include "headlight/settings.hpp"

namespace headlight::cli {

// One swept setting: a row of settingOptions() and its values, each already
// checked by that row's parser.
struct SettingSweep {
  std::string name;
  std::vector<OptionValue> values;
};

// What the bench sweeps when no --sweep is given: both methods, sample
// counts, radii around the auto radius, blur and SSGI resolution.
std::vector<SettingSweep> defaultBenchSweeps();

struct BenchCommand {
  std::vector<std::string> scenes;  // default: the built-ins
  std::string outDir = "bench";
  std::vector<std::pair<int, int>> resolutions{{128, 96}};
  RenderSettings base;               // what every configuration starts from (render flags)
  std::vector<SettingSweep> sweeps;  // empty: defaultBenchSweeps()
  ReferenceSettings reference;       // rays per pixel (--reference-samples)
  int repetitions = 5;               // timed frames per configuration (median and spread reported)
  int warmup = 2;                    // untimed frames first (shader variants, caches)
  bool chart = true;
  Verbosity verbosity = Verbosity::Normal;
  bool help = false;
  ContextOptions context;
};

// Throws SettingsError for a bad flag or value.
BenchCommand parseBenchArgs(const std::vector<std::string>& args);
std::string benchHelp();

// Every configuration of the command's sweep (cartesian product, in the
// order given), skipping combinations the settings refuse (below full SSGI
// resolution the blur cannot be off); then the seed preset.
struct BenchConfig {
  RenderSettings settings;
  std::string label;
  bool seedDefault = false;
};
std::vector<BenchConfig> benchConfigs(const BenchCommand& command, int width, int height);

// Runs the whole command; returns the exit code.
int runBenchCommand(const std::vector<std::string>& args);

}  // namespace headlight::cli

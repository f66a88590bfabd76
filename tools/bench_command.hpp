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
#include "headlight/renderer.hpp"
#include "headlight/settings.hpp"
#include "progress.hpp"
#include "tooling/bench.hpp"

namespace headlight::cli {

// One swept setting: a row of settingOptions() and its values, each already
// checked by that row's parser.
struct SettingSweep {
  std::string name;
  std::vector<OptionValue> values;
};

// "NAME=V1,V2,..." (a --sweep value): each value checked by the row NAME.
SettingSweep parseSweep(const std::string& text);

// --sweep (with `sweepHelp`, which must outlive the rows: a literal), --repetitions
// and --warmup: how bench and tune choose and time configurations. `Command`
// has sweeps, repetitions and warmup members.
template <class Command>
std::vector<Option<Command>> measurementOptions(std::string_view sweepHelp) {
  std::vector<Option<Command>> rows;
  rows.push_back(actionOption<Command>(
      {.name = "sweep", .type = OptionType::Text, .help = sweepHelp, .valueName = "NAME=V1,V2,..."},
      [](Command& c, const OptionValue& v) { c.sweeps.push_back(parseSweep(std::get<std::string>(v))); }));
  rows.push_back(bindOption<Command>(
      {.name = "repetitions",
       .type = OptionType::Int,
       .help = "timed frames per configuration",
       .minimum = 1,
       .maximum = 1000},
      [](auto& c) -> auto& { return c.repetitions; }));
  rows.push_back(bindOption<Command>(
      {.name = "warmup", .type = OptionType::Int, .help = "untimed frames first", .maximum = 1000},
      [](auto& c) -> auto& { return c.warmup; }));
  return rows;
}

// What the bench sweeps when no --sweep is given, as products of sweeps:
// the kernel methods over sample counts, radii around the auto radius, blur
// and SSGI resolution; and the default method, bitmask, over its slices and
// steps, the radii and the SSGI resolution (sample counts do not apply to it).
std::vector<std::vector<SettingSweep>> defaultBenchSweeps();

struct BenchCommand {
  std::vector<std::string> scenes;  // default: the built-ins
  std::string outDir = "bench";
  std::vector<std::pair<int, int>> resolutions{{128, 96}};
  // What every configuration starts from (render flags); antialiasing off
  // unless given: the reference traces the pixel centres, and lit is judged
  // against it pixel for pixel (TuneCommand::smallBase).
  RenderSettings base = centreSampled();
  std::vector<SettingSweep> sweeps;  // empty: every product of defaultBenchSweeps()
  static RenderSettings centreSampled() {
    RenderSettings settings;
    settings.antialiasSamples = 1;
    return settings;
  }
  ReferenceSettings reference;       // rays per pixel (--reference-samples)
  bool traceReference = true;        // --no-reference: time only (no errors, no chart, no Embree needed)
  int repetitions = 5;               // timed frames per configuration (median and spread reported)
  int warmup = 2;                    // untimed frames first (shader variants, caches)
  bool chart = true;
  bool force = false;  // replace bench.csv/json/png/svg files no earlier headlight bench wrote
  Verbosity verbosity = Verbosity::Normal;
  bool help = false;
  ContextOptions context;
  SceneLoadOptions sceneLoad;  // as render's (sceneInputOptions): --allow-external-paths, --strict-gltf, --scene
  ResourceLimits limits;       // --max-memory, --max-instances, --max-triangles, --max-texels
};

// Throws SettingsError for a bad flag or value.
BenchCommand parseBenchArgs(const std::vector<std::string>& args);
std::string benchHelp();

struct BenchConfig {
  RenderSettings settings;
  std::string label;
  bool seedDefault = false;
};
// Every combination of the sweeps' values on `base` at width x height
// (cartesian product, in the order given), skipping combinations the
// settings refuse (below full SSGI resolution the blur cannot be off).
std::vector<BenchConfig> sweepConfigs(const RenderSettings& base, const std::vector<SettingSweep>& sweeps, int width,
                                      int height);
// The command's sweep (sweepConfigs), then the seed preset.
std::vector<BenchConfig> benchConfigs(const BenchCommand& command, int width, int height);

// How each configuration is measured: untimed then timed frames, and the
// reference's rays per pixel.
struct MeasureOptions {
  int repetitions = 5;
  int warmup = 2;
  ReferenceSettings reference;
  bool traceReference = true;  // false: the rows' errors are nan (BenchRow::referenceTraced)
};
// Times each configuration on the renderer's scene and measures its errors
// against the reference, traced once per SSGI radius (the G-buffer is the
// same for every configuration of one camera and size). `progress` is
// advanced from `done`, which counts the configurations measured. Shared by
// `bench` and `tune`.
std::vector<BenchRow> measureConfigs(Renderer& renderer, const std::vector<BenchConfig>& configs,
                                     const MeasureOptions& options, Progress& progress, std::size_t& done);

// Runs the whole command; returns the exit code.
int runBenchCommand(const std::vector<std::string>& args);

}  // namespace headlight::cli

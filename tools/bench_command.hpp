#pragma once
// `headlight bench`: every SSGI method and setting, timed and compared with
// the ray-traced reference, on each scene and resolution; writes bench.csv,
// bench.json and the chart (bench.png, bench.svg).
#include <string>
#include <utility>
#include <vector>

#include "headlight/context.hpp"
#include "headlight/settings.hpp"

namespace headlight::cli {

struct BenchCommand {
  std::vector<std::string> scenes;  // default: the built-ins
  std::string outDir = "bench";
  std::vector<std::pair<int, int>> resolutions{{128, 96}};
  std::vector<SsgiMethod> methods{SsgiMethod::Hemisphere, SsgiMethod::Radiance};
  std::vector<int> samples{4, 8, 16, 32, 64};
  std::vector<float> radiusScales{0.5f, 1.0f, 2.0f};  // times the scene's auto radius
  std::vector<bool> blurs{true, false};
  std::vector<int> downsamples{1, 2};  // SSGI resolution divisors (1 full, 2 half, 4 quarter); blur forced below full
  int repetitions = 5;  // timed frames per configuration (median and spread reported)
  int warmup = 2;       // untimed frames first (shader variants, caches)
  int referenceSamples = 0;  // rays per pixel; 0 = ReferenceSettings' default
  bool chart = true;
  bool quiet = false;
  bool help = false;
  ContextOptions context;
};

// Throws SettingsError for a bad flag or value.
BenchCommand parseBenchArgs(const std::vector<std::string>& args);
std::string benchHelp();

// Runs the whole command; returns the exit code.
int runBenchCommand(const std::vector<std::string>& args);

}  // namespace headlight::cli

#pragma once
// What `headlight bench` measures, as functions a test can check: error
// metrics over geometry pixels, the Pareto front of (time, error), and the
// CSV/JSON rows. The sweep itself lives in tools/bench_command.cpp. Part of
// the internal support library (lib/tooling), not of libheadlight.
#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "headlight/frame.hpp"

namespace headlight {

// Error of channel `channelA` of `a` against channel `channelB` of `b` over
// the pixels where `mask` (a Frame's position target) has A = 1.
struct ErrorStats {
  double rmse = 0;
  double meanAbsolute = 0;
  double referenceMean = 0;  // mean of b over the same pixels (for relative errors)
  long long pixels = 0;
};
ErrorStats maskedError(const ImageF& a, int channelA, const ImageF& b, int channelB, const ImageF& mask);

// RMSE of an RGB triple (channels first..first+2 of each) over the mask, and
// that RMSE relative to the reference's mean (0 when the reference is 0).
struct ColorErrorStats {
  double rmse = 0;
  double relativeRmse = 0;
};
ColorErrorStats maskedColorError(const ImageF& a, int firstA, const ImageF& b, int firstB, const ImageF& mask);

// Mean SSIM (Wang et al. 2004; 7x7 box windows, C1 = 0.01^2, C2 = 0.03^2) of
// the luminance of two linear RGB(A) images after x/(1+x) tone mapping, over
// the windows centred on geometry pixels. 1 = identical.
double maskedSsim(const ImageF& a, const ImageF& b, const ImageF& mask);

// Mean HDR-FLIP (lib/diff/flip.hpp) of linear RGB(A) `test` against
// `reference` over every pixel (background included, as FLIP's tool and
// headlight diff take it); the exposures come from the reference. Throws
// Error for images of different sizes or without 3 channels.
double hdrFlipMean(const ImageF& test, const ImageF& reference);

// For points (time, error), both to be minimised: true where no other point
// is at least as good in both and better in one.
std::vector<bool> paretoFront(const std::vector<std::pair<double, double>>& timeError);

// Median and spread of repeated measurements (nan values left out; all nan
// or none: nan).
struct Summary {
  double median = 0;
  double minimum = 0;
  double maximum = 0;
};
Summary summarize(std::vector<double> values);

// One measured configuration on one scene at one resolution.
struct BenchRow {
  std::string scene;
  int width = 0;
  int height = 0;
  std::string label;  // the swept settings' values, e.g. "ssgi-method=radiance ssgi-samples=16"
  // Every render setting as used (auto values resolved), by the setting
  // table's row names: one CSV column each, so a new setting needs no change here.
  std::map<std::string, std::string> settings;
  bool seedDefault = false;  // the seed spec's settings (hemisphere, 64, radius 0.5, bias 0.025, no blur)
  int repetitions = 0;
  Summary frameMs;  // passes of one frame (G-buffer to composite), shadows cached, readback excluded
  Summary ssgiMs;   // SSGI (+ blur)
  // The same passes' GPU time (GL_TIME_ELAPSED queries: what the GPU spent,
  // without the CPU side llvmpipe adds to the wall times above).
  Summary frameGpuMs;
  Summary ssgiGpuMs;
  // Each pass's wall and GPU time (bench.json's "passes"), by PassTime::pass.
  std::map<std::string, Summary> passMs;
  std::map<std::string, Summary> passGpuMs;
  std::string forms;  // how each fullscreen pass ran, "direct=fragment ssgi=compute ..." (fullscreen-form)
  // No reference was traced (bench --no-reference): the error fields are
  // written as nan, and the rows time the configurations only.
  bool referenceTraced = true;
  ErrorStats ao;             // vs ao_ref within R
  ErrorStats sky;            // sky visibility (ssgi sky.Y) vs ao_ref's sky.Y, any distance
  ColorErrorStats indirect;  // vs indirect_ref within R
  ColorErrorStats lit;       // vs lit_ref
  double litSsim = 0;
  double litFlip = 0;  // mean HDR-FLIP (lib/diff/flip.hpp) of lit against lit_ref, over all pixels
  int referenceSamples = 0;
  double referenceAoStandardError = 0;
  bool referenceScreenBound = false;  // the errors are against the screen-space bound, not the truth
  bool paretoAo = false;              // on the (frame time, AO RMSE) front of its scene and resolution
  std::string renderer;               // GL_RENDERER
  std::string backend;
  std::string machine;  // CPU model and core count
};

// bench.csv's first columns: an earlier bench's file starts with them.
extern const char* const kCsvHeaderStart;
void writeBenchCsv(const std::vector<BenchRow>& rows, const std::filesystem::path& path);
void writeBenchJson(const std::vector<BenchRow>& rows, const std::string& command, const std::filesystem::path& path);

// "Model name" from /proc/cpuinfo and the hardware thread count.
std::string machineDescription();

}  // namespace headlight

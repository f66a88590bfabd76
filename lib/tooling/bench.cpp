#include "tooling/bench.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "diff/flip.hpp"
#include "headlight/error.hpp"
#include "headlight/settings.hpp"
#include "io/atomic_file.hpp"

namespace headlight {
namespace {

bool covered(const ImageF& mask, std::size_t pixel) { return mask.pixels[pixel * mask.channels.size() + 3] != 0.0f; }

void requireSameSize(const ImageF& a, const ImageF& b, const ImageF& mask) {
  if (a.width != b.width || a.height != b.height || a.width != mask.width || a.height != mask.height ||
      mask.channels.size() != 4)
    throw Error("bench metrics: images of different sizes (" + std::to_string(a.width) + "x" +
                std::to_string(a.height) + " vs " + std::to_string(b.width) + "x" + std::to_string(b.height) +
                ") or a mask without coverage");
}

float toneMappedLuminance(const ImageF& image, std::size_t pixel) {
  const float* p = &image.pixels[pixel * image.channels.size()];
  const float luminance = 0.2126f * p[0] + 0.7152f * p[1] + 0.0722f * p[2];
  return std::max(luminance, 0.0f) / (1.0f + std::max(luminance, 0.0f));
}

}  // namespace

ErrorStats maskedError(const ImageF& a, int channelA, const ImageF& b, int channelB, const ImageF& mask) {
  requireSameSize(a, b, mask);
  ErrorStats stats;
  double squared = 0, absolute = 0, reference = 0;
  const std::size_t count = std::size_t(a.width) * std::size_t(a.height);
  for (std::size_t p = 0; p < count; ++p) {
    if (!covered(mask, p)) continue;
    const double va = a.pixels[p * a.channels.size() + std::size_t(channelA)];
    const double vb = b.pixels[p * b.channels.size() + std::size_t(channelB)];
    squared += (va - vb) * (va - vb);
    absolute += std::abs(va - vb);
    reference += vb;
    ++stats.pixels;
  }
  if (stats.pixels > 0) {
    stats.rmse = std::sqrt(squared / double(stats.pixels));
    stats.meanAbsolute = absolute / double(stats.pixels);
    stats.referenceMean = reference / double(stats.pixels);
  }
  return stats;
}

ColorErrorStats maskedColorError(const ImageF& a, int firstA, const ImageF& b, int firstB, const ImageF& mask) {
  double squared = 0, reference = 0;
  long long pixels = 0;
  for (int c = 0; c < 3; ++c) {
    const ErrorStats channel = maskedError(a, firstA + c, b, firstB + c, mask);
    squared += channel.rmse * channel.rmse;
    reference += channel.referenceMean;
    pixels = channel.pixels;
  }
  ColorErrorStats stats;
  if (pixels == 0) return stats;
  stats.rmse = std::sqrt(squared / 3.0);
  const double referenceMean = reference / 3.0;
  stats.relativeRmse = referenceMean > 0 ? stats.rmse / referenceMean : 0.0;
  return stats;
}

double maskedSsim(const ImageF& a, const ImageF& b, const ImageF& mask) {
  requireSameSize(a, b, mask);
  const int width = a.width, height = a.height;
  std::vector<float> la(std::size_t(width) * std::size_t(height)), lb(la.size());
  for (std::size_t p = 0; p < la.size(); ++p) {
    la[p] = toneMappedLuminance(a, p);
    lb[p] = toneMappedLuminance(b, p);
  }
  constexpr int kHalf = 3;  // 7x7 windows
  constexpr double kC1 = 0.01 * 0.01, kC2 = 0.03 * 0.03;
  double sum = 0;
  long long windows = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      if (!covered(mask, std::size_t(y) * std::size_t(width) + std::size_t(x))) continue;
      double meanA = 0, meanB = 0, varA = 0, varB = 0, cov = 0;
      int n = 0;
      for (int dy = -kHalf; dy <= kHalf; ++dy)
        for (int dx = -kHalf; dx <= kHalf; ++dx) {
          const int sx = std::clamp(x + dx, 0, width - 1), sy = std::clamp(y + dy, 0, height - 1);
          const std::size_t q = std::size_t(sy) * std::size_t(width) + std::size_t(sx);
          meanA += la[q];
          meanB += lb[q];
          varA += double(la[q]) * la[q];
          varB += double(lb[q]) * lb[q];
          cov += double(la[q]) * lb[q];
          ++n;
        }
      meanA /= n;
      meanB /= n;
      varA = varA / n - meanA * meanA;
      varB = varB / n - meanB * meanB;
      cov = cov / n - meanA * meanB;
      sum +=
          ((2 * meanA * meanB + kC1) * (2 * cov + kC2)) / ((meanA * meanA + meanB * meanB + kC1) * (varA + varB + kC2));
      ++windows;
    }
  return windows > 0 ? sum / double(windows) : 1.0;
}

double hdrFlipMean(const ImageF& test, const ImageF& reference) {
  if (test.width != reference.width || test.height != reference.height || test.channelCount() < 3 ||
      reference.channelCount() < 3)
    throw Error("HDR-FLIP: expected two RGB images of one size, got " + std::to_string(test.width) + "x" +
                std::to_string(test.height) + " with " + std::to_string(test.channelCount()) + " channels and " +
                std::to_string(reference.width) + "x" + std::to_string(reference.height) + " with " +
                std::to_string(reference.channelCount()));
  return flip::hdrFlip({reference.pixels.data(), reference.width, reference.height, reference.channelCount()},
                       {test.pixels.data(), test.width, test.height, test.channelCount()})
      .mean;
}

std::vector<bool> paretoFront(const std::vector<std::pair<double, double>>& points) {
  std::vector<bool> front(points.size(), true);
  for (std::size_t i = 0; i < points.size(); ++i)
    for (std::size_t j = 0; j < points.size() && front[i]; ++j) {
      const bool noWorse = points[j].first <= points[i].first && points[j].second <= points[i].second;
      const bool better = points[j].first < points[i].first || points[j].second < points[i].second;
      if (j != i && noWorse && better) front[i] = false;
    }
  return front;
}

Summary summarize(std::vector<double> values) {
  Summary summary;
  // Unknown values (nan: a GPU time the driver did not give) are left out;
  // none known: all nan.
  std::erase_if(values, [](double value) { return std::isnan(value); });
  if (values.empty()) {
    summary.median = summary.minimum = summary.maximum = std::numeric_limits<double>::quiet_NaN();
    return summary;
  }
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  summary.median = n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
  summary.minimum = values.front();
  summary.maximum = values.back();
  return summary;
}

std::string machineDescription() {
  std::ifstream cpuinfo("/proc/cpuinfo");
  std::string line, model = "unknown CPU";
  while (std::getline(cpuinfo, line))
    if (line.rfind("model name", 0) == 0) {
      model = line.substr(line.find(':') + 2);
      break;
    }
  return model + ", " + std::to_string(std::thread::hardware_concurrency()) + " hardware threads";
}

const char* const kCsvHeaderStart = "scene,label,";

namespace {

// Settings columns (width and height among them) come between kCsvHeaderStart and this, one per setting row.
const char* kCsvHeaderEnd =
    "seed_default,repetitions,"
    "frame_ms_median,frame_ms_min,frame_ms_max,ssgi_ms_median,ssgi_ms_min,ssgi_ms_max,"
    "frame_gpu_ms_median,frame_gpu_ms_min,frame_gpu_ms_max,ssgi_gpu_ms_median,ssgi_gpu_ms_min,ssgi_gpu_ms_max,forms,"
    "ao_rmse,ao_mae,sky_rmse,sky_mae,indirect_rmse,indirect_rel_rmse,lit_rel_rmse,lit_ssim,lit_flip,"
    "reference_samples,reference_ao_se,reference_screen_bound,pareto_ao,renderer,backend,machine";

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += c == '"' ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

}  // namespace

void writeBenchCsv(const std::vector<BenchRow>& rows, const std::filesystem::path& path) {
  std::ostringstream out;
  out << std::setprecision(6) << kCsvHeaderStart;
  for (const Option<RenderSettings>& option : settingOptions()) out << option.spec.name << ',';
  out << kCsvHeaderEnd << "\n";
  for (const BenchRow& r : rows) {
    out << csvField(r.scene) << ',' << csvField(r.label) << ',';
    for (const Option<RenderSettings>& option : settingOptions()) {
      const auto value = r.settings.find(std::string(option.spec.name));
      out << (value == r.settings.end() ? "" : csvField(value->second)) << ',';
    }
    out << r.seedDefault << ',' << r.repetitions << ',' << r.frameMs.median << ',' << r.frameMs.minimum << ','
        << r.frameMs.maximum << ',' << r.ssgiMs.median << ',' << r.ssgiMs.minimum << ',' << r.ssgiMs.maximum << ','
        << r.frameGpuMs.median << ',' << r.frameGpuMs.minimum << ',' << r.frameGpuMs.maximum << ','
        << r.ssgiGpuMs.median << ',' << r.ssgiGpuMs.minimum << ',' << r.ssgiGpuMs.maximum << ',' << csvField(r.forms)
        << ',' << r.ao.rmse << ',' << r.ao.meanAbsolute << ',' << r.sky.rmse << ',' << r.sky.meanAbsolute << ','
        << r.indirect.rmse << ',' << r.indirect.relativeRmse << ',' << r.lit.relativeRmse << ',' << r.litSsim << ','
        << r.litFlip << ',' << r.referenceSamples << ',' << r.referenceAoStandardError << ',' << r.referenceScreenBound
        << ',' << r.paretoAo << ',' << csvField(r.renderer) << ',' << csvField(r.backend) << ',' << csvField(r.machine)
        << "\n";
  }
  detail::writeTextAtomically(path, out.str());
}

void writeBenchJson(const std::vector<BenchRow>& rows, const std::string& command, const std::filesystem::path& path) {
  nlohmann::json json;
  json["command"] = command;
  json["rows"] = nlohmann::json::array();
  for (const BenchRow& r : rows) {
    auto summary = [](const Summary& s) {
      return nlohmann::json{{"median", s.median}, {"min", s.minimum}, {"max", s.maximum}};
    };
    nlohmann::json passes = nlohmann::json::object();
    for (const auto& [pass, wall] : r.passMs) {
      passes[pass]["ms"] = summary(wall);
      const auto gpu = r.passGpuMs.find(pass);
      if (gpu != r.passGpuMs.end()) passes[pass]["gpu_ms"] = summary(gpu->second);
    }
    const nlohmann::json reference{{"traced", r.referenceTraced},
                                   {"samples", r.referenceSamples},
                                   {"ao_standard_error", r.referenceAoStandardError},
                                   {"screen_bound", r.referenceScreenBound}};
    json["rows"].push_back({{"scene", r.scene},
                            {"width", r.width},
                            {"height", r.height},
                            {"label", r.label},
                            {"settings", r.settings},
                            {"seed_default", r.seedDefault},
                            {"repetitions", r.repetitions},
                            {"frame_ms", summary(r.frameMs)},
                            {"ssgi_ms", summary(r.ssgiMs)},
                            {"frame_gpu_ms", summary(r.frameGpuMs)},
                            {"ssgi_gpu_ms", summary(r.ssgiGpuMs)},
                            {"forms", r.forms},
                            {"passes", passes},
                            {"ao", {{"rmse", r.ao.rmse}, {"mae", r.ao.meanAbsolute}, {"pixels", r.ao.pixels}}},
                            {"sky", {{"rmse", r.sky.rmse}, {"mae", r.sky.meanAbsolute}}},
                            {"indirect", {{"rmse", r.indirect.rmse}, {"relative_rmse", r.indirect.relativeRmse}}},
                            {"lit", {{"relative_rmse", r.lit.relativeRmse}, {"ssim", r.litSsim}, {"flip", r.litFlip}}},
                            {"reference", reference},
                            {"pareto_ao", r.paretoAo},
                            {"renderer", r.renderer},
                            {"backend", r.backend},
                            {"machine", r.machine}});
  }
  detail::writeTextAtomically(path, json.dump(2) + "\n");
}

}  // namespace headlight

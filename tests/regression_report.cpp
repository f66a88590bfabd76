#include "regression_report.hpp"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <cmath>
#include <fstream>
#include <sstream>

namespace headlight::test {
namespace {

namespace fs = std::filesystem;

// The channels a person would look at, by name (files store them sorted).
std::vector<std::string> displayChannels(const OIIO::ImageSpec& spec) {
  for (const auto& names :
       std::vector<std::vector<std::string>>{{"R", "G", "B"},
                                             {"position.X", "position.Y", "position.Z"},
                                             {"normal.X", "normal.Y", "normal.Z"},
                                             {"albedo.R", "albedo.G", "albedo.B"},
                                             {"emissive.R", "emissive.G", "emissive.B"},
                                             {"material.metallic", "material.roughness", "material.occlusion"},
                                             {"ao.Y"},
                                             {"depth.Z"}}) {
    bool all = true;
    for (const auto& name : names) all &= spec.channelindex(name) >= 0;
    if (all) return names;
  }
  return {spec.channelnames.front()};
}

// An 8-bit picture of an EXR: the display channels scaled by `low..high`
// (the golden's range, so golden and actual share one scale).
void writeThumbnail(const fs::path& exr, const fs::path& png, float low, float high) {
  OIIO::ImageBuf image(exr.string());
  if (!image.read(0, 0, true, OIIO::TypeDesc::FLOAT)) return;
  std::vector<int> order;
  for (const auto& name : displayChannels(image.spec())) order.push_back(image.spec().channelindex(name));
  if (order.size() == 1) order = {order[0], order[0], order[0]};
  OIIO::ImageBuf picked = OIIO::ImageBufAlgo::channels(image, 3, order);
  const float scale = high > low ? 1.0f / (high - low) : 1.0f;
  OIIO::ImageBuf scaled = OIIO::ImageBufAlgo::mad(picked, scale, -low * scale);
  OIIO::ImageBuf clamped = OIIO::ImageBufAlgo::clamp(scaled, 0.0f, 1.0f);
  clamped.write(png.string(), OIIO::TypeDesc::UINT8);
}

std::pair<float, float> range(const fs::path& exr) {
  OIIO::ImageBuf image(exr.string());
  if (!image.read(0, 0, true, OIIO::TypeDesc::FLOAT)) return {0.0f, 1.0f};
  std::vector<int> order;
  for (const auto& name : displayChannels(image.spec())) order.push_back(image.spec().channelindex(name));
  const auto stats =
      OIIO::ImageBufAlgo::computePixelStats(OIIO::ImageBufAlgo::channels(image, int(order.size()), order));
  float low = INFINITY, high = -INFINITY;
  for (std::size_t c = 0; c < stats.min.size(); ++c) {
    if (std::isfinite(stats.min[c])) low = std::min(low, stats.min[c]);
    if (std::isfinite(stats.max[c])) high = std::max(high, stats.max[c]);
  }
  if (!(low < high)) return {0.0f, 1.0f};
  return {low, high};
}

std::string escape(const std::string& text) {
  std::string out;
  for (char c : text) out += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : std::string(1, c);
  return out;
}

}  // namespace

fs::path writeRegressionReport(const DirectoryDiff& diff, const std::string& name, const fs::path& folder) {
  fs::create_directories(folder);
  std::ostringstream html;
  html << "<!doctype html><html><head><meta charset=utf-8><title>regression: " << escape(name)
       << "</title><style>body{font-family:sans-serif}td{vertical-align:top;padding:4px}"
          "img{width:256px;image-rendering:pixelated}.fail{color:#b00}.pass{color:#070}</style></head><body>"
       << "<h1>" << escape(name) << ": " << statusName(diff.status) << "</h1><p>golden: " << escape(diff.a.string())
       << "<br>actual: " << escape(diff.b.string()) << "</p><table><tr><th>target</th><th>golden</th><th>actual</th>"
       << "<th>error heatmap</th><th>numbers</th></tr>";
  for (const DiffResult& target : diff.targets) {
    const std::string stem = target.target;
    const auto [low, high] = range(target.a);
    writeThumbnail(target.a, folder / (stem + "_golden.png"), low, high);
    writeThumbnail(target.b, folder / (stem + "_actual.png"), low, high);
    std::string heatmap;
    if (!target.difference.empty()) {
      writeDiffImages(target, folder / (stem + "_diff.exr"));
      heatmap = stem + "_diff.png";
    }
    const bool ok = target.status == DiffStatus::Pass;
    html << "<tr><td><b>" << escape(stem) << "</b><br><span class=" << (ok ? "pass" : "fail") << ">"
         << statusName(target.status) << "</span></td><td><img src='" << stem << "_golden.png'></td><td><img src='"
         << stem << "_actual.png'></td><td>" << (heatmap.empty() ? "" : "<img src='" + heatmap + "'>")
         << "</td><td>metric " << metricName(target.metric) << "<br>max error " << target.maxError << " at ("
         << target.maxX << ", " << target.maxY << ") " << escape(target.maxChannel) << "<br>failing pixels "
         << target.failingPercent << "% (allowed " << target.thresholds.failPercent << "%, fail > "
         << target.thresholds.fail << ", hard fail > " << target.thresholds.hardFail << ")<br>"
         << escape(target.problem) << "</td></tr>";
  }
  html << "</table></body></html>\n";
  const fs::path page = folder / "report.html";
  std::ofstream(page) << html.str();
  return page;
}

}  // namespace headlight::test

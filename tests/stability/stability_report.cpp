// stability-report: runs every stability case for every SSGI method (the
// functions the stability tests assert on) and writes what docs/STABILITY.md
// shows: one PNG per case under <docs>/stability/, and the table, which
// replaces the text between the two marker lines of <docs>/STABILITY.md and
// is printed. Measurements are printed by this tool; the tests check bounds.
//
//   build/tests/stability-report docs [--backend egl|osmesa|auto]
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include "headlight/context.hpp"
#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "headlight/reference.hpp"
#include "output/tonemap.hpp"
#include "stability/stability.hpp"
#include "tooling/bench.hpp"

namespace fs = std::filesystem;
using namespace headlight;
using namespace headlight::stability;

namespace {

constexpr const char* kTableBegin = "<!-- stability-report: begin (generated, do not edit) -->";
constexpr const char* kTableEnd = "<!-- stability-report: end -->";
// Pictures stay small in the repository: 256 pixels wide in all, each cell
// at most 128.
constexpr int kPictureWidth = 256;
constexpr int kCellGap = 2;

// ---- Pictures ------------------------------------------------------------------

float srgbEncode(float linear) {
  linear = std::clamp(linear, 0.0f, 1.0f);
  return linear <= 0.0031308f ? 12.92f * linear : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

// The panel as display RGB (0..1): AO as is (a factor, shown linearly), lit
// tonemapped and sRGB-encoded, signed errors blue-white-red.
std::array<float, 3> displayColor(const Panel& panel, int x, int y) {
  if (!panel.coverage.empty() && panel.coverage.at(x, y, 3) == 0.0f) return {0.45f, 0.6f, 0.8f};
  const float value = panel.image.at(x, y, panel.channel);
  switch (panel.kind) {
    case Panel::Kind::Grey: {
      const float grey = std::clamp(value, 0.0f, 1.0f);
      return {grey, grey, grey};
    }
    case Panel::Kind::Tonemapped: {
      std::array<float, 3> rgb{};
      for (int c = 0; c < 3; ++c)
        rgb[std::size_t(c)] = srgbEncode(tonemapAces(panel.image.at(x, y, panel.channel + c)));
      return rgb;
    }
    case Panel::Kind::Signed: {
      const float e = std::clamp(value / panel.scale, -1.0f, 1.0f);
      return e >= 0 ? std::array<float, 3>{1.0f, 1.0f - e, 1.0f - e} : std::array<float, 3>{1.0f + e, 1.0f + e, 1.0f};
    }
  }
  return {0, 0, 0};
}

OIIO::ImageBuf panelImage(const Panel& panel, int cellWidth) {
  const int width = panel.image.width, height = panel.image.height;
  OIIO::ImageBuf source(OIIO::ImageSpec(width, height, 3, OIIO::TypeDesc::FLOAT));
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      const auto rgb = displayColor(panel, x, y);
      source.setpixel(x, y, rgb.data(), 3);
    }
  const int cellHeight = std::max(1, int(std::lround(double(cellWidth) * height / width)));
  OIIO::ImageBuf cell;
  // Box filter: AO noise stays visible as it is, not ringed.
  OIIO::ImageBufAlgo::resize(cell, source, "box", 0, OIIO::ROI(0, cellWidth, 0, cellHeight, 0, 1, 0, 3));
  return cell;
}

// One row per method, one column per panel.
void writeCasePicture(const std::vector<CaseResult>& perMethod, const fs::path& path) {
  const std::size_t columns = perMethod.front().panels.size();
  if (columns == 0) return;
  const int cellWidth = std::min(128, int((kPictureWidth - kCellGap * int(columns - 1)) / int(columns)));
  std::vector<std::vector<OIIO::ImageBuf>> cells;
  int totalHeight = 0;
  for (const CaseResult& result : perMethod) {
    cells.emplace_back();
    int rowHeight = 0;
    for (const Panel& panel : result.panels) {
      cells.back().push_back(panelImage(panel, cellWidth));
      rowHeight = std::max(rowHeight, cells.back().back().spec().height);
    }
    totalHeight += rowHeight + (totalHeight ? kCellGap : 0);
  }
  const int totalWidth = int(columns) * cellWidth + kCellGap * int(columns - 1);
  OIIO::ImageBuf canvas(OIIO::ImageSpec(totalWidth, totalHeight, 3, OIIO::TypeDesc::FLOAT));
  const float gap[3] = {1, 1, 1};
  OIIO::ImageBufAlgo::fill(canvas, gap);
  int top = 0;
  for (const auto& row : cells) {
    int left = 0, rowHeight = 0;
    for (const OIIO::ImageBuf& cell : row) {
      OIIO::ImageBufAlgo::paste(canvas, left, top, 0, 0, cell);
      left += cellWidth + kCellGap;
      rowHeight = std::max(rowHeight, cell.spec().height);
    }
    top += rowHeight + kCellGap;
  }
  if (!canvas.write(path.string(), OIIO::TypeDesc::UINT8)) throw IoError(path.string() + ": " + canvas.geterror());
}

// ---- Table ---------------------------------------------------------------------

std::string formatNumber(double value) {
  char text[32];
  if (!std::isfinite(value)) return value != value ? "NaN" : (value > 0 ? "inf" : "-inf");
  if (value == std::round(value))
    std::snprintf(text, sizeof text, "%.0f", value);
  else if (value != 0 && std::abs(value) < 1e-3)
    std::snprintf(text, sizeof text, "%.1e", value);
  else
    std::snprintf(text, sizeof text, std::abs(value) < 10 ? "%.3f" : "%.1f", value);
  return text;
}

// A table cell: '|' would end it.
std::string markdownCell(const std::string& text) {
  std::string cell;
  for (char c : text) cell += c == '|' ? std::string("\\|") : std::string(1, c);
  return cell;
}

std::string formatBound(const Check& check) {
  return std::string(check.relation == Relation::AtLeast ? "≥ " : "≤ ") + formatNumber(check.bound);
}

// Rows of one case: its checks, then its notes; values side by side per
// method (every method's result lists the same quantities in the same order).
void appendCaseRows(std::ostringstream& table, const std::vector<CaseResult>& perMethod) {
  const CaseResult& first = perMethod.front();
  bool firstRow = true;
  auto row = [&](const std::string& quantity, const std::vector<double>& values, const std::string& asserted) {
    table << "| " << (firstRow ? first.failureMode : "") << " | " << markdownCell(quantity);
    for (double value : values) table << " | " << formatNumber(value);
    table << " | " << asserted << " | "
          << (firstRow && !first.panels.empty() ? "[png](stability/" + first.id + ".png)" : "") << " |\n";
    firstRow = false;
  };
  for (std::size_t i = 0; i < first.checks.size(); ++i) {
    std::vector<double> values;
    std::string asserted;
    for (const CaseResult& result : perMethod) {
      values.push_back(result.checks[i].measured);
      std::string bound = formatBound(result.checks[i]);
      if (!result.checks[i].knownBug.empty()) bound += " (fails: bug " + result.checks[i].knownBug.substr(0, 2) + ")";
      if (asserted.find(bound) == std::string::npos) asserted += (asserted.empty() ? "" : " / ") + bound;
    }
    row(first.checks[i].quantity, values, asserted);
  }
  for (std::size_t i = 0; i < first.notes.size(); ++i) {
    std::vector<double> values;
    for (const CaseResult& result : perMethod) values.push_back(result.notes[i].value);
    row(first.notes[i].quantity, values, "reported");
  }
}

std::string makeTable(const std::vector<std::vector<CaseResult>>& results, const Context& context) {
  std::ostringstream table;
  table << "Renderer: " << context.renderer() << " (" << context.description() << "), " << machineDescription()
        << ". Reference: Embree, " << kReferenceSamples << " rays per pixel.\n\n";
  table << "| Failure mode | Quantity";
  for (SsgiMethod method : kMethods) table << " | " << ssgiMethodName(method);
  table << " | Asserted | Picture |\n|---|---";
  for (std::size_t i = 0; i < std::size(kMethods); ++i) table << "|---:";
  table << "|---|---|\n";
  for (const auto& perMethod : results) appendCaseRows(table, perMethod);
  return table.str();
}

// Replaces the text between the markers of `doc`; false if it has none.
bool replaceGenerated(const fs::path& doc, const std::string& generated) {
  std::ifstream in(doc);
  if (!in) return false;
  std::stringstream whole;
  whole << in.rdbuf();
  std::string text = whole.str();
  const std::size_t begin = text.find(kTableBegin), end = text.find(kTableEnd);
  if (begin == std::string::npos || end == std::string::npos || end < begin) return false;
  const std::size_t from = begin + std::string(kTableBegin).size();
  text.replace(from, end - from, "\n" + generated);
  std::ofstream(doc) << text;
  return true;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 4 || (argc == 4 && std::string(argv[2]) != "--backend") || argc == 3) {
    std::cerr << "usage: stability-report DOCS_DIR [--backend egl|osmesa|auto]\n";
    return 2;
  }
  try {
    const fs::path docs = argv[1];
    fs::create_directories(docs / "stability");
    Context context(ContextOptions{.backend = argc == 4 ? parseBackend(argv[3]) : Backend::Auto,
                                   .errorPolicy = GlErrorPolicy::Throw,
                                   .eglDeviceName = {}});
    Renderer renderer(context);
    std::vector<std::vector<CaseResult>> results;
    for (const CaseEntry& entry : allCases()) {
      if (entry.needsReference && !referenceAvailable()) {
        std::cerr << "skipping " << entry.name << ": this build has no Embree reference\n";
        continue;
      }
      results.emplace_back();
      for (SsgiMethod method : kMethods) {
        results.back().push_back(entry.run(renderer, method));
        std::cerr << results.back().back().describe();
      }
      writeCasePicture(results.back(), docs / "stability" / (results.back().front().id + ".png"));
    }
    const std::string table = makeTable(results, context);
    std::cout << table;
    if (replaceGenerated(docs / "STABILITY.md", table))
      std::cerr << "updated " << (docs / "STABILITY.md").string() << "\n";
    else
      std::cerr << (docs / "STABILITY.md").string() << " has no markers; the table was only printed\n";
  } catch (const Error& error) {
    std::cerr << "stability-report: " << error.what() << "\n";
    return 1;
  }
  return 0;
}

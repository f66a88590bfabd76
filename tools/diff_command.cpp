// headlight diff: flags -> DiffOptions -> diffImages / diffDirectories ->
// a table (or one JSON object) -> optional diff images -> exit code.
#include "diff_command.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "diff/heatmap.hpp"
#include "headlight/diff.hpp"
#include "headlight/error.hpp"
#include "headlight/options.hpp"
#include "settings/option_binding.hpp"
#include "tooling/command_line.hpp"

namespace headlight::cli {
namespace {

namespace fs = std::filesystem;
// ordered_json keeps keys in insertion order: status first, as a reader expects.
using json = nlohmann::ordered_json;

// A bad command line: exit kDiffExitUsage with the message.
struct UsageError {
  std::string message;
};

struct DiffCommand {
  std::vector<std::string> paths;  // A, B
  DiffOptions options;
  std::string out;  // file mode: diff.exr; folder mode: a folder
  bool json = false;
  bool quiet = false;
  bool force = false;  // replace files in --out that no earlier headlight diff wrote
  bool help = false;
};

std::vector<std::string> parseChannels(const std::string& text) {
  std::vector<std::string> names;
  std::stringstream stream(text);
  for (std::string name; std::getline(stream, name, ',');) {
    if (name.empty()) throw UsageError{"--channels: empty channel name in '" + text + "' (expected c1,c2,...)"};
    names.push_back(name);
  }
  if (names.empty()) throw UsageError{"--channels: expected c1,c2,..., got an empty list"};
  return names;
}

// The target table's names, for --target's choices.
std::span<const std::string_view> targetNames() {
  static const std::vector<std::string_view> names = [] {
    std::vector<std::string_view> list;
    for (const FrameTarget& target : frameTargets()) list.push_back(target.name);
    list.push_back(previewTargetRow().name);
    return list;
  }();
  return names;
}

// A threshold row: a number, or "auto" for the target's default (the table's).
Option<DiffCommand> threshold(std::string_view name, std::string_view help, double maximum,
                              std::optional<double> DiffOptions::*field) {
  return bindOption<DiffCommand>(
      {.name = name,
       .type = OptionType::Float,
       .help = help,
       .maximum = maximum,
       .autoMeaning = "the target's default (table below)"},
      [field](auto& c) -> auto& { return c.options.*field; });
}

const std::vector<Option<DiffCommand>>& diffOptions() {
  using T = OptionType;
  using C = DiffCommand;
  constexpr double kInf = std::numeric_limits<double>::infinity();
  static const std::vector<Option<C>> rows{
      threshold("fail", "a pixel fails when any channel's error > this", kInf, &DiffOptions::fail),
      threshold("failpercent", "FAIL when more than this % of the pixels fail", 100, &DiffOptions::failPercent),
      threshold("hardfail", "FAIL when any error > this, however few pixels (inf = off)", kInf, &DiffOptions::hardFail),
      threshold("failmean", "FAIL when any channel's mean error > this (inf = off)", kInf, &DiffOptions::failMean),
      threshold("warn", "a pixel warns when any channel's error > this", kInf, &DiffOptions::warn),
      threshold("warnpercent", "WARN when more than this % of the pixels warn", 100, &DiffOptions::warnPercent),
      threshold("hardwarn", "WARN when any error > this (inf = off)", kInf, &DiffOptions::hardWarn),
      actionOption<C>({.name = "channels",
                       .type = T::Text,
                       .help = "compare only these channels (file mode only)",
                       .valueName = "c1,c2,..."},
                      [](C& c, const OptionValue& v) { c.options.channels = parseChannels(std::get<std::string>(v)); }),
      actionOption<C>({.name = "metric",
                       .type = T::Choice,
                       .help = "judge by this error measure instead of the target's (its thresholds then come "
                               "from the first table row using it: flip -> lit's)",
                       .choices = metricNames()},
                      [](C& c, const OptionValue& v) {
                        const auto names = metricNames();
                        const auto found = std::find(names.begin(), names.end(), std::get<std::string>(v));
                        c.options.metric = DiffMetric(found - names.begin());
                      }),
      // A typo would silently fall back to idiff's defaults: a choice refuses it.
      actionOption<C>({.name = "target",
                       .type = T::Choice,
                       .help = "use this row of the default table (file mode only; default: A's file stem)",
                       .choices = targetNames()},
                      [](C& c, const OptionValue& v) { c.options.target = std::get<std::string>(v); }),
      actionOption<C>(
          {.name = "out",
           .type = T::Text,
           .help = "write the difference: file mode PATH.exr/.png/.html; folder mode <target>_diff.* + report.html",
           .valueName = "PATH"},
          [](C& c, const OptionValue& v) {
            if (std::get<std::string>(v).empty()) throw UsageError{"--out: expected a path"};
            c.out = std::get<std::string>(v);
          }),
      actionOption<C>({.name = "max-memory",
                       .type = T::Int,
                       .help = "MiB the compared images may take decoded (checked on their declared sizes first)",
                       .minimum = 64,
                       .maximum = double(std::int64_t(1) << 30),
                       .autoMeaning = "half of physical memory or of the address-space limit (ulimit -v), the smaller"},
                      [](C& c, const OptionValue& v) {
                        if (const auto* mib = std::get_if<std::int64_t>(&v))
                          c.options.maxMemoryMiB = *mib;
                        else
                          c.options.maxMemoryMiB.reset();  // auto
                      }),
      actionOption<C>({.name = "max-flip-exposures",
                       .type = T::Int,
                       .help = "HDR-FLIP: most exposures evaluated (one a stop from A's brightest luminance to its "
                               "median, each a whole FLIP); a pair needing more is refused [default: 64]",
                       .minimum = 2,
                       .maximum = 100000},
                      [](C& c, const OptionValue& v) { c.options.maxFlipExposures = int(std::get<std::int64_t>(v)); }),
      bindOption<C>(
          {.name = "force",
           .type = T::Switch,
           .help = "let --out replace files that no earlier headlight diff wrote there (a report.html, "
                   "a PNG of your own)"},
          [](auto& c) -> auto& { return c.force; }),
      bindOption<C>(
          {.name = "json", .type = T::Switch, .help = "print one JSON object instead of the table"},
          [](auto& c) -> auto& { return c.json; }),
      bindOption<C>(
          {.name = "quiet",
           .type = T::Switch,
           .help = "print nothing on stdout (the exit code tells); errors still go to stderr"},
          [](auto& c) -> auto& { return c.quiet; }),
      bindOption<C>(
          {.name = "help", .type = T::Switch, .help = "this help"}, [](auto& c) -> auto& { return c.help; }),
  };
  return rows;
}

DiffCommand parseDiffArgs(const std::vector<std::string>& args) {
  DiffCommand command;
  try {
    command.paths = parseCommandLine<DiffCommand>(args, diffOptions(), command, "diff");
  } catch (const SettingsError& error) {
    throw UsageError{error.what()};
  }
  if (command.help) return command;
  if (command.paths.size() != 2)
    throw UsageError{"expected two images or two folders (A B), got " + std::to_string(command.paths.size()) + " path" +
                     (command.paths.size() == 1 ? "" : "s")};
  return command;
}

// ---- printing ---------------------------------------------------------------

std::string number(double value) {
  if (std::isinf(value)) return value > 0 ? "inf" : "-inf";
  char text[32];
  std::snprintf(text, sizeof text, "%.4g", value);
  return text;
}

std::string upper(std::string_view text) {
  std::string result(text);
  for (char& c : result) c = char(std::toupper(static_cast<unsigned char>(c)));
  return result;
}

std::string unitSuffix(DiffMetric metric) { return metric == DiffMetric::AngleDegrees ? " deg" : ""; }

std::string flipDescription(const DiffResult& r) {
  if (!r.flip) return "error = FLIP of R, G, B (0..1); other channels absolute";
  const FlipDetails& f = *r.flip;
  std::string text = f.hdr ? "error = HDR-FLIP of R, G, B (0..1) over " + std::to_string(f.exposureCount) +
                                 " exposures " + number(f.startExposure) + " .. " + number(f.stopExposure) + " EV of A"
                           : std::string("error = LDR-FLIP of sRGB-decoded R, G, B (0..1)");
  return text + ", " + number(f.pixelsPerDegree) + " pixels/degree; other channels absolute";
}

std::string describeMetric(const DiffResult& r) {
  switch (r.metric) {
    case DiffMetric::Absolute:
      return "error = |a - b|";
    case DiffMetric::RelativeToScene:
      return "error = |a - b| / " + number(r.scale) + " (" + r.scaleSource + "); coverage channel absolute";
    case DiffMetric::RelativeToValue:
      return "error = |a - b| / max(1, |a|)";
    case DiffMetric::AngleDegrees:
      return "error = angle between the normals of A and B, in degrees";
    case DiffMetric::Flip:
      return flipDescription(r);
    case DiffMetric::Mismatch:
      return "error = 1 where a != b, else 0";
  }
  return "";
}

std::string values(const std::vector<float>& v) {
  if (v.size() == 1) return number(v[0]);
  std::string text = "(";
  for (std::size_t i = 0; i < v.size(); ++i) text += (i ? ", " : "") + number(v[i]);
  return text + ")";
}

std::string thresholdsLine(const DiffThresholds& t) {
  return "warn " + number(t.warn) + " (allow " + number(t.warnPercent) + "%), fail " + number(t.fail) + " (allow " +
         number(t.failPercent) + "%), hardwarn " + number(t.hardWarn) + ", hardfail " + number(t.hardFail);
}

void printFileResult(const DiffResult& r, std::ostream& out) {
  out << "A: " << r.a.string() << "\nB: " << r.b.string() << "\n";
  out << "target " << (r.target.empty() ? "(none)" : r.target) << ": " << metricName(r.metric) << ", "
      << describeMetric(r) << "\n";
  out << "thresholds: " << thresholdsLine(r.thresholds) << "\n";
  if (!r.channels.empty()) {
    char line[512];
    std::snprintf(line, sizeof line, "%-16s %10s %10s %8s %10s %12s  %-24s %-24s %s\n", "channel", "mean", "rms",
                  "PSNR", "max", "at (x, y)", "A there", "B there", "> fail");
    out << line;
    for (const ChannelDiff& c : r.channels) {
      // Built with += : GCC 12 warns falsely (-Wrestrict) on "(" + std::to_string(...).
      std::string at = "(";
      at += std::to_string(c.maxX) + ", " + std::to_string(c.maxY) + ")";
      std::string over = std::to_string(c.failingPixels) + " (" + number(c.failingPercent) + "%)";
      if (c.nonFiniteA + c.nonFiniteB)
        over += ", NaN/Inf " + std::to_string(c.nonFiniteA) + " in A, " + std::to_string(c.nonFiniteB) + " in B";
      std::snprintf(line, sizeof line, "%-16s %10s %10s %8s %10s %12s  %-24s %-24s %s\n", c.name.c_str(),
                    number(c.meanError).c_str(), number(c.rmsError).c_str(), number(c.psnr).c_str(),
                    number(c.maxError).c_str(), at.c_str(), values(c.valuesA).c_str(), values(c.valuesB).c_str(),
                    over.c_str());
      out << line;
    }
  }
  out << upper(statusName(r.status)) << (r.problem.empty() ? "" : ": " + r.problem) << "\n";
}

// One line per target in folder mode: name, status, the key numbers.
std::string targetLine(const DiffResult& r) {
  char head[64];
  std::snprintf(head, sizeof head, "%-9s %-11s", r.target.c_str(), upper(statusName(r.status)).c_str());
  std::string text = head;
  const std::string overFail = number(r.failingPercent) + "% of pixels > fail " + number(r.thresholds.fail) +
                               " (allowed " + number(r.thresholds.failPercent) + "%)";
  // The problem already holds the numbers that decided; a warning adds the
  // share over fail, which it stayed within.
  if (!r.problem.empty())
    return text + r.problem + (r.status == DiffStatus::Warn && r.failingPixels ? "; " + overFail : "");
  if (r.maxError == 0) return text + "identical";
  return text + "max " + number(r.maxError) + unitSuffix(r.metric) + " at (" + std::to_string(r.maxX) + ", " +
         std::to_string(r.maxY) + ") " + r.maxChannel + ", " + overFail;
}

std::string verdictLine(const DirectoryDiff& d) {
  if (d.incompleteSet) return "verdict: INCOMPLETE SET: " + d.problem;
  if (d.targets.empty()) return "verdict: " + upper(statusName(d.status)) + ": " + d.problem;
  int counts[5] = {};
  for (const DiffResult& r : d.targets) ++counts[int(r.status)];
  std::string text = "verdict: " + upper(statusName(d.status)) + " (" + std::to_string(d.targets.size()) + " targets:";
  for (int s = 0; s < 5; ++s)
    text += std::string(s ? "," : "") + " " + std::to_string(counts[s]) + " " + std::string(statusName(DiffStatus(s)));
  return text + ")";
}

// JSON: numbers that are not finite (inf thresholds, PSNR of identical
// images, max error at a NaN) become null, since JSON has no Inf or NaN.
json num(double value) { return std::isfinite(value) ? json(value) : json(nullptr); }

json toJson(const DiffThresholds& t) {
  return {{"fail", num(t.fail)},          {"fail_percent", num(t.failPercent)},
          {"hard_fail", num(t.hardFail)}, {"fail_mean", num(t.failMean)},
          {"warn", num(t.warn)},          {"warn_percent", num(t.warnPercent)},
          {"hard_warn", num(t.hardWarn)}};
}

json toJson(const DiffResult& r) {
  json j;
  j["status"] = std::string(statusName(r.status));
  j["exit_code"] = exitCode(r.status);
  j["problem"] = r.problem;
  j["a"] = r.a.string();
  j["b"] = r.b.string();
  j["target"] = r.target;
  j["metric"] = std::string(metricName(r.metric));
  if (r.metric == DiffMetric::RelativeToScene && !r.channels.empty()) {
    j["scale"] = num(r.scale);
    j["scale_source"] = r.scaleSource;
  }
  if (r.flip)
    j["flip"] = {{"variant", r.flip->hdr ? "hdr" : "ldr"},
                 {"pixels_per_degree", r.flip->pixelsPerDegree},
                 {"start_exposure", num(r.flip->startExposure)},
                 {"stop_exposure", num(r.flip->stopExposure)},
                 {"exposures", r.flip->exposureCount}};
  j["thresholds"] = toJson(r.thresholds);
  j["width"] = r.width;
  j["height"] = r.height;
  j["pixels"] = r.pixelCount;
  if (!r.channels.empty()) {
    j["max_error"] = num(r.maxError);
    j["max_x"] = r.maxX;
    j["max_y"] = r.maxY;
    j["max_channel"] = r.maxChannel;
    j["failing_pixels"] = r.failingPixels;
    j["failing_percent"] = r.failingPercent;
    j["warning_pixels"] = r.warningPixels;
    j["warning_percent"] = r.warningPercent;
    j["nonfinite_values"] = r.nonFiniteValues;
  }
  json channels = json::array();
  for (const ChannelDiff& c : r.channels) {
    json values_a = json::array(), values_b = json::array();
    for (float v : c.valuesA) values_a.push_back(num(v));
    for (float v : c.valuesB) values_b.push_back(num(v));
    channels.push_back({{"name", c.name},
                        {"sources", c.sources},
                        {"mean_error", num(c.meanError)},
                        {"rms_error", num(c.rmsError)},
                        {"psnr", num(c.psnr)},
                        {"max_error", num(c.maxError)},
                        {"max_x", c.maxX},
                        {"max_y", c.maxY},
                        {"value_a", values_a},
                        {"value_b", values_b},
                        {"failing_pixels", c.failingPixels},
                        {"failing_percent", c.failingPercent},
                        {"warning_pixels", c.warningPixels},
                        {"nonfinite_a", c.nonFiniteA},
                        {"nonfinite_b", c.nonFiniteB}});
  }
  j["channels"] = channels;
  return j;
}

// ---- running ------------------------------------------------------------------

// Writes the diff images; returns the paths, or adds a message to `errors`.
std::vector<std::string> writeImages(const DiffResult& r, const fs::path& exrPath, std::vector<std::string>& errors) {
  std::vector<std::string> written;
  if (r.difference.empty()) return written;  // structural or file error: nothing to show
  try {
    for (const fs::path& path : writeDiffImages(r, exrPath)) written.push_back(path.string());
  } catch (const Error& error) {
    errors.push_back(error.what());
  }
  return written;
}

std::string htmlEscaped(std::string_view text) {
  std::string escaped;
  for (char c : text) {
    switch (c) {
      case '<':
        escaped += "&lt;";
        break;
      case '>':
        escaped += "&gt;";
        break;
      case '&':
        escaped += "&amp;";
        break;
      case '\'':
        escaped += "&#39;";
        break;
      default:
        escaped += c;
    }
  }
  return escaped;
}

// A file's bytes as base64 (RFC 4648, section 4), for a data: URI; empty when
// the file cannot be read.
std::string base64File(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(file)), std::istreambuf_iterator<char>());
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t left = bytes.size() - i;
    const std::uint32_t group = std::uint32_t(std::uint8_t(bytes[i])) << 16 |
                                (left > 1 ? std::uint32_t(std::uint8_t(bytes[i + 1])) << 8 : 0) |
                                (left > 2 ? std::uint32_t(std::uint8_t(bytes[i + 2])) : 0);
    text += kAlphabet[group >> 18 & 63];
    text += kAlphabet[group >> 12 & 63];
    text += left > 1 ? kAlphabet[group >> 6 & 63] : '=';
    text += left > 2 ? kAlphabet[group & 63] : '=';
  }
  return text;
}

// report.html beside the diff images, one self-contained page (the images
// are in it as data: URIs, so it can be mailed or attached to a CI run
// alone): the verdict and exit code first, then per compared target its
// status, A, B and the error map (for the flip metric A and B as FLIP saw
// them, then the FLIP map; else the heatmap) with its colour scale
// labelled, and the numbers. `diffs`: each result with its diff.exr.
void writeHtmlReport(const fs::path& html, const std::vector<std::pair<const DiffResult*, fs::path>>& diffs,
                     const std::string& verdict, int exitStatus, std::vector<std::string>& written,
                     std::vector<std::string>& errors) {
  DiffStatus worst = DiffStatus::Pass;
  for (const auto& [r, exr] : diffs) worst = std::max(worst, r->status);
  std::ostringstream page;
  page << "<!DOCTYPE html>\n<html><head><meta charset='utf-8'><title>headlight diff</title><style>"
          "body{font-family:sans-serif;margin:1em} table{border-collapse:collapse;width:100%}"
          "td,th{vertical-align:top;padding:4px;border-bottom:1px solid #ddd;text-align:left}"
          "td.numbers{overflow-wrap:anywhere;min-width:16em;font-size:90%}"
          "figure{margin:0} figcaption{font-size:80%;color:#555;overflow-wrap:anywhere}"
          "img{image-rendering:pixelated;max-width:min(320px,22vw)} img.scale{height:12px;width:min(320px,22vw)}"
          ".ends{display:flex;justify-content:space-between;font-size:80%;width:min(320px,22vw)}"
          ".verdict{font-size:130%;padding:8px;border:2px solid} .pass{color:green} .warn{color:darkorange}"
          ".fail,.structural,.file-error{color:red}</style></head><body>\n<h1>headlight diff</h1>\n"
       << "<p class='verdict " << statusName(worst) << "'>" << htmlEscaped(verdict) << " &mdash; exit " << exitStatus
       << "</p>\n<table>\n<tr><th>target</th><th>A (reference)</th><th>B</th><th>error</th><th>numbers</th></tr>\n";
  std::error_code ignored;
  for (const auto& [r, exr] : diffs) {
    const std::string stem = exr.stem().string();
    auto image = [&](const std::string& name, const char* type = "") {
      const fs::path path = exr.parent_path() / name;
      if (!fs::exists(path, ignored)) return std::string();
      return "<figure><img" + std::string(*type ? " class='" + std::string(type) + "'" : "") + " alt='" +
             htmlEscaped(name) + "' src='data:image/png;base64," + base64File(path) + "'>" +
             (*type ? "" : "<figcaption>" + htmlEscaped(name) + "</figcaption>") + "</figure>";
    };
    std::string scale;
    if (!r->difference.empty()) {
      const HeatmapScale heat = heatmapScale(*r);
      scale = image(stem + "_scale.png", "scale") + "<div class='ends'><span>0</span>" +
              (heat.failAtMiddle ? "<span>fail " + number(r->thresholds.fail) + "</span>" : std::string()) + "<span>" +
              number(heat.fullScale) + (heat.colorMap == "magma" ? " (FLIP)" : " or more") + "</span></div>";
    }
    page << "<tr><td><b>" << htmlEscaped(r->target.empty() ? "(none)" : r->target) << "</b><br><span class='"
         << statusName(r->status) << "'>" << upper(statusName(r->status)) << "</span></td><td>"
         << image(stem + "_a.png") << "</td><td>" << image(stem + "_b.png") << "</td><td>" << image(stem + ".png")
         << scale << "</td><td class='numbers'>A: " << htmlEscaped(r->a.string())
         << "<br>B: " << htmlEscaped(r->b.string()) << "<br>"
         << htmlEscaped(std::string(metricName(r->metric)) + ": " + describeMetric(*r)) << "<br>"
         << htmlEscaped(thresholdsLine(r->thresholds)) << "<br>";
    for (const ChannelDiff& c : r->channels)
      page << htmlEscaped(c.name) << ": mean " << number(c.meanError) << ", max " << number(c.maxError) << " at ("
           << c.maxX << ", " << c.maxY << "), " << number(c.failingPercent) << "% > fail<br>";
    page << htmlEscaped(r->problem) << "</td></tr>\n";
  }
  page << "</table></body></html>\n";
  // A hidden temporary name in the same folder, then a rename, as for the images.
  // Built with += : GCC 12 warns falsely (-Wrestrict) on "." + std::string.
  std::string hiddenName = ".";
  hiddenName += html.filename().string() + ".tmp";
  const fs::path temporary = html.parent_path() / hiddenName;
  std::error_code error;
  {
    std::ofstream file(temporary, std::ios::binary | std::ios::trunc);
    file << page.str();
    if (!file.flush()) error = std::make_error_code(std::errc::io_error);
  }
  if (!error) fs::rename(temporary, html, error);
  if (error) {
    fs::remove(temporary, ignored);
    errors.push_back(html.string() + ": cannot write the report: " + error.message());
    return;
  }
  written.push_back(html.string());
}

// ---- What --out may replace -------------------------------------------------------

// The files one comparison's --out PATH.exr writes (writeDiffImages, and
// the report beside it in file mode).
std::vector<fs::path> comparisonFiles(const fs::path& exr) {
  fs::path png = exr, a = exr, b = exr, scale = exr;
  png.replace_extension(".png");
  a.replace_filename(exr.stem().string() + "_a.png");
  b.replace_filename(exr.stem().string() + "_b.png");
  scale.replace_filename(exr.stem().string() + "_scale.png");
  return {exr, png, a, b, scale};
}

// True when `html` is a report an earlier headlight diff wrote (its title
// says so; writeHtmlReport): the files beside it are that diff's.
bool isDiffReport(const fs::path& html) {
  std::error_code error;
  if (!fs::is_regular_file(html, error)) return false;
  std::ifstream file(html, std::ios::binary);
  std::string head(512, '\0');
  file.read(head.data(), std::streamsize(head.size()));
  head.resize(std::size_t(file.gcount()));
  return head.find("<title>headlight diff</title>") != std::string::npos;
}

// Refuses (a usage error naming the file) to replace a file that exists
// where --out writes, unless an earlier headlight diff's report sits there
// (the files are that diff's) or --force is given.
void checkOutputsOurs(const std::vector<fs::path>& files, const fs::path& report, const DiffCommand& command) {
  if (command.force || isDiffReport(report)) return;
  for (const fs::path& file : files) {
    std::error_code error;
    if (fs::exists(fs::symlink_status(file, error)))
      throw UsageError{"--out " + command.out + ": " + file.string() +
                       " exists and no earlier headlight diff report there lists it; pass --force to replace it, "
                       "or write the difference elsewhere"};
  }
}

int runFiles(const DiffCommand& command, std::ostream& out, std::ostream& err) {
  if (!command.out.empty() && fs::path(command.out).extension() != ".exr")
    throw UsageError{"--out: in file mode, expected a path ending in .exr (the heatmap goes beside it as .png), got '" +
                     command.out + "'"};
  if (!command.out.empty()) {
    // The heatmap and the difference never replace an input.
    const fs::path exr = command.out, png = fs::path(command.out).replace_extension(".png");
    for (const fs::path& written : {exr, png})
      for (const std::string& input : command.paths) {
        std::error_code error;
        if (fs::exists(written, error) && fs::equivalent(written, input, error))
          throw UsageError{"--out " + command.out + ": would overwrite the input " + input + " (with " +
                           written.string() + "); write the difference elsewhere"};
      }
  }
  if (!command.out.empty()) {
    const fs::path html = fs::path(command.out).replace_extension(".html");
    std::vector<fs::path> files = comparisonFiles(command.out);
    files.push_back(html);
    checkOutputsOurs(files, html, command);
  }
  const DiffResult result = diffImages(command.paths[0], command.paths[1], command.options);
  std::vector<std::string> errors, written;
  if (!command.out.empty()) {
    written = writeImages(result, command.out, errors);
    if (!result.difference.empty() && errors.empty())
      writeHtmlReport(
          fs::path(command.out).replace_extension(".html"), {{&result, fs::path(command.out)}},
          "verdict: " + upper(statusName(result.status)) + (result.problem.empty() ? "" : ": " + result.problem),
          errors.empty() ? exitCode(result.status) : std::max(exitCode(result.status), exitCode(DiffStatus::FileError)),
          written, errors);
  }
  int code = exitCode(result.status);
  if (!errors.empty()) code = std::max(code, exitCode(DiffStatus::FileError));
  if (command.json) {
    json j = toJson(result);
    j["exit_code"] = code;
    j["written"] = written;
    j["write_errors"] = errors;
    out << j.dump(2) << "\n";
  } else if (!command.quiet) {
    printFileResult(result, out);
    for (const std::string& path : written) out << "wrote " << path << "\n";
  }
  for (const std::string& error : errors) err << "headlight diff: IoError: " << error << "\n";
  return code;
}

int runFolders(const DiffCommand& command, std::ostream& out, std::ostream& err) {
  if (!command.options.channels.empty() || !command.options.target.empty())
    throw UsageError{
        "--channels and --target apply to one file; in folder mode each target uses its own row "
        "(compare the files one by one instead)"};
  if (!command.out.empty()) {
    // Never into a compared folder: its files would be mixed with the diff's.
    for (const std::string& input : command.paths) {
      std::error_code error;
      if (fs::equivalent(command.out, input, error))
        throw UsageError{"--out " + command.out + ": is the compared folder " + input +
                         "; write the difference elsewhere"};
    }
    const fs::path report = fs::path(command.out) / "report.html";
    std::vector<fs::path> files{report};
    for (const FrameTarget& target : frameTargets())
      for (const fs::path& file : comparisonFiles(fs::path(command.out) / (std::string(target.name) + "_diff.exr")))
        files.push_back(file);
    checkOutputsOurs(files, report, command);
  }
  const DirectoryDiff result = diffDirectories(command.paths[0], command.paths[1], command.options);
  std::vector<std::string> errors, written;
  if (!command.out.empty() && !result.targets.empty()) {
    std::error_code error;
    fs::create_directories(command.out, error);
    if (error)
      errors.push_back(command.out + ": cannot create the output folder: " + error.message());
    else {
      std::vector<std::pair<const DiffResult*, fs::path>> diffs;
      for (const DiffResult& r : result.targets) {
        const fs::path exr = fs::path(command.out) / (r.target + "_diff.exr");
        for (std::string& path : writeImages(r, exr, errors)) written.push_back(std::move(path));
        diffs.emplace_back(&r, exr);
      }
      const int code = exitCode(result.status);
      writeHtmlReport(fs::path(command.out) / "report.html", diffs, verdictLine(result),
                      errors.empty() ? code : std::max(code, exitCode(DiffStatus::FileError)), written, errors);
    }
  }
  int code = result.incompleteSet ? kDiffExitIncompleteSet : exitCode(result.status);
  if (!errors.empty() && !result.incompleteSet) code = std::max(code, exitCode(DiffStatus::FileError));
  if (command.json) {
    json targets = json::array();
    for (const DiffResult& r : result.targets) targets.push_back(toJson(r));
    const json j = {
        {"status", result.incompleteSet ? std::string("incomplete-set") : std::string(statusName(result.status))},
        {"exit_code", code},
        {"problem", result.problem},
        {"a", result.a.string()},
        {"b", result.b.string()},
        {"targets", targets},
        {"written", written},
        {"write_errors", errors}};
    out << j.dump(2) << "\n";
  } else if (!command.quiet) {
    out << "A: " << result.a.string() << "\nB: " << result.b.string() << "\n";
    for (const DiffResult& r : result.targets) out << targetLine(r) << "\n";
    for (const std::string& path : written) out << "wrote " << path << "\n";
    out << verdictLine(result) << "\n";
  }
  for (const std::string& error : errors) err << "headlight diff: IoError: " << error << "\n";
  return code;
}

}  // namespace

std::string diffHelp() {
  std::ostringstream out;
  out << "usage: headlight diff A B [options]\n\n"
         "Compares image B against reference A (idiff's rules), or, when A and B are folders, every\n"
         "headlight target (position, normal, albedo, material, depth, emissive, ssgi, lit .exr) in them.\n"
         "A pixel fails when its error > fail; the result is FAIL when more than failpercent % of the\n"
         "pixels fail or any error > hardfail, WARN likewise with warn, warnpercent and hardwarn, else\n"
         "PASS. Any NaN or Inf in A or B is FAIL. Flags override the target's defaults (table below).\n\n"
         "Exit codes (folder mode: the worst target):\n"
         "  0 pass   1 warn   2 fail   3 structural mismatch (size, channel names, target in one folder only)\n"
         "  4 file error (missing or unreadable file or folder, diff image not written)   5 usage error\n"
         "  6 incomplete output set: a folder's frame.json says a render never finished writing it, or a\n"
         "    file differs from the one the set recorded (nothing is compared)\n\n"
         "options:\n";
  out << optionHelp<DiffCommand>(diffOptions(), DiffCommand{});
  out << "\ndefault thresholds by target (A's file stem; units are the metric's):\n";
  char line[256];
  std::snprintf(line, sizeof line, "  %-9s %-18s %8s %8s %9s %9s %9s\n", "target", "metric", "warn", "fail", "failpct",
                "failmean", "hardfail");
  out << line;
  auto printRow = [&](const FrameTarget& row) {
    const DiffThresholds& t = row.thresholds;
    std::snprintf(line, sizeof line, "  %-9s %-18s %8s %8s %9s %9s %9s\n",
                  row.name.empty() ? "(other)" : std::string(row.name).c_str(),
                  std::string(metricName(row.metric)).c_str(), number(t.warn).c_str(), number(t.fail).c_str(),
                  number(t.failPercent).c_str(), number(t.failMean).c_str(), number(t.hardFail).c_str());
    out << line;
  };
  for (const FrameTarget& row : frameTargets()) printRow(row);
  printRow(previewTargetRow());
  printRow(unknownTargetRow());
  out << "  (warnpercent 0 and hardwarn inf everywhere; reasons in docs/DIFF.md)\n"
         "relative-to-scene: error / A's headlight:far (coverage channel A absolute);\n"
         "relative-to-value: error / max(1, |a|); angle-degrees: angle between the normal vectors;\n"
         "flip: the perceived difference of R, G, B, 0..1 (HDR-FLIP of float images, exposures from A;\n"
         "LDR-FLIP of sRGB 8/16-bit images), other channels absolute; failmean bounds the mean FLIP.\n"
         "Background pixels are compared like any other (their values are deterministic).\n";
  return out.str();
}

int runDiffCommand(const std::vector<std::string>& args) { return runDiffCommand(args, std::cout, std::cerr); }

int runDiffCommand(const std::vector<std::string>& args, std::ostream& out, std::ostream& err) {
  try {
    const DiffCommand command = parseDiffArgs(args);
    if (command.help) {
      out << diffHelp();
      return exitCode(DiffStatus::Pass);
    }
    std::error_code error;
    const bool folderA = fs::is_directory(command.paths[0], error), folderB = fs::is_directory(command.paths[1], error);
    if (folderA || folderB) {
      // A folder against a file that exists is a mistake in the command; a
      // missing path is left to diffDirectories (a file error).
      for (const std::string& path : command.paths)
        if (fs::exists(path, error) && !fs::is_directory(path, error))
          throw UsageError{"cannot compare a folder with a file ('" + path + "'); give two files or two folders"};
      return runFolders(command, out, err);
    }
    return runFiles(command, out, err);
  } catch (const UsageError& error) {
    err << "headlight diff: " << error.message << " (see headlight diff --help)\n";
    return kDiffExitUsage;
  } catch (const std::exception& error) {
    // Not expected (file problems are statuses); say so rather than crash.
    err << "headlight diff: error: " << error.what() << "\n";
    return exitCode(DiffStatus::FileError);
  }
}

}  // namespace headlight::cli

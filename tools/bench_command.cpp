#include "bench_command.hpp"

#include <unistd.h>

#include <chrono>
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <sstream>

#include "headlight/bench.hpp"
#include "headlight/error.hpp"
#include "headlight/reference.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"

namespace headlight::detail {
std::string_view benchChartScript();  // tools/bench_chart.py, embedded at build time
}

namespace headlight::cli {
namespace {

std::vector<std::string> splitList(const std::string& text) {
  std::vector<std::string> items;
  std::stringstream stream(text);
  for (std::string item; std::getline(stream, item, ',');)
    if (!item.empty()) items.push_back(item);
  if (items.empty()) throw SettingsError("expected a comma-separated list, got '" + text + "'");
  return items;
}

template <class Number>
Number parseNumber(const std::string& flag, const std::string& text, Number low, Number high) {
  Number value{};
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < low || value > high) {
    std::ostringstream message;
    message << "--" << flag << ": expected a number in " << low << ".." << high << ", got '" << text << "'";
    throw SettingsError(message.str());
  }
  return value;
}

std::pair<int, int> parseResolution(const std::string& text) {
  const auto x = text.find('x');
  if (x == std::string::npos) throw SettingsError("--resolutions: expected WIDTHxHEIGHT, got '" + text + "'");
  return {parseNumber<int>("resolutions", text.substr(0, x), 1, 16384),
          parseNumber<int>("resolutions", text.substr(x + 1), 1, 16384)};
}

// One configuration of the sweep: a label and the settings it renders with.
struct Config {
  RenderSettings settings;
  float radiusScale = 1;
  bool seedDefault = false;
};

std::vector<Config> sweep(const BenchCommand& command, int width, int height, float autoRadius) {
  std::vector<Config> configs;
  for (SsgiMethod method : command.methods)
    for (int samples : command.samples)
      for (float scale : command.radiusScales)
        for (int downsample : command.downsamples)
        for (bool blur : command.blurs) {
          // Below full resolution the blur is the upsample: it cannot be off.
          if (downsample > 1 && !blur) continue;
          Config config;
          config.settings.ssgi.downsample = downsample;
          config.settings.width = width;
          config.settings.height = height;
          config.settings.ssgi.method = method;
          config.settings.ssgi.sampleCount = samples;
          config.settings.ssgi.radius = autoRadius * scale;
          config.settings.ssgi.blur = blur;
          config.radiusScale = scale;
          configs.push_back(config);
        }
  // The seed spec's own numbers, whatever the scene's size: the point to beat.
  Config seed;
  seed.settings.width = width;
  seed.settings.height = height;
  applyPreset(seed.settings, "seed");
  seed.settings.ssgi.blur = false;
  seed.radiusScale = seed.settings.ssgi.radius / autoRadius;
  seed.seedDefault = true;
  configs.push_back(seed);
  return configs;
}

class Progress {
 public:
  Progress(std::size_t total, bool enabled) : total_(total), enabled_(enabled && isatty(2)) {}
  void update(std::size_t done, const std::string& what) {
    if (!enabled_) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double eta = done > 0 ? elapsed / double(done) * double(total_ - done) : 0.0;
    const int width = 30, filled = int(double(width) * double(done) / double(std::max<std::size_t>(total_, 1)));
    std::fprintf(stderr, "\r[%s%s] %zu/%zu ETA %3d:%02d  %-48.48s", std::string(std::size_t(filled), '#').c_str(),
                 std::string(std::size_t(width - filled), ' ').c_str(), done, total_, int(eta) / 60, int(eta) % 60,
                 what.c_str());
    std::fflush(stderr);
  }
  void finish() {
    if (enabled_) std::fprintf(stderr, "\n");
  }

 private:
  std::size_t total_;
  bool enabled_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
};

// Frame time without readback (a cost of getting images to the CPU, not of
// rendering) and without shadows (made once per scene, then cached).
double frameMilliseconds(const Frame& frame) {
  double total = 0;
  for (const PassTime& time : frame.timings)
    if (time.pass != "readback" && time.pass != "shadows") total += time.milliseconds;
  return total;
}

double ssgiMilliseconds(const Frame& frame) {
  double total = 0;
  for (const PassTime& time : frame.timings)
    if (time.pass == "ssgi" || time.pass == "ssgi-blur") total += time.milliseconds;
  return total;
}

BenchRow measure(Renderer& renderer, const Config& config, const BenchCommand& command,
                 const ReferenceImages& reference) {
  for (int i = 0; i < command.warmup; ++i) renderer.render(config.settings);
  std::vector<double> frameTimes, ssgiTimes;
  Frame frame;
  for (int i = 0; i < command.repetitions; ++i) {
    frame = renderer.render(config.settings);
    frameTimes.push_back(frameMilliseconds(frame));
    ssgiTimes.push_back(ssgiMilliseconds(frame));
  }
  BenchRow row;
  row.scene = frame.sceneSource;
  row.width = frame.settings.width;
  row.height = frame.settings.height;
  row.method = std::string(ssgiMethodName(frame.settings.ssgi.method));
  row.samples = frame.settings.ssgi.sampleCount;
  row.radius = frame.settings.ssgi.radius;
  row.radiusScale = config.radiusScale;
  row.blur = frame.settings.ssgi.blur;
  row.downsample = frame.settings.ssgi.downsample;
  row.seedDefault = config.seedDefault;
  row.repetitions = command.repetitions;
  row.frameMs = summarize(frameTimes);
  row.ssgiMs = summarize(ssgiTimes);
  row.ao = maskedError(frame.ssgi, 0, reference.ao, 0, frame.position);
  row.indirect = maskedColorError(frame.ssgi, 1, reference.indirect, 0, frame.position);
  row.lit = maskedColorError(frame.lit, 0, reference.lit, 0, frame.position);
  row.litSsim = maskedSsim(frame.lit, reference.lit, frame.position);
  row.referenceSamples = reference.samplesPerPixel;
  row.referenceAoStandardError = reference.aoMeanStandardError;
  row.renderer = frame.glRenderer;
  row.backend = frame.backend;
  row.machine = machineDescription();
  return row;
}

void markParetoFronts(std::vector<BenchRow>& rows) {
  std::map<std::tuple<std::string, int, int>, std::vector<std::size_t>> groups;
  for (std::size_t i = 0; i < rows.size(); ++i) groups[{rows[i].scene, rows[i].width, rows[i].height}].push_back(i);
  for (const auto& [key, members] : groups) {
    std::vector<std::pair<double, double>> points;
    for (std::size_t i : members) points.emplace_back(rows[i].frameMs.median, rows[i].ao.rmse);
    const std::vector<bool> front = paretoFront(points);
    for (std::size_t k = 0; k < members.size(); ++k) rows[members[k]].paretoAo = front[k];
  }
}

// Runs the embedded chart script with Debian's Python (matplotlib lives there).
bool drawChart(const std::filesystem::path& csv, const std::filesystem::path& outDir) {
  const std::string python = std::filesystem::exists("/usr/bin/python3") ? "/usr/bin/python3" : "python3";
  const std::string command = python + " - '" + csv.string() + "' '" + outDir.string() + "'";
  FILE* pipe = popen(command.c_str(), "w");
  if (pipe == nullptr) return false;
  const std::string_view script = detail::benchChartScript();
  std::fwrite(script.data(), 1, script.size(), pipe);
  return pclose(pipe) == 0;
}

std::string joinArgs(const std::vector<std::string>& args) {
  std::string text = "headlight bench";
  for (const auto& arg : args) text += " " + arg;
  return text;
}

}  // namespace

BenchCommand parseBenchArgs(const std::vector<std::string>& args) {
  BenchCommand command;
  for (std::size_t i = 0; i < args.size(); ++i) {
    const std::string& arg = args[i];
    auto value = [&]() -> const std::string& {
      if (i + 1 >= args.size()) throw SettingsError(arg + " needs a value");
      return args[++i];
    };
    if (arg == "--help") command.help = true;
    else if (arg == "--out") command.outDir = value();
    else if (arg == "--resolutions") {
      command.resolutions.clear();
      for (const auto& item : splitList(value())) command.resolutions.push_back(parseResolution(item));
    } else if (arg == "--methods") {
      command.methods.clear();
      for (const auto& item : splitList(value())) command.methods.push_back(parseSsgiMethod(item));
    } else if (arg == "--samples") {
      command.samples.clear();
      for (const auto& item : splitList(value())) command.samples.push_back(parseNumber<int>("samples", item, 1, 64));
    } else if (arg == "--radius-scales") {
      command.radiusScales.clear();
      for (const auto& item : splitList(value()))
        command.radiusScales.push_back(parseNumber<float>("radius-scales", item, 1e-3f, 1e3f));
    } else if (arg == "--ssgi-resolutions") {
      command.downsamples.clear();
      for (const auto& item : splitList(value())) {
        if (item != "full" && item != "half" && item != "quarter")
          throw SettingsError("--ssgi-resolutions: expected full, half and/or quarter, got '" + item + "'");
        command.downsamples.push_back(item == "full" ? 1 : item == "half" ? 2 : 4);
      }
    } else if (arg == "--blur") {
      command.blurs.clear();
      for (const auto& item : splitList(value())) {
        if (item != "on" && item != "off") throw SettingsError("--blur: expected on and/or off, got '" + item + "'");
        command.blurs.push_back(item == "on");
      }
    } else if (arg == "--repetitions") command.repetitions = parseNumber<int>("repetitions", value(), 1, 1000);
    else if (arg == "--warmup") command.warmup = parseNumber<int>("warmup", value(), 0, 1000);
    else if (arg == "--reference-samples")
      command.referenceSamples = parseNumber<int>("reference-samples", value(), 1, 1 << 20);
    else if (arg == "--backend") command.context.backend = parseBackend(value());
    else if (arg == "--no-chart") command.chart = false;
    else if (arg == "--quiet") command.quiet = true;
    else if (!arg.empty() && arg[0] == '-') throw SettingsError("unknown option '" + arg + "' (see headlight bench --help)");
    else command.scenes.push_back(arg);
  }
  if (command.scenes.empty())
    for (const auto& name : builtinSceneNames()) command.scenes.push_back("builtin:" + name);
  return command;
}

std::string benchHelp() {
  return "usage: headlight bench [SCENE...] [options]\n\n"
         "Times every SSGI configuration (median and spread of --repetitions frames after --warmup,\n"
         "each pass bounded by glFinish) and compares its output with the Embree reference over\n"
         "geometry pixels. Writes bench.csv, bench.json, bench.png and bench.svg into --out.\n"
         "Scenes default to the built-ins.\n\noptions:\n"
         "  --out DIR                 output folder (default bench)\n"
         "  --resolutions WxH,...     image sizes (default 128x96)\n"
         "  --methods LIST            hemisphere,radiance (default both)\n"
         "  --samples LIST            SSGI kernel samples (default 4,8,16,32,64)\n"
         "  --radius-scales LIST      radius as a multiple of the scene's auto radius (default 0.5,1,2)\n"
         "  --blur LIST               on,off (default both; below full SSGI resolution always on)\n"
         "  --ssgi-resolutions LIST   full,half,quarter: SSGI resolution (default full,half)\n"
         "  --repetitions N           timed frames per configuration (default 5)\n"
         "  --warmup N                untimed frames first (default 2)\n"
         "  --reference-samples N     reference rays per pixel (default: the reference's own)\n"
         "  --backend auto|egl|osmesa headless GL backend\n"
         "  --no-chart                skip bench.png/svg (needs /usr/bin/python3 with matplotlib)\n"
         "  --quiet                   no progress bar or table\n"
         "The seed spec's settings (hemisphere, 64 samples, radius 0.5, bias 0.025, no blur) are always\n"
         "measured too and marked in the chart.\n\n"
         "Exit codes: 0 ok, 1 runtime error, 2 usage error.\n";
}

int runBenchCommand(const std::vector<std::string>& args) {
  const BenchCommand command = parseBenchArgs(args);
  if (command.help) {
    std::cout << benchHelp();
    return 0;
  }
  if (!referenceAvailable()) throw Error("headlight bench needs the reference: this build has no Embree");
  Context context(command.context);
  Renderer renderer(context);
  std::vector<BenchRow> rows;
  const std::size_t configsPerGroup = sweep(command, 1, 1, 1.0f).size();
  Progress progress(command.scenes.size() * command.resolutions.size() * configsPerGroup, !command.quiet);
  std::size_t done = 0;
  for (const std::string& sceneName : command.scenes) {
    renderer.setScene(loadScene(sceneName));
    for (const auto& [width, height] : command.resolutions) {
      RenderSettings base;
      base.width = width;
      base.height = height;
      const float autoRadius = renderer.resolve(base).ssgi.radius;
      const Frame gbufferFrame = renderer.render(base);
      std::map<float, ReferenceImages> references;  // by radius
      for (const Config& config : sweep(command, width, height, autoRadius)) {
        const float radius = config.settings.ssgi.radius;
        if (!references.count(radius)) {
          progress.update(done, sceneName + " reference R=" + std::to_string(radius));
          ReferenceSettings settings;
          if (command.referenceSamples > 0) settings.samplesPerPixel = command.referenceSamples;
          settings.radius = radius;
          references.emplace(radius, traceReference(renderer.scene(), gbufferFrame, settings));
        }
        progress.update(done, sceneName + " " + std::string(ssgiMethodName(config.settings.ssgi.method)) + " s" +
                                  std::to_string(config.settings.ssgi.sampleCount));
        rows.push_back(measure(renderer, config, command, references.at(radius)));
        ++done;
      }
    }
  }
  progress.finish();
  markParetoFronts(rows);

  const std::filesystem::path out(command.outDir);
  std::filesystem::create_directories(out);
  writeBenchCsv(rows, out / "bench.csv");
  writeBenchJson(rows, joinArgs(args), out / "bench.json");
  if (!command.quiet) std::cout << (out / "bench.csv").string() << "\n" << (out / "bench.json").string() << "\n";
  if (command.chart && !drawChart(out / "bench.csv", out))
    throw IoError((out / "bench.png").string() + ": the chart script failed (is python3-matplotlib installed?)");
  return 0;
}

}  // namespace headlight::cli

#include "bench_command.hpp"

#include "batch.hpp"
#include "batch_plan.hpp"
#include "io/folder_lock.hpp"

#include <unistd.h>

#include <charconv>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <limits>
#include <map>
#include <optional>
#include <sstream>

#include "headlight/error.hpp"
#include "headlight/reference.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/targets.hpp"
#include "progress.hpp"
#include "tooling/bench.hpp"

namespace headlight::detail {
std::string_view benchChartScript();  // tools/bench_chart.py, embedded at build time
}

namespace headlight::cli {
namespace {

std::pair<int, int> parseResolution(const std::string& text) {
  const auto x = text.find('x');
  if (x == std::string::npos) throw SettingsError("--resolutions: expected WIDTHxHEIGHT, got '" + text + "'");
  const Option<RenderSettings>& width = findOption(settingOptions(), "width");
  const Option<RenderSettings>& height = findOption(settingOptions(), "height");
  return {int(std::get<std::int64_t>(parseOptionValue(width.spec, text.substr(0, x)))),
          int(std::get<std::int64_t>(parseOptionValue(height.spec, text.substr(x + 1))))};
}

const std::string kBenchFiles[] = {"bench.csv", "bench.json", "bench.png", "bench.svg"};

// An earlier bench's file: its CSV starts with the bench's header, its JSON
// with the bench's command; the chart beside either is that bench's too.
bool isBenchOutput(const std::filesystem::path& file) {
  // The first bytes of `path`, when it is a regular file.
  const auto head = [](const std::filesystem::path& path, std::size_t bytes) {
    std::error_code error;
    if (!std::filesystem::is_regular_file(path, error)) return std::string();
    std::ifstream in(path, std::ios::binary);
    std::string text(bytes, '\0');
    in.read(text.data(), std::streamsize(text.size()));
    text.resize(std::size_t(in.gcount()));
    return text;
  };
  const std::filesystem::path folder = file.parent_path();
  const bool csv = head(folder / "bench.csv", 64).rfind(kCsvHeaderStart, 0) == 0;
  const bool json = head(folder / "bench.json", 64).find("\"command\": \"headlight bench") != std::string::npos;
  if (file.filename() == "bench.csv") return csv;
  if (file.filename() == "bench.json") return json;
  return csv || json;
}

std::vector<Option<BenchCommand>> benchOptions() {
  using T = OptionType;
  using C = BenchCommand;
  std::vector<Option<C>> rows = commonCommandOptions<C>(kVerboseHelpBench);
  rows.push_back(actionOption<C>({.name = "resolutions",
                                  .type = T::Text,
                                  .help = "image sizes, comma-separated (default 128x96)",
                                  .valueName = "WxH,..."},
                                 [](C& c, const OptionValue& v) {
                                   c.resolutions.clear();
                                   // An empty list is refused before this (setFromCommandLine).
                                   for (const auto& item : detail::splitList("resolutions", std::get<std::string>(v)))
                                     c.resolutions.push_back(parseResolution(item));
                                 }));
  for (auto& row : measurementOptions<C>("sweep a render setting over values; repeat for a cartesian product (default: "
                                         "hemisphere and radiance over ssgi-samples, ssgi-radius-fraction, ssgi-blur, "
                                         "ssgi-resolution; bitmask over ssgi-slices, ssgi-steps, ssgi-radius-fraction, "
                                         "ssgi-resolution)"))
    rows.push_back(std::move(row));
  rows.push_back(bindOption<C>(
      {.name = "chart", .type = T::Bool, .help = "draw bench.png/svg (needs /usr/bin/python3 with matplotlib)"},
      [](auto& c) -> auto& { return c.chart; }));
  rows.push_back(bindOption<C>(
      {.name = "force",
       .type = T::Switch,
       .help = "replace bench.csv, bench.json, bench.png or bench.svg files in --out that no earlier headlight "
               "bench wrote"},
      [](auto& c) -> auto& { return c.force; }));
  rows.push_back(bindOption<C>(
      {.name = "reference",
       .type = T::Bool,
       .help = "trace the Embree reference and measure each configuration's errors against it (--no-reference: "
               "time only, errors nan, no chart; a 4K frame need not wait on a 4K reference)"},
      [](auto& c) -> auto& { return c.traceReference; }));
  for (auto& row : liftOptions(referenceOptions(), &C::reference)) rows.push_back(std::move(row));
  for (auto& row : sceneInputOptions<C>()) rows.push_back(std::move(row));
  rows.push_back(settingsFileOption<C>(&C::base));
  for (auto& row : liftOptions(settingOptions(), &C::base)) rows.push_back(std::move(row));
  return rows;
}

std::string configLabel(const std::vector<std::pair<const Option<RenderSettings>*, OptionValue>>& choice) {
  std::string label;
  for (const auto& [row, value] : choice)
    (label += label.empty() ? "" : " ") += std::string(row->spec.name) + "=" + formatOptionValue(row->spec, value);
  return label;
}

}  // namespace

SettingSweep parseSweep(const std::string& text) {
  const auto equals = text.find('=');
  if (equals == std::string::npos || equals == 0)
    throw SettingsError("--sweep: expected NAME=V1,V2,... (NAME a render setting), got '" + text + "'");
  SettingSweep sweep{text.substr(0, equals), {}};
  const Option<RenderSettings>& row = findOption(settingOptions(), sweep.name);
  for (const std::string& value : detail::splitList("sweep " + sweep.name, text.substr(equals + 1)))
    sweep.values.push_back(parseOptionValue(row.spec, value));
  if (sweep.values.empty()) throw SettingsError("--sweep " + sweep.name + ": no values");
  return sweep;
}

std::vector<std::vector<SettingSweep>> defaultBenchSweeps() {
  return {{parseSweep("ssgi-method=hemisphere,radiance"), parseSweep("ssgi-samples=4,8,16,32,64"),
           parseSweep("ssgi-radius-fraction=0.075,0.15,0.3"), parseSweep("ssgi-blur=on,off"),
           parseSweep("ssgi-resolution=full,half")},
          // The default method (issue 30: the default sweep never measured it).
          {parseSweep("ssgi-method=bitmask"), parseSweep("ssgi-slices=1,2,4"), parseSweep("ssgi-steps=8,16"),
           parseSweep("ssgi-radius-fraction=0.075,0.15,0.3"), parseSweep("ssgi-resolution=full,half")}};
}

std::vector<BenchConfig> sweepConfigs(const RenderSettings& base, const std::vector<SettingSweep>& sweeps, int width,
                                      int height) {
  // The product bounded before the odometer runs: five lists of 100 values
  // would enumerate 1e10 configurations (issue 15).
  constexpr double kMaxConfigs = 100'000;  // a bench measures about one a second: a day
  double product = 1;
  std::string sizes;
  for (const SettingSweep& sweep : sweeps) {
    product *= double(sweep.values.size());
    (sizes += sizes.empty() ? "" : " x ") += std::to_string(sweep.values.size());
  }
  if (product > kMaxConfigs) {
    char count[32];
    std::snprintf(count, sizeof count, "%.3g", product);
    throw SettingsError("--sweep: " + sizes + " values make " + count + " configurations, more than the " +
                        std::to_string(std::int64_t(kMaxConfigs)) + " one run may measure; shorten the lists");
  }
  std::vector<BenchConfig> configs;
  std::vector<std::size_t> index(sweeps.size(), 0);  // an odometer over the sweeps' values
  for (bool more = true; more;) {
    BenchConfig config{base, "", false};
    config.settings.width = width;
    config.settings.height = height;
    std::vector<std::pair<const Option<RenderSettings>*, OptionValue>> choice;
    for (std::size_t s = 0; s < sweeps.size(); ++s) {
      const Option<RenderSettings>& row = findOption(settingOptions(), sweeps[s].name);
      row.set(config.settings, sweeps[s].values[index[s]]);
      choice.emplace_back(&row, sweeps[s].values[index[s]]);
    }
    config.label = configLabel(choice);
    try {
      config.settings.validate();
      configs.push_back(config);
    } catch (const SettingsError&) {
      // A combination the renderer refuses (half resolution without blur).
    }
    more = false;
    for (std::size_t s = sweeps.size(); s-- > 0;) {
      if (++index[s] < sweeps[s].values.size()) {
        more = true;
        break;
      }
      index[s] = 0;
    }
  }
  return configs;
}

std::vector<BenchConfig> benchConfigs(const BenchCommand& command, int width, int height) {
  std::vector<BenchConfig> configs;
  if (!command.sweeps.empty())
    configs = sweepConfigs(command.base, command.sweeps, width, height);
  else
    for (const std::vector<SettingSweep>& product : defaultBenchSweeps())
      for (BenchConfig& config : sweepConfigs(command.base, product, width, height))
        configs.push_back(std::move(config));
  // The seed spec's own numbers, whatever the scene's size: the point to beat.
  BenchConfig seed{RenderSettings{}, "preset=seed ssgi-blur=off", true};
  seed.settings.width = width;
  seed.settings.height = height;
  applyPreset(seed.settings, "seed");
  seed.settings.ssgi.blur = false;
  seed.settings.antialiasSamples = 1;  // the seed had none
  configs.push_back(seed);
  return configs;
}

namespace {

// A pass's wall time, or with `gpu` its GPU time (nan where the driver gave
// none: the sum is then unknown too, never an undercount).
double passMilliseconds(const PassTime& time, bool gpu) {
  if (!gpu) return time.milliseconds;
  return time.gpuMilliseconds >= 0 ? time.gpuMilliseconds : std::numeric_limits<double>::quiet_NaN();
}

// Frame time without readback (a cost of getting images to the CPU, not of
// rendering) and without shadows (made once per scene, then cached).
double frameMilliseconds(const Frame& frame, bool gpu) {
  double total = 0;
  for (const PassTime& time : frame.timings)
    if (time.pass != "readback" && time.pass != "shadows") total += passMilliseconds(time, gpu);
  return total;
}

double ssgiMilliseconds(const Frame& frame, bool gpu) {
  double total = 0;
  for (const PassTime& time : frame.timings)
    if (time.pass == "ssgi" || time.pass == "ssgi-blur") total += passMilliseconds(time, gpu);
  return total;
}

// Each timed frame's wall and GPU times.
struct FrameTimes {
  std::vector<double> frame, ssgi, frameGpu, ssgiGpu;
  std::map<std::string, std::vector<double>> passWall, passGpu;  // by PassTime::pass
};

// Times one configuration: `warmup` frames, then `repetitions` timed ones.
// These read back the lit image alone (the passes are the same: every other
// target is an input of lit's). Reading every target back took an H200 ~400
// ms a 1920x1080 frame against ~12 ms of passes, and the GPU, idle that long,
// fell from 1980 to 345 MHz within 4 s: the frames timed after were ~5x
// slower than the same passes on a busy GPU (docs/BENCHMARKS.md, "Session
// 14"). The frame the errors are measured on, untimed, has every target.
Frame timeFrames(Renderer& renderer, const BenchConfig& config, const MeasureOptions& options, FrameTimes& times) {
  const std::string timedTargets[] = {"lit"};
  for (int i = 0; i < options.warmup; ++i) renderer.render(config.settings, nullptr, timedTargets);
  Frame frame;
  for (int i = 0; i < options.repetitions; ++i) {
    frame = renderer.render(config.settings, nullptr, timedTargets);
    times.frame.push_back(frameMilliseconds(frame, false));
    times.ssgi.push_back(ssgiMilliseconds(frame, false));
    times.frameGpu.push_back(frameMilliseconds(frame, true));
    times.ssgiGpu.push_back(ssgiMilliseconds(frame, true));
    for (const PassTime& time : frame.timings) {
      times.passWall[time.pass].push_back(time.milliseconds);
      if (time.gpuMilliseconds >= 0) times.passGpu[time.pass].push_back(time.gpuMilliseconds);
    }
  }
  return options.traceReference ? renderer.render(config.settings) : frame;
}

std::string formsText(const Frame& frame) {
  std::string text;
  for (const PassTime& time : frame.timings)
    if (!time.form.empty()) (text += text.empty() ? "" : " ") += time.pass + "=" + time.form;
  return text;
}

// A row without errors: what --no-reference measures.
BenchRow timedRow(const Frame& frame, const BenchConfig& config, const MeasureOptions& options,
                  const FrameTimes& times) {
  BenchRow row;
  row.scene = frame.sceneSource;
  row.width = frame.settings.width;
  row.height = frame.settings.height;
  row.label = config.label;
  row.settings = settingsAsText(frame.settings);
  row.seedDefault = config.seedDefault;
  row.repetitions = options.repetitions;
  row.frameMs = summarize(times.frame);
  row.ssgiMs = summarize(times.ssgi);
  row.frameGpuMs = summarize(times.frameGpu);
  row.ssgiGpuMs = summarize(times.ssgiGpu);
  row.forms = formsText(frame);
  for (const auto& [pass, values] : times.passWall) row.passMs[pass] = summarize(values);
  for (const auto& [pass, values] : times.passGpu) row.passGpuMs[pass] = summarize(values);
  row.renderer = frame.glRenderer;
  row.backend = frame.backend;
  row.machine = machineDescription();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  row.ao.rmse = row.ao.meanAbsolute = row.sky.rmse = row.sky.meanAbsolute = nan;
  row.indirect.rmse = row.indirect.relativeRmse = row.lit.relativeRmse = row.litSsim = row.litFlip = nan;
  row.referenceTraced = false;
  return row;
}

// What the composite takes for SSGI when it is off: every pixel open (AO,
// sky and specular visibility 1) and no indirect light, in ssgi.exr's layout.
ImageF openSsgi(const Frame& frame) {
  ImageF image;
  image.width = frame.lit.width;
  image.height = frame.lit.height;
  for (std::string_view channel : findFrameTarget("ssgi")->channels) image.channels.emplace_back(channel);
  image.pixels.resize(std::size_t(image.width) * std::size_t(image.height) * image.channels.size());
  for (std::size_t i = 0; i < image.pixels.size(); ++i)
    image.pixels[i] = image.channels[i % image.channels.size()].ends_with(".Y") ? 1.0f : 0.0f;
  return image;
}

BenchRow measure(const Frame& frame, const BenchConfig& config, const MeasureOptions& options, const FrameTimes& times,
                 const ReferenceImages& reference) {
  BenchRow row = timedRow(frame, config, options, times);
  row.referenceTraced = true;
  // --sweep ssgi=on,off: no SSGI is measured as the image the composite used.
  const ImageF ssgi = frame.ssgi.empty() ? openSsgi(frame) : frame.ssgi;
  row.ao = maskedError(ssgi, 0, reference.ao, 0, frame.position);
  row.sky = maskedError(ssgi, 4, reference.ao, 1, frame.position);  // sky.Y in both
  row.indirect = maskedColorError(ssgi, 1, reference.indirect, 0, frame.position);
  row.lit = maskedColorError(frame.lit, 0, reference.lit, 0, frame.position);
  row.litSsim = maskedSsim(frame.lit, reference.lit, frame.position);
  row.litFlip = hdrFlipMean(frame.lit, reference.lit);
  row.referenceSamples = reference.samplesPerPixel;
  row.referenceAoStandardError = reference.aoMeanStandardError;
  row.referenceScreenBound = reference.screenBound;
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

std::vector<BenchRow> measureConfigs(Renderer& renderer, const std::vector<BenchConfig>& configs,
                                     const MeasureOptions& options, Progress& progress, std::size_t& done) {
  const std::string sceneName = renderer.scene().source;
  std::vector<BenchRow> rows;
  // The reference depends on the radius the frame used (and the G-buffer,
  // the same for every configuration of one camera and size).
  std::map<float, ReferenceImages> references;
  for (const BenchConfig& config : configs) {
    progress.update(done, sceneName + " " + config.label);
    FrameTimes times;
    const Frame frame = timeFrames(renderer, config, options, times);
    if (!options.traceReference) {
      rows.push_back(timedRow(frame, config, options, times));
      ++done;
      continue;
    }
    const float radius = *frame.settings.ssgi.radius;
    if (!references.count(radius)) {
      progress.update(done, sceneName + " reference R=" + std::to_string(radius));
      ReferenceSettings settings = options.reference;
      settings.radius = radius;
      references.emplace(radius, traceReference(renderer.scene(), frame, settings));
    }
    rows.push_back(measure(frame, config, options, times, references.at(radius)));
    ++done;
  }
  return rows;
}

BenchCommand parseBenchArgs(const std::vector<std::string>& args) {
  BenchCommand command;
  const auto options = benchOptions();
  command.scenes = parseCommandLine<BenchCommand>(args, options, command, "bench");
  if (command.scenes.empty())
    for (const auto& name : builtinSceneNames()) command.scenes.push_back("builtin:" + name);
  return command;
}

std::string benchHelp() {
  const BenchCommand defaults;
  std::string help =
      "usage: headlight bench [SCENE...] [options]\n\n"
      "Times every SSGI configuration (median and spread of --repetitions frames after --warmup,\n"
      "each pass bounded by glFinish) and compares its output with the Embree reference over\n"
      "geometry pixels. Writes bench.csv, bench.json, bench.png and bench.svg into --out.\n"
      "Scenes default to the built-ins. A configuration is the render settings below with one\n"
      "combination of the --sweep values, e.g. --sweep ssgi-samples=4,8,16 --sweep ssgi-method=radiance.\n"
      "The seed spec's settings (hemisphere, 64 samples, radius 0.5, bias 0.025, no blur) are always\n"
      "measured too and marked in the chart. Exit codes: 0 ok, 1 runtime error, 2 usage error.\n\n";
  help += commandOptionsHelp(benchOptions(), defaults,
                             "render settings every configuration starts from (any of them can be swept)");
  return help;
}

int runBenchCommand(const std::vector<std::string>& args) {
  const BenchCommand command = parseBenchArgs(args);
  if (command.help) {
    std::cout << benchHelp();
    return 0;
  }
  if (command.traceReference && !referenceAvailable())
    throw Error("headlight bench needs the reference: this build has no Embree (--no-reference times only)");
  // Before any measurement, without making anything yet (a refused scene
  // leaves no folder): an --out that cannot become a folder must not cost
  // the whole run. The nearest part of the path that exists must be a folder.
  const std::filesystem::path out(command.outDir);
  std::error_code statusError;
  for (std::filesystem::path part = out; !part.empty(); part = part.parent_path()) {
    const std::filesystem::file_status status = std::filesystem::status(part, statusError);
    if (!std::filesystem::exists(status)) {
      if (part == part.parent_path()) break;
      continue;
    }
    if (!std::filesystem::is_directory(status))
      throw IoError(out.string() + ": cannot create the output folder: " + part.string() + " is not a folder");
    break;
  }
  // Render's folder rules (issue 32): never a scene's own folder, and one
  // writer at a time from before the first measurement (the lock makes the
  // folder, and removes it again if the run fails before writing into it).
  for (const std::string& sceneName : command.scenes) {
    Job folderJob;
    folderJob.scene = sceneName;
    folderJob.outDir = command.outDir;
    if (const std::string refusal = outputFolderRefusal(folderJob, /*force=*/true); !refusal.empty())
      throw IoError(refusal);
  }
  const detail::OutputFolderLock lock(out, false);
  if (const std::string refusal =
          foreignFilesRefusal(out, kBenchFiles, isBenchOutput, "headlight bench", command.force);
      !refusal.empty())
    throw IoError(refusal);
  std::optional<Context> context;  // made once the first scene has loaded: a refused scene needs no GL
  std::optional<Renderer> renderer;
  std::vector<BenchRow> rows;
  const bool quiet = command.verbosity == Verbosity::Quiet;
  const std::size_t configsPerGroup = benchConfigs(command, 1, 1).size();
  Progress progress(command.scenes.size() * command.resolutions.size() * configsPerGroup, !quiet, "configs");
  std::size_t done = 0;
  const MeasureOptions measureOptions{command.repetitions, command.warmup, command.reference, command.traceReference};
  for (const std::string& sceneName : command.scenes) {
    Scene scene = loadCommandScene(sceneName, command.sceneLoad, command.limits, command.verbosity == Verbosity::Quiet);
    if (!context) {
      context.emplace(command.context);
      renderer.emplace(*context);
      renderer->setLimits(command.limits);
    }
    if (command.verbosity == Verbosity::Verbose) {
      progress.clear();
      std::cerr << verboseHeader(*context, scene);
    }
    renderer->setScene(std::move(scene));
    for (const auto& [width, height] : command.resolutions)
      for (BenchRow& row :
           measureConfigs(*renderer, benchConfigs(command, width, height), measureOptions, progress, done))
        rows.push_back(std::move(row));
  }
  progress.finish();
  markParetoFronts(rows);

  // Into the folder the lock holds, through its descriptor (issue 32): a
  // folder renamed or replaced during the run keeps this run's files, as
  // render's and reference's do. The chart's python3 child reaches it
  // through this process's /proc entry (/proc/self would be the child's).
  const std::filesystem::path folder = lock.directory();
  try {
    writeBenchCsv(rows, folder / "bench.csv");
    writeBenchJson(rows, joinArgs(args), folder / "bench.json");
  } catch (const Error& error) {
    throw IoError(lock.named(error.what(), out), error.settings());
  }
  if (!quiet) std::cout << (out / "bench.csv").string() << "\n" << (out / "bench.json").string() << "\n";
  std::string childFolder = folder.string();
  if (childFolder.rfind("/proc/self/", 0) == 0)
    childFolder = "/proc/" + std::to_string(getpid()) + childFolder.substr(std::string("/proc/self").size());
  // The chart plots errors: none without a reference.
  if (command.chart && command.traceReference &&
      !drawChart(std::filesystem::path(childFolder) / "bench.csv", childFolder))
    throw IoError((out / "bench.png").string() + ": the chart script failed (is python3-matplotlib installed?)");
  return 0;
}

}  // namespace headlight::cli

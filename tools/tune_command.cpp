#include "tune_command.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <sstream>

#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "io/atomic_file.hpp"
#include "io/bounded_read.hpp"

namespace headlight::cli {
namespace {

std::vector<Option<TuneCommand>> tuneOptions() {
  using T = OptionType;
  using C = TuneCommand;
  std::vector<Option<C>> rows = commonCommandOptions<C>(kVerboseHelpTune);
  for (Option<C>& row : rows)
    if (row.spec.name == "out") {
      row.spec.help = "the settings file to write (render --settings FILE reads it)";
      row.spec.valueName = "FILE";
      // A file, not render's folder: an image's name is refused in tune's words.
      row.set = [](C& c, const OptionValue& v) {
        const std::string& file = std::get<std::string>(v);
        if (namesImageFile(file))
          throw SettingsError("--out " + file +
                              ": names an image file, but tune writes a settings file (`name = "
                              "value` lines); name it e.g. headlight.settings");
        c.outDir = file;
      };
    }
  rows.push_back(bindOption<C>(
      {.name = "max-ao-error",
       .type = T::Float,
       .help = "required: the largest AO RMSE against the reference (over geometry pixels, within the radius) "
               "the chosen configuration may have",
       .minimum = 0,
       .maximum = 1},
      [](auto& c) -> auto& { return c.maxAoError; }));
  rows.push_back(bindOption<C>(
      {.name = "max-flip",
       .type = T::Float,
       .help = "the largest mean HDR-FLIP of lit against the reference's lit_ref (every pixel; 0 = identical, "
               "1 = green against blue) the chosen configuration may have; with --max-ao-error both must hold",
       .minimum = 0,
       .maximum = 1},
      [](auto& c) -> auto& { return c.maxFlip; }));
  for (auto& row : measurementOptions<C>("candidates: sweep a render setting over values; repeat for a cartesian "
                                         "product (default: ssgi-slices, ssgi-steps, ssgi-thickness, ssgi-resolution, "
                                         "ssgi-frames of the bitmask method)"))
    rows.push_back(std::move(row));
  for (auto& row : liftOptions(referenceOptions(), &C::reference)) rows.push_back(std::move(row));
  for (auto& row : sceneInputOptions<C>()) rows.push_back(std::move(row));
  // render's --settings row, also remembering the file (checkTuneOut).
  Option<C> settings = settingsFileOption<C>(&C::base);
  settings.set = [apply = settings.set](C& c, const OptionValue& v) {
    apply(c, v);
    c.settingsFiles.push_back(std::get<std::string>(v));
  };
  rows.push_back(std::move(settings));
  for (auto& row : liftOptions(settingOptions(), &C::base)) rows.push_back(std::move(row));
  return rows;
}

std::string joinArgs(const std::vector<std::string>& args) {
  std::string text = "headlight tune";
  for (const auto& arg : args) text += " " + arg;
  return text;
}

constexpr const char* kAsGiven = "as given";

std::string number(double value, int digits = 4) {
  std::ostringstream text;
  text.precision(digits);
  text << value;
  return text.str();
}

// --out checked before the (long) measurement: a folder, a device or the
// scene itself is refused up front, not after minutes of work.
void checkTuneOut(const TuneCommand& command) {
  namespace fs = std::filesystem;
  const fs::path out = command.outDir;
  if (out.empty()) throw SettingsError("--out: expected the settings file to write");
  std::error_code error;
  if (fs::is_directory(out, error))
    throw SettingsError("--out " + out.string() + ": is a folder, expected the settings file to write");
  if (const std::string kind = detail::nonRegularKind(out); !kind.empty())
    throw SettingsError("--out " + out.string() + ": is " + kind + ", expected the settings file to write");
  if (command.scene.rfind("builtin:", 0) != 0 && fs::exists(out, error) && fs::equivalent(out, command.scene, error))
    throw SettingsError("--out " + out.string() + ": is the scene being tuned; write the settings elsewhere");
  // Nor an input of the run (issue 32: the environment map was replaced by a settings file, exit 0).
  const auto isInput = [&](const std::string& input) {
    return !input.empty() && fs::exists(out, error) && fs::equivalent(out, input, error);
  };
  if (isInput(command.sceneLoad.environment))
    throw SettingsError("--out " + out.string() +
                        ": is the --environment map the run reads; write the settings elsewhere");
  for (const std::string& settings : command.settingsFiles)
    if (isInput(settings))
      throw SettingsError("--out " + out.string() + ": is the --settings file the run starts from (" + settings +
                          "); write the tuned settings elsewhere");
}

// The two configurations every tune measures beside its candidates, so that
// a user sees what the pick is worth (issue 30): the settings as given (the
// defaults, --settings and flags; what render would do without tune's file)
// and no SSGI at all (cheapest of all, and within a loose bound the honest
// answer). No SSGI is left out when the sweeps already vary `ssgi`.
struct Comparisons {
  std::size_t asGiven = 0;
  std::optional<std::size_t> noSsgi;
};
Comparisons addComparisons(const TuneCommand& command, const std::vector<SettingSweep>& sweeps,
                           std::vector<BenchConfig>& configs) {
  Comparisons added{configs.size(), std::nullopt};
  for (BenchConfig config : sweepConfigs(command.base, {}, command.base.width, command.base.height)) {
    config.label = kAsGiven;
    configs.push_back(std::move(config));
  }
  const bool sweepsSsgi =
      std::any_of(sweeps.begin(), sweeps.end(), [](const SettingSweep& s) { return s.name == "ssgi"; });
  if (!sweepsSsgi && command.base.ssgi.enabled) {
    added.noSsgi = configs.size();
    for (BenchConfig& config :
         sweepConfigs(command.base, {parseSweep("ssgi=off")}, command.base.width, command.base.height))
      configs.push_back(std::move(config));
  }
  return added;
}

}  // namespace

std::vector<SettingSweep> defaultTuneSweeps(float autoThickness) {
  std::vector<SettingSweep> sweeps{parseSweep("ssgi-method=bitmask"), parseSweep("ssgi-slices=1,2,4"),
                                   parseSweep("ssgi-steps=4,8,16,24")};
  // Thickness is in world units: around the scene's own auto value.
  sweeps.push_back({"ssgi-thickness", {AutoValue{}, double(0.5f * autoThickness), double(2.0f * autoThickness)}});
  sweeps.push_back(parseSweep("ssgi-resolution=full,half"));
  sweeps.push_back(parseSweep("ssgi-frames=1,4"));
  return sweeps;
}

std::optional<std::size_t> cheapestWithin(const std::vector<BenchRow>& rows, std::optional<double> maxAoError,
                                          std::optional<double> maxFlip) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const bool within = (!maxAoError || rows[i].ao.rmse <= *maxAoError) && (!maxFlip || rows[i].litFlip <= *maxFlip);
    if (within && (!best || rows[i].frameMs.median < rows[*best].frameMs.median)) best = i;
  }
  return best;
}

TuneCommand parseTuneArgs(const std::vector<std::string>& args) {
  TuneCommand command;
  const auto options = tuneOptions();
  const std::vector<std::string> scenes = parseCommandLine<TuneCommand>(args, options, command, "tune");
  if (command.help) return command;
  if (scenes.size() > 1) throw SettingsError("more than one scene given: '" + scenes[0] + "' and '" + scenes[1] + "'");
  if (!scenes.empty()) command.scene = scenes[0];
  if (command.maxAoError < 0 && command.maxFlip < 0)
    throw SettingsError(
        "--max-ao-error: required unless --max-flip is given (the AO RMSE to meet, e.g. 0.05, or lit's HDR-FLIP, "
        "e.g. 0.1)");
  command.base.validate();
  return command;
}

std::string tuneHelp() {
  TuneCommand defaults;
  std::string help =
      "usage: headlight tune [SCENE] (--max-ao-error E | --max-flip F) [options]\n\n"
      "Measures SCENE's own speed/accuracy front (default builtin:cornell): every candidate SSGI\n"
      "configuration is rendered at --width x --height (default 128 x 128), timed (median of\n"
      "--repetitions frames after --warmup) and its AO compared with the Embree reference (`headlight\n"
      "reference`) over geometry pixels, as `headlight bench` does. Writes --out (a settings file:\n"
      "`name = value` lines, for `headlight render --settings FILE`) holding the cheapest\n"
      "configuration whose AO RMSE is at most E (and/or whose lit, as mean HDR-FLIP against the reference's\n"
      "lit_ref, is at most F), with its measured errors and time as '# tune:' lines.\n"
      "Two configurations are measured beside the candidates and may be chosen: the settings as given\n"
      "(defaults, --settings, flags) and no SSGI (--no-ssgi; unless the sweeps vary ssgi); the pick is\n"
      "reported beside both, with its time as a fraction of the settings as given.\n"
      "Prints the front; a progress bar on stderr when it is a terminal.\n\n"
      "Exit codes: 0 written; 1 runtime error; 2 usage error; 3 no configuration reaches E: nothing is\n"
      "written, and the message names the best AO RMSE reached.\n\n";
  help += commandOptionsHelp(tuneOptions(), defaults,
                             "render settings every configuration starts from (the file keeps them, but width, "
                             "height, camera)");
  return help;
}

int runTuneCommand(const std::vector<std::string>& args) {
  const auto start = std::chrono::steady_clock::now();
  const TuneCommand command = parseTuneArgs(args);
  if (command.help) {
    std::cout << tuneHelp();
    return 0;
  }
  checkTuneOut(command);
  if (!referenceAvailable()) throw Error("headlight tune needs the reference: this build has no Embree");
  Scene scene =
      loadCommandScene(command.scene, command.sceneLoad, command.limits, command.verbosity == Verbosity::Quiet);
  Context context(command.context);
  if (command.verbosity == Verbosity::Verbose) std::cerr << verboseHeader(context, scene);
  Renderer renderer(context);
  renderer.setLimits(command.limits);
  renderer.setScene(std::move(scene));
  const std::vector<SettingSweep> sweeps =
      command.sweeps.empty() ? defaultTuneSweeps(*renderer.resolve(command.base).ssgi.thickness) : command.sweeps;
  std::vector<BenchConfig> configs = sweepConfigs(command.base, sweeps, command.base.width, command.base.height);
  if (configs.empty()) throw SettingsError("tune: every combination of the --sweep values is refused by the settings");
  const Comparisons comparisons = addComparisons(command, sweeps, configs);

  const bool quiet = command.verbosity == Verbosity::Quiet;
  Progress progress(configs.size(), !quiet, "configs");
  std::size_t done = 0;
  std::vector<BenchRow> rows =
      measureConfigs(renderer, configs, {command.repetitions, command.warmup, command.reference}, progress, done);
  progress.update(done, "done");
  progress.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  // The front on the bound asked for (AO when both are).
  const std::optional<double> maxAo =
      command.maxAoError >= 0 ? std::optional<double>(command.maxAoError) : std::nullopt;
  const std::optional<double> maxFlip = command.maxFlip >= 0 ? std::optional<double>(command.maxFlip) : std::nullopt;
  auto frontError = [&](const BenchRow& row) { return maxAo ? row.ao.rmse : row.litFlip; };
  std::vector<std::pair<double, double>> points;
  for (const BenchRow& row : rows) points.emplace_back(row.frameMs.median, frontError(row));
  const std::vector<bool> front = paretoFront(points);
  std::vector<std::size_t> order(rows.size());
  for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](std::size_t a, std::size_t b) { return rows[a].frameMs.median < rows[b].frameMs.median; });
  if (!quiet) {
    std::cout << "tune: " << rows.size() << " configurations of " << renderer.scene().source << " at "
              << command.base.width << "x" << command.base.height << " in " << number(seconds, 3) << " s; reference "
              << rows.front().referenceSamples << " rays/pixel (mean AO standard error "
              << number(rows.front().referenceAoStandardError, 2) << ")\n";
    std::cout << (command.verbosity == Verbosity::Verbose ? "every configuration" : "the front")
              << (maxAo ? " on AO" : " on lit HDR-FLIP") << " (frame ms, AO RMSE, lit HDR-FLIP):\n";
    for (std::size_t i : order)
      if (front[i] || command.verbosity == Verbosity::Verbose)
        std::printf("  %8.2f ms  %.4f  %.4f  %s%s\n", rows[i].frameMs.median, rows[i].ao.rmse, rows[i].litFlip,
                    rows[i].label.c_str(), front[i] ? "" : "  (off the front)");
    std::fflush(stdout);
  }

  std::string bounds;  // "AO RMSE <= 0.05 and lit HDR-FLIP <= 0.1"
  if (maxAo) bounds = "AO RMSE <= " + number(*maxAo);
  if (maxFlip) bounds += (bounds.empty() ? "" : " and ") + std::string("lit HDR-FLIP <= ") + number(*maxFlip);
  const std::optional<std::size_t> chosen = cheapestWithin(rows, maxAo, maxFlip);
  if (!chosen) {
    std::cerr << "headlight tune: no configuration reaches " << bounds << " on " << renderer.scene().source;
    // The best reached on each bound asked for.
    if (maxAo) {
      const auto best = std::min_element(rows.begin(), rows.end(),
                                         [](const BenchRow& a, const BenchRow& b) { return a.ao.rmse < b.ao.rmse; });
      std::cerr << "; the best reached " << number(best->ao.rmse) << " (" << best->label << ", "
                << number(best->frameMs.median) << " ms/frame)";
    }
    if (maxFlip) {
      const auto best = std::min_element(rows.begin(), rows.end(),
                                         [](const BenchRow& a, const BenchRow& b) { return a.litFlip < b.litFlip; });
      std::cerr << "; the best lit HDR-FLIP reached " << number(best->litFlip) << " (" << best->label << ", "
                << number(best->frameMs.median) << " ms/frame)";
    }
    std::cerr << "; nothing written to " << command.outDir << "\n";
    return kExitTuneUnmet;
  }
  const BenchRow& row = rows[*chosen];
  std::vector<std::string> comments{
      "headlight settings, written by: " + joinArgs(args),
      "the cheapest of " + std::to_string(rows.size()) + " configurations measured on " + row.scene + " at " +
          std::to_string(row.width) + "x" + std::to_string(row.height) + " with " + bounds + ": " + row.label,
      "tune: ao-rmse = " + number(row.ao.rmse, 6), "tune: lit-flip = " + number(row.litFlip, 6)};
  if (maxAo) comments.push_back("tune: max-ao-error = " + number(*maxAo, 6));
  if (maxFlip) comments.push_back("tune: max-flip = " + number(*maxFlip, 6));
  comments.push_back("tune: frame-ms = " + number(row.frameMs.median, 6) + " (median of " +
                     std::to_string(row.repetitions) + "; ssgi " + number(row.ssgiMs.median) + " ms) on " +
                     row.renderer);
  comments.push_back(
      "tune: reference = " + std::to_string(row.referenceSamples) + " rays/pixel, mean AO standard error " +
      number(row.referenceAoStandardError, 3) +
      (row.referenceScreenBound ? ", the screen-space bound (--reference-screen-bound), not the truth" : ""));
  const BenchRow& given = rows[comparisons.asGiven];
  const std::string timeRatio = number(row.frameMs.median / given.frameMs.median, 3) + "x";
  // The comparisons as the chosen row is recorded: one `# tune: key = value` line each.
  const auto record = [&](const std::string& prefix, const BenchRow& r) {
    comments.push_back("tune: " + prefix + "-ao-rmse = " + number(r.ao.rmse, 6));
    comments.push_back("tune: " + prefix + "-lit-flip = " + number(r.litFlip, 6));
    comments.push_back("tune: " + prefix + "-frame-ms = " + number(r.frameMs.median, 6));
  };
  record("as-given", given);
  if (comparisons.noSsgi) record("no-ssgi", rows[*comparisons.noSsgi]);
  comments.push_back("use: headlight render SCENE --settings FILE (flags after --settings override it)");
  writeTextFile(command.outDir, settingsFileText(configs[*chosen].settings, comments));
  if (!quiet) {
    const auto line = [](const BenchRow& r) {
      return "AO RMSE " + number(r.ao.rmse) + ", lit HDR-FLIP " + number(r.litFlip) + ", " + number(r.frameMs.median) +
             " ms/frame";
    };
    std::cout << "chosen: " << row.label << ": " << line(row) << " (" << bounds << ")\n"
              << "  as given: " << line(given) << "; the chosen takes " << timeRatio << " its time\n";
    if (comparisons.noSsgi) std::cout << "  no SSGI: " << line(rows[*comparisons.noSsgi]) << "\n";
    std::cout << command.outDir << "\n";
  }
  return 0;
}

}  // namespace headlight::cli

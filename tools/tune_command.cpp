#include "tune_command.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>

#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "output/atomic_file.hpp"
#include "output/bounded_read.hpp"

namespace headlight::cli {
namespace {

std::vector<Option<TuneCommand>> tuneOptions() {
  using T = OptionType;
  using C = TuneCommand;
  std::vector<Option<C>> rows = commonCommandOptions<C>();
  for (Option<C>& row : rows)
    if (row.spec.name == "out") {
      row.spec.help = "the settings file to write (render --settings FILE reads it)";
      row.spec.valueName = "FILE";
    }
  rows.push_back(bindOption<C>(
      {.name = "max-ao-error",
       .type = T::Float,
       .help = "required: the largest AO RMSE against the reference (over geometry pixels, within the radius) "
               "the chosen configuration may have",
       .minimum = 0,
       .maximum = 1},
      [](auto& c) -> auto& { return c.maxAoError; }));
  for (auto& row : measurementOptions<C>("candidates: sweep a render setting over values; repeat for a cartesian "
                                         "product (default: ssgi-slices, ssgi-steps, ssgi-thickness, ssgi-resolution, "
                                         "ssgi-frames of the bitmask method)"))
    rows.push_back(std::move(row));
  for (auto& row : liftOptions(referenceOptions(), &C::reference)) rows.push_back(std::move(row));
  rows.push_back(settingsFileOption<C>(&C::base));
  for (auto& row : liftOptions(settingOptions(), &C::base)) rows.push_back(std::move(row));
  return rows;
}

std::string joinArgs(const std::vector<std::string>& args) {
  std::string text = "headlight tune";
  for (const auto& arg : args) text += " " + arg;
  return text;
}

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

std::optional<std::size_t> cheapestWithin(const std::vector<BenchRow>& rows, double maxAoError) {
  std::optional<std::size_t> best;
  for (std::size_t i = 0; i < rows.size(); ++i)
    if (rows[i].ao.rmse <= maxAoError && (!best || rows[i].frameMs.median < rows[*best].frameMs.median)) best = i;
  return best;
}

TuneCommand parseTuneArgs(const std::vector<std::string>& args) {
  TuneCommand command;
  command.maxAoError = -1;  // "not given"
  const auto options = tuneOptions();
  const std::vector<std::string> scenes = parseCommandLine<TuneCommand>(args, options, command, "tune");
  if (command.help) return command;
  if (scenes.size() > 1) throw SettingsError("more than one scene given: '" + scenes[0] + "' and '" + scenes[1] + "'");
  if (!scenes.empty()) command.scene = scenes[0];
  if (command.maxAoError < 0) throw SettingsError("--max-ao-error: required (the AO RMSE to meet, e.g. 0.05)");
  command.base.validate();
  return command;
}

std::string tuneHelp() {
  TuneCommand defaults;
  std::string help =
      "usage: headlight tune [SCENE] --max-ao-error E [options]\n\n"
      "Measures SCENE's own speed/accuracy front (default builtin:cornell): every candidate SSGI\n"
      "configuration is rendered at --width x --height (default 128 x 128), timed (median of\n"
      "--repetitions frames after --warmup) and its AO compared with the Embree reference (`headlight\n"
      "reference`) over geometry pixels, as `headlight bench` does. Writes --out (a settings file:\n"
      "`name = value` lines, for `headlight render --settings FILE`) holding the cheapest\n"
      "configuration whose AO RMSE is at most E, with its measured error and time as '# tune:' lines.\n"
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
  Context context(command.context);
  Renderer renderer(context);
  renderer.setScene(loadScene(command.scene));
  const std::vector<SettingSweep> sweeps =
      command.sweeps.empty() ? defaultTuneSweeps(*renderer.resolve(command.base).ssgi.thickness) : command.sweeps;
  const std::vector<BenchConfig> configs = sweepConfigs(command.base, sweeps, command.base.width, command.base.height);
  if (configs.empty()) throw SettingsError("tune: every combination of the --sweep values is refused by the settings");

  const bool quiet = command.verbosity == Verbosity::Quiet;
  Progress progress(configs.size(), !quiet, "configs");
  std::size_t done = 0;
  std::vector<BenchRow> rows =
      measureConfigs(renderer, configs, {command.repetitions, command.warmup, command.reference}, progress, done);
  progress.update(done, "done");
  progress.finish();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();

  std::vector<std::pair<double, double>> points;
  for (const BenchRow& row : rows) points.emplace_back(row.frameMs.median, row.ao.rmse);
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
              << " (frame ms, AO RMSE):\n";
    for (std::size_t i : order)
      if (front[i] || command.verbosity == Verbosity::Verbose)
        std::printf("  %8.2f ms  %.4f  %s%s\n", rows[i].frameMs.median, rows[i].ao.rmse, rows[i].label.c_str(),
                    front[i] ? "" : "  (off the front)");
    std::fflush(stdout);
  }

  const std::optional<std::size_t> chosen = cheapestWithin(rows, command.maxAoError);
  if (!chosen) {
    const auto best = std::min_element(rows.begin(), rows.end(),
                                       [](const BenchRow& a, const BenchRow& b) { return a.ao.rmse < b.ao.rmse; });
    std::cerr << "headlight tune: no configuration reaches AO RMSE <= " << number(command.maxAoError) << " on "
              << renderer.scene().source << "; the best reached " << number(best->ao.rmse) << " (" << best->label
              << ", " << number(best->frameMs.median) << " ms/frame); nothing written to " << command.outDir << "\n";
    return kExitTuneUnmet;
  }
  const BenchRow& row = rows[*chosen];
  const std::vector<std::string> comments{
      "headlight settings, written by: " + joinArgs(args),
      "the cheapest of " + std::to_string(rows.size()) + " configurations measured on " + row.scene + " at " +
          std::to_string(row.width) + "x" + std::to_string(row.height) + " whose AO RMSE is at most " +
          number(command.maxAoError) + ": " + row.label,
      "tune: ao-rmse = " + number(row.ao.rmse, 6),
      "tune: max-ao-error = " + number(command.maxAoError, 6),
      "tune: frame-ms = " + number(row.frameMs.median, 6) + " (median of " + std::to_string(row.repetitions) +
          "; ssgi " + number(row.ssgiMs.median) + " ms) on " + row.renderer,
      "tune: reference = " + std::to_string(row.referenceSamples) + " rays/pixel, mean AO standard error " +
          number(row.referenceAoStandardError, 3),
      "use: headlight render SCENE --settings FILE (flags after --settings override it)"};
  detail::writeTextAtomically(command.outDir, settingsFileText(configs[*chosen].settings, comments));
  if (!quiet)
    std::cout << "chosen: " << row.label << ": AO RMSE " << number(row.ao.rmse) << " <= " << number(command.maxAoError)
              << ", " << number(row.frameMs.median) << " ms/frame\n"
              << command.outDir << "\n";
  return 0;
}

}  // namespace headlight::cli

// headlight: glTF (or a built-in scene) in, every G-buffer target, the SSGI
// output and the lit image out as EXR. The whole data flow of `render`:
//   parse flags -> plan the jobs (tools/batch.cpp) -> run: loadScene ->
//   Context -> Renderer::setScene -> Renderer::submit/collect -> writeFrame
//   -> report: one summary line per file.
#include <cstdio>
#include <iostream>
#include <string>
#include <vector>

#include "batch.hpp"
#include "batch_plan.hpp"
#include "bench_command.hpp"
#include "cli_options.hpp"
#include "diff_command.hpp"
#include "headlight/context.hpp"
#include "headlight/error.hpp"
#include "headlight/output.hpp"
#include "headlight/reference.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/version.hpp"
#include "io/folder_lock.hpp"
#include "job_file.hpp"
#include "progress.hpp"
#include "tooling/large_pages.hpp"
#include "tune_command.hpp"

namespace {

using namespace headlight;

constexpr int kExitOk = 0;
constexpr int kExitRuntimeError = 1;
constexpr int kExitUsage = 2;

const char* kUsage =
    "usage: headlight <command> [options]\n\n"
    "commands:\n"
    "  render [SCENE...]  render glTF files or builtin:<name> to EXRs; batches, job files (headlight render --help)\n"
    "  reference [SCENE]  ray-traced ground truth for the SSGI outputs (headlight reference --help)\n"
    "  bench [SCENE...]   time every SSGI setting and chart it against the reference (headlight bench --help)\n"
    "  tune [SCENE]       the cheapest SSGI settings within an AO error, as a settings file (headlight tune --help)\n"
    "  diff A B           compare two EXRs or two render folders (headlight diff --help)\n\n"
    "options:\n"
    "  --help           this help\n"
    "  --version        print the version\n";

// The error's type, for the message: a user (and a script) can tell a bad
// scene from a missing GL driver at a glance.
const char* errorKind(const std::exception& error) {
  if (dynamic_cast<const SceneError*>(&error)) return "SceneError";
  if (dynamic_cast<const ContextError*>(&error)) return "ContextError";
  if (dynamic_cast<const IoError*>(&error)) return "IoError";
  if (dynamic_cast<const GlError*>(&error)) return "GlError";
  if (dynamic_cast<const LimitError*>(&error)) return "LimitError";
  return "error";
}

int runRender(const std::vector<std::string>& args) {
  const cli::RenderCommand command = cli::parseRenderArgs(args);
  if (command.help) {
    std::cout << cli::renderHelp();
    return kExitOk;
  }
  return cli::runRender(command);
}

// `reference`: the G-buffer as `render` would draw it, then Embree traces
// the truth at those pixels.
int runReference(const std::vector<std::string>& args) {
  const cli::RenderCommand command = cli::parseRenderArgs(args, cli::CommandKind::Reference);
  if (command.help) {
    std::cout << cli::renderHelp(cli::CommandKind::Reference);
    return kExitOk;
  }
  if (!referenceAvailable()) throw Error("this headlight was built without Embree (meson -Dembree=enabled)");
  // The folder rules render keeps (issue 32): never the scene's own folder,
  // and one writer at a time, held from before the trace until the files
  // are written (a second reference into it is refused, naming the holder).
  cli::Job folderJob;
  folderJob.scene = command.scene;
  folderJob.outDir = command.outDir;
  if (const std::string refusal = cli::outputFolderRefusal(folderJob, /*force=*/true); !refusal.empty())
    throw IoError(refusal);
  const detail::OutputFolderLock lock(command.outDir, command.wait, command.waitSeconds);
  // Nor a file of that name the user keeps there: ours carry Headlight's settings attributes.
  const std::vector<std::string> referenceFiles{"ao_ref.exr", "indirect_ref.exr", "lit_ref.exr"};
  const auto isHeadlightExr = [](const std::filesystem::path& file) {
    try {
      return !readSettingAttributes(file).empty();
    } catch (const Error&) {
      return false;  // not an EXR, or unreadable: not ours
    }
  };
  if (const std::string refusal = cli::foreignFilesRefusal(command.outDir, referenceFiles, isHeadlightExr,
                                                           "headlight reference", command.force);
      !refusal.empty())
    throw IoError(refusal);
  Scene scene =
      loadCommandScene(command.scene, command.sceneLoad, command.limits, command.verbosity == cli::Verbosity::Quiet);
  Context context(command.context);
  if (command.verbosity == cli::Verbosity::Verbose) std::cerr << verboseHeader(context, scene);
  Renderer renderer(context);
  renderer.setLimits(command.limits);
  renderer.setScene(std::move(scene));
  // An explicit camera (--eye, --target) places the view as render's does.
  const std::optional<Camera> camera = cli::commandLineCamera(command).build(
      renderer.scene(), float(command.settings.width) / float(command.settings.height));
  const Frame frame = renderer.render(command.settings, camera ? &*camera : nullptr);
  ReferenceSettings settings = command.reference;
  settings.radius = *frame.settings.ssgi.radius;
  // Minutes at 640x480 and 4096 rays: a bar with the time left (on a terminal; issue 30).
  cli::Progress progress(std::size_t(frame.position.height), command.verbosity != cli::Verbosity::Quiet, "rows");
  const ReferenceImages reference = traceReference(renderer.scene(), frame, settings, [&](int rowsStarted, int rows) {
    progress.update(std::size_t(rowsStarted), "tracing " + std::to_string(settings.samplesPerPixel) + " rays/pixel, " +
                                                  std::to_string(rows) + " rows");
  });
  progress.finish();
  const ExrAttributes metadata{
      {"headlight:reference:samplesPerPixel", std::to_string(reference.samplesPerPixel)},
      {"headlight:reference:radiusWorld", std::to_string(settings.radius)},
      // The screen-space bound is not the truth: say which one this is.
      {"headlight:reference:screenBound", reference.screenBound ? "on" : "off"},
      {"headlight:reference:aoMeanStandardError", std::to_string(reference.aoMeanStandardError)},
      {"headlight:reference:aoMaxStandardError", std::to_string(reference.aoMaxStandardError)},
      {"headlight:reference:indirectMeanStandardError", std::to_string(reference.indirectMeanStandardError)},
      {"headlight:reference:seconds", std::to_string(reference.seconds)}};
  // Through the lock's descriptor: a trace takes minutes, and a folder
  // renamed meanwhile keeps its files (the lock is the folder, not its name).
  const std::filesystem::path out = lock.directory();
  std::vector<WrittenFile> files;
  try {
    files = {writeExr(frame, reference.ao, out / referenceFiles[0], true, metadata),
             writeExr(frame, reference.indirect, out / referenceFiles[1], true, metadata),
             writeExr(frame, reference.lit, out / referenceFiles[2], true, metadata)};
  } catch (const IoError& error) {
    throw IoError(lock.named(error.what(), command.outDir), error.settings());
  }
  if (command.verbosity != cli::Verbosity::Quiet) {
    for (const WrittenFile& file : files) std::cout << lock.named(file.summary, command.outDir) << "\n";
    std::cout << "reference: " << reference.samplesPerPixel << " rays/pixel in " << reference.seconds
              << " s; AO standard error mean " << reference.aoMeanStandardError << ", max "
              << reference.aoMaxStandardError << "\n";
  }
  return kExitOk;
}

}  // namespace

int main(int argc, char** argv) {
  const std::vector<std::string> args(argv + 1, argv + argc);
  if (args.empty() || args[0] == "--help" || args[0] == "-h") {
    std::cout << kUsage;
    return args.empty() ? kExitUsage : kExitOk;
  }
  if (args[0] == "--version") {
    std::cout << "headlight " << kVersion << "\n";
    return kExitOk;
  }
  restartWithLargePages(argv);  // returns unless it restarts
  try {
    const std::vector<std::string> rest(args.begin() + 1, args.end());
    if (args[0] == "render") return runRender(rest);
    if (args[0] == "reference") return runReference(rest);
    if (args[0] == "bench") return cli::runBenchCommand(rest);
    if (args[0] == "tune") return cli::runTuneCommand(rest);  // exit 3: no configuration meets the bound
    if (args[0] == "diff") return cli::runDiffCommand(rest);  // its own exit codes (docs/DIFF.md)
    std::cerr << "headlight: unknown command '" << args[0] << "'\n" << kUsage;
    return kExitUsage;
  } catch (const SettingsError& error) {
    std::cerr << "headlight: " << commandLineMessage(error) << "\n";
    return kExitUsage;
  } catch (const std::exception& error) {
    std::cerr << "headlight: " << errorKind(error) << ": " << commandLineMessage(error) << "\n";
    return kExitRuntimeError;
  }
}

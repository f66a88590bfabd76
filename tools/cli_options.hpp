#pragma once
// Command-line parsing for `headlight render` and `reference`. Render
// settings are the library's one table (settingOptions()), reference
// settings referenceOptions(); the rows here are only the CLI's own (where
// to write, which backend, how chatty). Every row goes through the one
// parser (parseCommandLine) and one help writer (optionHelp) of the support
// library (lib/tooling/command_line.hpp).
#include <filesystem>
#include <optional>

#include <glm/glm.hpp>

#include <string>
#include <vector>

#include "headlight/context.hpp"
#include "headlight/limits.hpp"
#include "headlight/options.hpp"
#include "headlight/output.hpp"
#include "headlight/reference.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/settings.hpp"
#include "settings/option_binding.hpp"
#include "tooling/command_line.hpp"
#include "tooling/command_setup.hpp"

namespace headlight::cli {

enum class Verbosity { Quiet, Normal, Verbose };

// Which command's flags are accepted: `reference` takes render's and its own.
enum class CommandKind { Render, Reference };

struct RenderCommand {
  std::string scene = "builtin:cornell";  // file path or builtin:<name>
  std::string outDir = "out";
  ContextOptions context;      // backend, --device; error policy from --strict
  SceneLoadOptions sceneLoad;  // --allow-external-paths, --strict-gltf, --scene
  Verbosity verbosity = Verbosity::Normal;
  bool help = false;
  RenderSettings settings;
  ResourceLimits limits;        // --max-memory, --max-instances, --max-triangles, --max-texels
  ReferenceSettings reference;  // `reference` only

  // `render` only: batches (tools/batch.hpp, docs/BATCH.md).
  std::vector<std::string> scenes;             // every SCENE given (empty: `scene`)
  std::vector<std::string> jobFiles;           // --jobs FILE: JSON Lines, one job per line
  int views = 0;                               // --views N: N views per scene (with --orbit)
  bool orbit = false;                          // --orbit: a turntable around the scene's bounds
  bool throughTime = false;                    // --through-time: the views step through --animation's length
  std::optional<float> orbitElevationDegrees;  // --orbit-elevation DEG (default: fitCamera's 14)
  std::optional<float> orbitDistanceScale;     // --orbit-distance F: times the framing distance
  bool camerasAll = false;                     // --cameras all: one job per camera of the scene
  // --eye X,Y,Z --target X,Y,Z [--up X,Y,Z] [--fov DEG]: an explicit camera,
  // as a job file's eye/target/up/fov (docs/BATCH.md).
  std::optional<glm::vec3> eye, target, up;
  std::optional<float> fovDegrees;
  int shardIndex = 0;  // --shard I/N: jobs k with k % N == I
  int shardCount = 1;
  bool shardIndexOmitted = false;  // --shard /N: I must come from --shard-index-env
  std::string shardIndexEnv;       // --shard-index-env VAR: I read from $VAR when the batch starts
  bool wait = false;               // --wait: wait for another render's lock on an output folder
  double waitSeconds = 600.0;      // --wait-timeout: how long (detail::kDefaultWaitSeconds)
  bool force = false;              // --force: replace files with a target's name no Headlight set listed
  bool resume = false;             // skip jobs whose complete frame.json records the same job hash
  OutputOptions output;            // --targets, --exr-compression, --clamp-nonfinite
  bool json = false;               // --json: one JSON summary on stdout instead of the summary lines
};

// What --verbose adds, per command (the help says what that command prints).
inline constexpr std::string_view kVerboseHelpRender = "print the GL backend, renderer and each pass's time";
inline constexpr std::string_view kVerboseHelpReference = "print the GL backend, renderer and the scene's size";
inline constexpr std::string_view kVerboseHelpBench = "print the GL backend, renderer and each scene's size";
inline constexpr std::string_view kVerboseHelpTune =
    "print the GL backend, renderer and the scene's size, and every configuration (not only the front)";

// The CLI's own rows shared by every command that renders (out, backend,
// device, strict, quiet, verbose, help). `Command` is any struct with
// outDir, context, verbosity and help members.
// True when `path` ends in an image file's extension (.png, .exr, .hdr, ...,
// any case): what --out must not name (render's is a folder, tune's a settings file).
bool namesImageFile(const std::filesystem::path& path);

template <class Command>
std::vector<Option<Command>> commonCommandOptions(std::string_view verboseHelp);

// --settings FILE: applies a settings file (headlight tune writes them) to
// the command's `member` settings where it stands on the command line: flags
// after it override it, flags before it are overridden by it.
template <class Command>
Option<Command> settingsFileOption(RenderSettings Command::*member) {
  return actionOption<Command>(
      {.name = "settings",
       .type = OptionType::Text,
       .help = "apply a settings file (`name = value` lines, as `headlight tune` writes); flags after it "
               "override it, flags before it are overridden by it",
       .valueName = "FILE"},
      [member](Command& c, const OptionValue& v) { applySettingsFile(c.*member, std::get<std::string>(v)); });
}

// The options part of a command's --help: its own rows under "options:",
// then the render-setting rows (which every command's table ends with, from
// settingOptions()) under `settingsHeading`.
template <class Command>
std::string commandOptionsHelp(const std::vector<Option<Command>>& rows, const Command& defaults,
                               std::string_view settingsHeading) {
  const std::size_t settingsStart = rows.size() - settingOptions().size();
  return "options:\n" + optionHelp<Command>(std::span(rows).first(settingsStart), defaults) + "\n" +
         std::string(settingsHeading) + ":\n" + optionHelp<Command>(std::span(rows).subspan(settingsStart), defaults);
}

// Parses the arguments after "render" (or "reference"). Throws SettingsError
// for a bad or unknown flag or value (the CLI maps it to exit code 2).
RenderCommand parseRenderArgs(const std::vector<std::string>& args, CommandKind kind = CommandKind::Render);

// `headlight render --help` (or reference's), generated from the same tables.
std::string renderHelp(CommandKind kind = CommandKind::Render);

}  // namespace headlight::cli

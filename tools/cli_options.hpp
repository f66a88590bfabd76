#pragma once
// Command-line parsing for `headlight render`. Render settings come from the
// library's one table (settingOptions()); the flags here are only the CLI's
// own (where to write, which backend, how chatty).
#include <string>
#include <vector>

#include "headlight/context.hpp"
#include "headlight/settings.hpp"

namespace headlight::cli {

enum class Verbosity { Quiet, Normal, Verbose };

// Which command's flags are accepted: `reference` takes render's and its own.
enum class CommandKind { Render, Reference };

struct RenderCommand {
  std::string scene = "builtin:cornell";  // file path or builtin:<name>
  std::string outDir = "out";
  ContextOptions context;  // backend, --device; error policy from --strict
  bool allowExternalPaths = false;
  Verbosity verbosity = Verbosity::Normal;
  bool help = false;
  RenderSettings settings;
  int referenceSamples = 4096;  // reference only: rays per pixel (ReferenceSettings' default)
};

// Parses the arguments after "render". Throws SettingsError for a bad or
// unknown flag or value (the CLI maps it to exit code 2).
RenderCommand parseRenderArgs(const std::vector<std::string>& args, CommandKind kind = CommandKind::Render);

// `headlight render --help` (or reference's), generated from the same tables.
std::string renderHelp(CommandKind kind = CommandKind::Render);

}  // namespace headlight::cli

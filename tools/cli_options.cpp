#include "cli_options.hpp"

#include <sstream>

#include "bench_command.hpp"
#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"

namespace headlight::cli {
namespace {

constexpr std::string_view kBackendNames[] = {"auto", "egl", "osmesa"};

std::string text(const OptionValue& value) { return std::get<std::string>(value); }

std::vector<Option<RenderCommand>> renderCommandOptions(CommandKind kind) {
  using T = OptionType;
  using C = RenderCommand;
  std::vector<Option<C>> rows = commonCommandOptions<C>();
  rows.push_back(actionOption<C>({.name = "preset",
                                  .type = T::Choice,
                                  .help = "named settings; flags after it override it",
                                  .choices = presetNames()},
                                 [](C& c, const OptionValue& v) { applyPreset(c.settings, text(v)); }));
  rows.push_back(bindOption<C>(
      {.name = "allow-external-paths",
       .type = T::Switch,
       .help = "let glTF URIs point outside the scene file's folder"},
      [](auto& c) -> auto& { return c.allowExternalPaths; }));
  for (auto& row : liftOptions(limitOptions(), &C::limits)) rows.push_back(std::move(row));
  if (kind == CommandKind::Reference)
    for (auto& row : liftOptions(referenceOptions(), &C::reference)) rows.push_back(std::move(row));
  for (auto& row : liftOptions(settingOptions(), &C::settings)) rows.push_back(std::move(row));
  return rows;
}

}  // namespace

template <class Command>
std::vector<Option<Command>> commonCommandOptions() {
  using T = OptionType;
  using C = Command;
  return {
      bindOption<C>(
          {.name = "out", .type = T::Text, .help = "folder for the output files", .valueName = "DIR"},
          [](auto& c) -> auto& { return c.outDir; }),
      actionOption<C>(
          {.name = "backend",
           .type = T::Choice,
           .help = "headless GL backend (auto: EGL, then OSMesa)",
           .choices = kBackendNames},
          [](C& c, const OptionValue& v) { c.context.backend = parseBackend(text(v)); },
          [](const C& c) { return OptionValue(std::string(backendName(c.context.backend))); }),
      actionOption<C>({.name = "device",
                       .type = T::Int,
                       .help = "EGL device index (EGL_EXT_device_enumeration)",
                       .maximum = 1 << 16,
                       .autoMeaning = "the first that works"},
                      [](C& c, const OptionValue& v) {
                        if (std::holds_alternative<std::int64_t>(v))
                          c.context.eglDevice = int(std::get<std::int64_t>(v));
                      }),
      actionOption<C>({.name = "strict", .type = T::Switch, .help = "treat OpenGL errors as fatal (default: warn)"},
                      [](C& c, const OptionValue&) { c.context.errorPolicy = GlErrorPolicy::Throw; }),
      actionOption<C>({.name = "quiet", .type = T::Switch, .help = "print nothing but errors"},
                      [](C& c, const OptionValue&) { c.verbosity = Verbosity::Quiet; }),
      actionOption<C>(
          {.name = "verbose", .type = T::Switch, .help = "print the GL backend, renderer and each pass's time"},
          [](C& c, const OptionValue&) { c.verbosity = Verbosity::Verbose; }),
      bindOption<C>(
          {.name = "help", .type = T::Switch, .help = "this help"}, [](auto& c) -> auto& { return c.help; }),
  };
}
template std::vector<Option<RenderCommand>> commonCommandOptions<RenderCommand>();
template std::vector<Option<BenchCommand>> commonCommandOptions<BenchCommand>();

RenderCommand parseRenderArgs(const std::vector<std::string>& args, CommandKind kind) {
  RenderCommand command;
  command.context.errorPolicy = GlErrorPolicy::Warn;
  const auto options = renderCommandOptions(kind);
  const std::vector<std::string> scenes =
      parseCommandLine<RenderCommand>(args, options, command, kind == CommandKind::Render ? "render" : "reference");
  if (scenes.size() > 1) throw SettingsError("more than one scene given: '" + scenes[0] + "' and '" + scenes[1] + "'");
  if (!scenes.empty()) command.scene = scenes[0];
  return command;
}

std::string renderHelp(CommandKind kind) {
  std::ostringstream out;
  if (kind == CommandKind::Render)
    out << "usage: headlight render [SCENE] [options]\n\n"
           "Renders SCENE (a .gltf/.glb file or builtin:NAME; default builtin:cornell) and writes\n"
           "position, normal, albedo, material, depth, [emissive], ssgi and lit .exr plus preview.png\n"
           "into the output folder, printing one line per file.\n\n";
  else
    out << "usage: headlight reference [SCENE] [options]\n\n"
           "Ray-traces (Embree) the ground truth for SCENE at the pixels `render` would draw with the same\n"
           "options, and writes ao_ref.exr, indirect_ref.exr and lit_ref.exr into the output folder\n"
           "(docs/ACCURACY.md defines them).\n\n";
  out << "Built-in scenes:";
  for (const std::string& name : builtinSceneNames()) out << " builtin:" << name;
  out << "\n\nExit codes: 0 ok, 1 runtime error (scene, GL, I/O), 2 usage error.\n\noptions:\n";
  RenderCommand defaults;
  defaults.context.errorPolicy = GlErrorPolicy::Warn;
  const auto rows = renderCommandOptions(kind);
  const std::size_t settingsStart = rows.size() - settingOptions().size();
  out << optionHelp<RenderCommand>(std::span(rows).first(settingsStart), defaults);
  out << "\nrender settings (also recorded in every EXR's metadata as headlight:setting:NAME):\n";
  out << optionHelp<RenderCommand>(std::span(rows).subspan(settingsStart), defaults);
  return out.str();
}

}  // namespace headlight::cli

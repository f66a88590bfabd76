#include "cli_options.hpp"

#include <charconv>
#include <functional>
#include <optional>
#include <sstream>

#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"

namespace headlight::cli {
namespace {

struct CliFlag {
  bool referenceOnly;
  const char* name;
  const char* valueName;  // empty for a switch
  const char* help;
  std::function<void(RenderCommand&, const std::string&)> apply;
};

int parseCount(const char* name, const std::string& text, int low, int high) {
  int value = 0;
  auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc() || end != text.data() + text.size() || value < low || value > high)
    throw SettingsError(std::string("--") + name + ": expected an integer in " + std::to_string(low) + ".." +
                        std::to_string(high) + ", got '" + text + "'");
  return value;
}

const std::vector<CliFlag>& cliFlags() {
  static const std::vector<CliFlag> flags{
      {false, "out", "DIR", "folder for the EXRs and preview.png (default: out)",
       [](RenderCommand& c, const std::string& v) { c.outDir = v; }},
      {false, "backend", "auto|egl|osmesa", "headless GL backend (default: auto = EGL, then OSMesa)",
       [](RenderCommand& c, const std::string& v) { c.context.backend = parseBackend(v); }},
      {false, "device", "N", "EGL device index (EGL_EXT_device_enumeration); default: the first that works",
       [](RenderCommand& c, const std::string& v) { c.context.eglDevice = parseCount("device", v, 0, 1 << 16); }},
      {false, "preset", "fast|default|high|seed", "named settings; flags after it override it",
       [](RenderCommand& c, const std::string& v) { applyPreset(c.settings, v); }},
      {false, "allow-external-paths", "", "let glTF URIs point outside the scene file's folder",
       [](RenderCommand& c, const std::string&) { c.allowExternalPaths = true; }},
      {false, "strict", "", "treat OpenGL errors as fatal (default: warn)",
       [](RenderCommand& c, const std::string&) { c.context.errorPolicy = GlErrorPolicy::Throw; }},
      {false, "quiet", "", "print nothing but errors", [](RenderCommand& c, const std::string&) { c.verbosity = Verbosity::Quiet; }},
      {false, "verbose", "", "print the GL backend, renderer and each pass's time",
       [](RenderCommand& c, const std::string&) { c.verbosity = Verbosity::Verbose; }},
      {true, "samples", "N", "reference rays per pixel (1..1048576; default 4096)",
       [](RenderCommand& c, const std::string& v) { c.referenceSamples = parseCount("samples", v, 1, 1 << 20); }},
      {false, "help", "", "this help", [](RenderCommand& c, const std::string&) { c.help = true; }},
  };
  return flags;
}

// Splits "--name=value" and "--name value"; returns false if `arg` is no flag.
bool splitFlag(const std::string& arg, std::string& name, std::optional<std::string>& inlineValue) {
  if (arg.size() < 3 || arg.compare(0, 2, "--") != 0) return false;
  const auto equals = arg.find('=');
  name = arg.substr(2, equals == std::string::npos ? std::string::npos : equals - 2);
  if (equals != std::string::npos) inlineValue = arg.substr(equals + 1);
  return true;
}

}  // namespace

RenderCommand parseRenderArgs(const std::vector<std::string>& args, CommandKind kind) {
  RenderCommand command;
  command.context.errorPolicy = GlErrorPolicy::Warn;
  bool sceneGiven = false;
  for (std::size_t i = 0; i < args.size(); ++i) {
    std::string name;
    std::optional<std::string> inlineValue;
    if (!splitFlag(args[i], name, inlineValue)) {
      if (args[i].size() > 1 && args[i][0] == '-') throw SettingsError("unknown option '" + args[i] + "'");
      if (sceneGiven) throw SettingsError("more than one scene given: '" + command.scene + "' and '" + args[i] + "'");
      command.scene = args[i];
      sceneGiven = true;
      continue;
    }
    auto takeValue = [&](bool needsValue) -> std::string {
      if (!needsValue) {
        if (inlineValue) throw SettingsError(std::string("--") + name + " takes no value");
        return {};
      }
      if (inlineValue) return *inlineValue;
      if (i + 1 >= args.size()) throw SettingsError(std::string("--") + name + " needs a value");
      return args[++i];
    };
    bool known = false;
    for (const CliFlag& flag : cliFlags()) {
      if (name != flag.name || (flag.referenceOnly && kind != CommandKind::Reference)) continue;
      flag.apply(command, takeValue(*flag.valueName != '\0'));
      known = true;
    }
    for (const SettingOption& option : settingOptions()) {
      if (name != option.name) continue;
      option.parse(command.settings, takeValue(!option.valueName.empty()));
      known = true;
    }
    if (!known) throw SettingsError("unknown option '--" + name + "' (see headlight render --help)");
  }
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
  auto line = [&](std::string_view name, std::string_view value, std::string_view help) {
    std::string left = "  --";
    left += name;
    if (!value.empty()) (left += " ") += value;
    if (left.size() < 34) left.resize(34, ' ');
    else left += "\n" + std::string(34, ' ');
    out << left << help << "\n";
  };
  for (const CliFlag& flag : cliFlags())
    if (!flag.referenceOnly || kind == CommandKind::Reference) line(flag.name, flag.valueName, flag.help);
  out << "\nrender settings (also recorded in every EXR's metadata):\n";
  const RenderSettings defaults;
  for (const SettingOption& option : settingOptions())
    line(option.name, option.valueName,
         std::string(option.help) + (option.valueName.empty() ? "" : " [default: " + option.format(defaults) + "]"));
  return out.str();
}

}  // namespace headlight::cli

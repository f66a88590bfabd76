#include "cli_options.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <sstream>

#include "bench_command.hpp"
#include "headlight/error.hpp"
#include "headlight/scene_loader.hpp"
#include "headlight/targets.hpp"
#include "io/message_text.hpp"
#include "tune_command.hpp"

namespace headlight::cli {
namespace {

// --targets' help: every name it takes, from the target table.
std::string_view targetsHelp() {
  static const std::string help = [] {
    std::string names;
    for (std::string_view name : outputTargetNames()) (names += names.empty() ? "" : ",") += name;
    return "write only these (" + names + "); passes only other targets need are skipped";
  }();
  return help;
}

constexpr std::string_view kBackendNames[] = {"auto", "egl", "osmesa"};

std::string text(const OptionValue& value) { return std::get<std::string>(value); }

constexpr std::string_view kCameraModes[] = {"one", "all"};

// "I/N": shard I of N, 0 <= I < N.
void parseShard(RenderCommand& c, const std::string& value) {
  const auto slash = value.find('/');
  try {
    std::size_t usedIndex = 0, usedCount = 0;
    if (slash == std::string::npos) throw std::invalid_argument("no slash");
    const std::string index = value.substr(0, slash), count = value.substr(slash + 1);
    // Digits only: std::stoi would skip a leading space or sign (" 1/ 2", "+1/2").
    auto digits = [](const std::string& part) {
      return std::all_of(part.begin(), part.end(), [](unsigned char ch) { return std::isdigit(ch); });
    };
    if (!digits(index) || !digits(count) || count.empty()) throw std::invalid_argument("not digits");
    c.shardIndexOmitted = index.empty();
    c.shardIndex = index.empty() ? 0 : std::stoi(index, &usedIndex);
    c.shardCount = std::stoi(count, &usedCount);
    if (usedIndex != index.size() || usedCount != count.size()) throw std::invalid_argument("trailing text");
  } catch (const std::exception&) {
    throw SettingsError("--shard: expected I/N (shard I of N, counting from 0), got '" + value + "'");
  }
  if (c.shardCount < 1 || c.shardIndex < 0 || c.shardIndex >= c.shardCount)
    throw SettingsError("--shard " + value + ": expected 0 <= I < N");
}

// "X,Y,Z" (three finite numbers) for --eye, --target and --up.
glm::vec3 parsePoint(const std::string& flag, const std::string& value) {
  glm::vec3 point;
  std::size_t at = 0;
  for (int i = 0; i < 3; ++i) {
    const std::size_t comma = i < 2 ? value.find(',', at) : value.size();
    const std::string part = value.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
    float number = 0.0f;
    const auto [end, error] = std::from_chars(part.data(), part.data() + part.size(), number);
    if (comma == std::string::npos || part.empty() || error != std::errc() || end != part.data() + part.size() ||
        !std::isfinite(number))
      throw SettingsError("--" + flag + ": expected X,Y,Z (three finite numbers), got '" + value + "'");
    point[i] = number;
    at = comma + 1;
  }
  return point;
}

// An explicit camera: `render` and `reference` (which traces the pixels render draws).
std::vector<Option<RenderCommand>> cameraOptions() {
  using T = OptionType;
  using C = RenderCommand;
  return {
      actionOption<C>({.name = "eye",
                       .type = T::Text,
                       .help = "an explicit camera's position (with --target; as a job file's \"eye\")",
                       .valueName = "X,Y,Z"},
                      [](C& c, const OptionValue& v) { c.eye = parsePoint("eye", text(v)); }),
      actionOption<C>({.name = "target",
                       .type = T::Text,
                       .help = "the point an explicit camera looks at (with --eye)",
                       .valueName = "X,Y,Z"},
                      [](C& c, const OptionValue& v) { c.target = parsePoint("target", text(v)); }),
      actionOption<C>({.name = "up",
                       .type = T::Text,
                       .help = "an explicit camera's up direction (default 0,1,0)",
                       .valueName = "X,Y,Z"},
                      [](C& c, const OptionValue& v) { c.up = parsePoint("up", text(v)); }),
      actionOption<C>({.name = "fov",
                       .type = T::Float,
                       .help = "an explicit camera's vertical field of view in degrees (default 40)",
                       .minimum = 0.01,
                       .maximum = 179.99},
                      [](C& c, const OptionValue& v) { c.fovDegrees = float(std::get<double>(v)); }),
  };
}

std::vector<Option<RenderCommand>> batchOptions() {
  using T = OptionType;
  using C = RenderCommand;
  return {
      actionOption<C>({.name = "jobs",
                       .type = T::Text,
                       .help = "a job file: JSON Lines, one job per line (docs/BATCH.md); repeatable",
                       .valueName = "FILE"},
                      [](C& c, const OptionValue& v) { c.jobFiles.push_back(text(v)); }),
      bindOption<C>(
          {.name = "views",
           .type = T::Int,
           .help = "views per scene: on a turntable (--orbit), through an animation (--through-time), or both; "
                   "0: one view",
           .maximum = 100000},
          [](auto& c) -> auto& { return c.views; }),
      bindOption<C>(
          {.name = "orbit",
           .type = T::Switch,
           .help = "--views N cameras on a circle around the scene's bounds, looking at their centre"},
          [](auto& c) -> auto& { return c.orbit; }),
      bindOption<C>(
          {.name = "through-time",
           .type = T::Switch,
           .help = "--views N poses at N times through --animation (default 0): view k at k / N of its length"},
          [](auto& c) -> auto& { return c.throughTime; }),
      actionOption<C>({.name = "orbit-elevation",
                       .type = T::Float,
                       .help = "--orbit: degrees above the bounds' centre (default 14, a little from above)",
                       .minimum = -89,
                       .maximum = 89},
                      [](C& c, const OptionValue& v) { c.orbitElevationDegrees = float(std::get<double>(v)); }),
      actionOption<C>({.name = "orbit-distance",
                       .type = T::Float,
                       .help = "--orbit: times the distance that frames the bounds whole (default 1)",
                       .minimum = 0.1,
                       .maximum = 100},
                      [](C& c, const OptionValue& v) { c.orbitDistanceScale = float(std::get<double>(v)); }),
      actionOption<C>(
          {.name = "cameras",
           .type = T::Choice,
           .help = "one: the view the camera setting picks; all: one job per camera in the scene",
           .choices = kCameraModes},
          [](C& c, const OptionValue& v) { c.camerasAll = text(v) == "all"; },
          [](const C& c) { return OptionValue(std::string(c.camerasAll ? "all" : "one")); }),
      actionOption<C>({.name = "shard",
                       .type = T::Text,
                       .help = "render only jobs k with k % N == I (I from 0); with --shard-index-env, write /N",
                       .valueName = "I/N"},
                      [](C& c, const OptionValue& v) { parseShard(c, text(v)); }),
      actionOption<C>(
          {.name = "shard-index-env",
           .type = T::Text,
           .help = "read the shard index I from this environment variable (SLURM_ARRAY_TASK_ID, "
                   "JOB_COMPLETION_INDEX)",
           .valueName = "VAR"},
          [](C& c, const OptionValue& v) {
            if (text(v).empty()) throw SettingsError("--shard-index-env: expected the name of an environment variable");
            c.shardIndexEnv = text(v);
          },
          [](const C& c) { return OptionValue(c.shardIndexEnv); }),
      bindOption<C>(
          {.name = "wait",
           .type = T::Switch,
           .help = "when another render holds an output folder's lock, wait for it (default: fail at once)"},
          [](auto& c) -> auto& { return c.wait; }),
      actionOption<C>({.name = "wait-timeout",
                       .type = T::Float,
                       .help = "--wait: give up after this many seconds, naming the process that holds the folder "
                               "(default 600)",
                       .minimum = 0,
                       .maximum = 1e7},
                      [](C& c, const OptionValue& v) { c.waitSeconds = std::get<double>(v); }),
      bindOption<C>(
          {.name = "force",
           .type = T::Switch,
           .help = "replace files with a target's name (lit.exr, frame.json, ...) that no earlier Headlight set in "
                   "the folder wrote"},
          [](auto& c) -> auto& { return c.force; }),
      bindOption<C>(
          {.name = "resume",
           .type = T::Switch,
           .help = "skip a job whose folder holds a complete set (frame.json) of the same job hash"},
          [](auto& c) -> auto& { return c.resume; }),
      actionOption<C>({.name = "targets", .type = T::Text, .help = targetsHelp(), .valueName = "LIST"},
                      [](C& c, const OptionValue& v) {
                        c.output.targets = detail::splitList("targets", text(v));
                        const auto names = outputTargetNames();
                        for (const std::string& name : c.output.targets)
                          if (std::find(names.begin(), names.end(), name) == names.end()) {
                            std::string known;
                            for (std::string_view target : names)
                              known += (known.empty() ? "" : ", ") + std::string(target);
                            throw SettingsError("--targets: unknown target " + quotedName(name) + " (known: " + known +
                                                ")");
                          }
                        if (c.output.targets.empty()) throw SettingsError("--targets: expected a list of targets");
                      }),
      actionOption<C>({.name = "png",
                       .type = T::Text,
                       .help = "also write these targets as <target>.png, as a person looks at them: normal as "
                               "colours, depth through viridis (near yellow), ssgi's AO as grey, albedo and "
                               "material as they are, lit and emissive tone mapped (docs/PIPELINE.md, \"PNG "
                               "targets\")",
                       .valueName = "LIST"},
                      [](C& c, const OptionValue& v) {
                        c.output.pngTargets = detail::splitList("png", text(v));
                        for (const std::string& name : c.output.pngTargets)
                          if (!findFrameTarget(name)) {
                            std::string known;
                            for (const FrameTarget& target : frameTargets())
                              known += (known.empty() ? "" : ", ") + std::string(target.name);
                            throw SettingsError("--png: unknown target " + quotedName(name) + " (known: " + known +
                                                "; preview.png is always written)");
                          }
                        if (c.output.pngTargets.empty()) throw SettingsError("--png: expected a list of targets");
                      }),
      actionOption<C>(
          {.name = "exr-compression",
           .type = T::Choice,
           .help = "OpenEXR's lossless compression (docs/BENCHMARKS.md measures each)",
           .choices = exrCompressionNames()},
          [](C& c, const OptionValue& v) {
            const auto names = exrCompressionNames();
            c.output.compression = ExrCompression(std::find(names.begin(), names.end(), text(v)) - names.begin());
          },
          [](const C& c) { return OptionValue(std::string(exrCompressionName(c.output.compression))); }),
      actionOption<C>({.name = "clamp-nonfinite",
                       .type = T::Switch,
                       .help = "write NaN as 0 and inf as the largest finite value, counting them (default: "
                               "a target with NaN or inf is an error)"},
                      [](C& c, const OptionValue&) { c.output.nonFinite = NonFinitePolicy::Clamp; }),
      bindOption<C>(
          {.name = "json",
           .type = T::Switch,
           .help = "print one JSON summary (jobs, files, pass times, failures) instead of the lines"},
          [](auto& c) -> auto& { return c.json; }),
  };
}

std::vector<Option<RenderCommand>> renderCommandOptions(CommandKind kind) {
  using T = OptionType;
  using C = RenderCommand;
  std::vector<Option<C>> rows =
      commonCommandOptions<C>(kind == CommandKind::Render ? kVerboseHelpRender : kVerboseHelpReference);
  rows.push_back(actionOption<C>({.name = "preset",
                                  .type = T::Choice,
                                  .help = "named settings; flags after it override it",
                                  .choices = presetNames()},
                                 [](C& c, const OptionValue& v) { applyPreset(c.settings, text(v)); }));
  rows.push_back(settingsFileOption<C>(&C::settings));
  for (auto& row : sceneInputOptions<C>()) rows.push_back(std::move(row));
  if (kind == CommandKind::Reference) {
    for (auto& row : liftOptions(referenceOptions(), &C::reference)) rows.push_back(std::move(row));
    rows.push_back(bindOption<C>(
        {.name = "force",
         .type = T::Switch,
         .help = "replace ao_ref.exr, indirect_ref.exr or lit_ref.exr files in --out that no "
                 "earlier headlight reference wrote"},
        [](auto& c) -> auto& { return c.force; }));
  }
  for (auto& row : cameraOptions()) rows.push_back(std::move(row));
  if (kind == CommandKind::Render)
    for (auto& row : batchOptions()) rows.push_back(std::move(row));
  for (auto& row : liftOptions(settingOptions(), &C::settings)) rows.push_back(std::move(row));
  return rows;
}

}  // namespace

bool namesImageFile(const std::filesystem::path& path) {
  std::string extension = path.extension().string();
  for (char& letter : extension) letter = char(std::tolower(static_cast<unsigned char>(letter)));
  for (std::string_view image : {".png", ".exr", ".jpg", ".jpeg", ".tif", ".tiff", ".hdr", ".webp"})
    if (extension == image) return true;
  return false;
}

template <class Command>
std::vector<Option<Command>> commonCommandOptions(std::string_view verboseHelp) {
  using T = OptionType;
  using C = Command;
  return {
      actionOption<C>(
          {.name = "out", .type = T::Text, .help = "folder for the output files", .valueName = "DIR"},
          [](C& c, const OptionValue& v) {
            const std::string& folder = std::get<std::string>(v);
            // F3D's --output names an image; ours names a folder: x.png would become a folder called x.png.
            if (namesImageFile(folder) && !std::filesystem::is_directory(folder))
              throw SettingsError("--out " + folder +
                                  ": --out is a folder (the images are written inside it as "
                                  "lit.exr, preview.png, ...), and this names an image file; name a folder, e.g. "
                                  "--out " +
                                  std::filesystem::path(folder).replace_extension().string());
            c.outDir = folder;
          },
          [](const C& c) { return OptionValue(c.outDir); }),
      actionOption<C>(
          {.name = "backend",
           .type = T::Choice,
           .help = "headless GL backend (auto: EGL, then OSMesa)",
           .choices = kBackendNames},
          [](C& c, const OptionValue& v) { c.context.backend = parseBackend(text(v)); },
          [](const C& c) { return OptionValue(std::string(backendName(c.context.backend))); }),
      actionOption<C>({.name = "device",
                       .type = T::Text,
                       .help = "EGL device: an index (EGL_EXT_device_enumeration) or a name (DRM or render node "
                               "file, driver, renderer or extension, e.g. EGL_MESA_device_software); auto: the "
                               "first that works",
                       .valueName = "auto|N|NAME"},
                      [](C& c, const OptionValue& v) {
                        const std::string& device = std::get<std::string>(v);
                        int index = 0;
                        const auto [end, error] = std::from_chars(device.data(), device.data() + device.size(), index);
                        if (device == "auto") {
                          c.context.eglDevice = -1;
                          c.context.eglDeviceName.clear();
                        } else if (error == std::errc() && end == device.data() + device.size() && index >= 0) {
                          c.context.eglDevice = index;
                        } else {
                          c.context.eglDeviceName = device;
                        }
                      }),
      actionOption<C>({.name = "device-fallback",
                       .type = T::Switch,
                       .help = "if the --device asked for cannot be used, render on another (the surfaceless "
                               "platform, then OSMesa with --backend auto) instead of failing"},
                      [](C& c, const OptionValue&) { c.context.deviceFallback = true; }),
      actionOption<C>({.name = "strict", .type = T::Switch, .help = "treat OpenGL errors as fatal (default: warn)"},
                      [](C& c, const OptionValue&) { c.context.errorPolicy = GlErrorPolicy::Throw; }),
      actionOption<C>({.name = "quiet", .type = T::Switch, .help = "print nothing but errors"},
                      [](C& c, const OptionValue&) { c.verbosity = Verbosity::Quiet; }),
      actionOption<C>({.name = "verbose", .type = T::Switch, .help = verboseHelp},
                      [](C& c, const OptionValue&) { c.verbosity = Verbosity::Verbose; }),
      bindOption<C>(
          {.name = "help", .type = T::Switch, .help = "this help"}, [](auto& c) -> auto& { return c.help; }),
  };
}
template std::vector<Option<RenderCommand>> commonCommandOptions<RenderCommand>(std::string_view);
template std::vector<Option<BenchCommand>> commonCommandOptions<BenchCommand>(std::string_view);
template std::vector<Option<TuneCommand>> commonCommandOptions<TuneCommand>(std::string_view);

RenderCommand parseRenderArgs(const std::vector<std::string>& args, CommandKind kind) {
  RenderCommand command;
  command.context.errorPolicy = GlErrorPolicy::Warn;
  const auto options = renderCommandOptions(kind);
  const std::vector<std::string> scenes =
      parseCommandLine<RenderCommand>(args, options, command, kind == CommandKind::Render ? "render" : "reference");
  if (kind == CommandKind::Reference && scenes.size() > 1)
    throw SettingsError("more than one scene given: '" + scenes[0] + "' and '" + scenes[1] + "'");
  if (!scenes.empty()) command.scene = scenes[0];
  // A .jsonl positional is a job file, the rest are scenes.
  for (const std::string& scene : scenes)
    if (scene.size() > 6 && scene.compare(scene.size() - 6, 6, ".jsonl") == 0)
      command.jobFiles.push_back(scene);
    else
      command.scenes.push_back(scene);
  if (command.views > 0 && !command.orbit && !command.throughTime)
    throw SettingsError("--views " + std::to_string(command.views) +
                        ": needs --orbit (cameras on a turntable) or --through-time (poses through an animation)");
  if (command.orbit && command.views == 0) throw SettingsError("--orbit: needs --views N");
  if (command.throughTime && command.views == 0) throw SettingsError("--through-time: needs --views N");
  if (command.throughTime && command.sceneLoad.animationTime)
    throw SettingsError("--through-time and --time: choose one (the views' times are k / N of the animation)");
  if (!command.orbit && (command.orbitElevationDegrees || command.orbitDistanceScale))
    throw SettingsError("--orbit-elevation and --orbit-distance: need --views N --orbit");
  if (command.orbit && command.camerasAll) throw SettingsError("--orbit and --cameras all: choose one");
  if (command.eye.has_value() != command.target.has_value())
    throw SettingsError(command.eye ? "--eye: needs --target X,Y,Z" : "--target: needs --eye X,Y,Z");
  if (!command.eye && (command.up || command.fovDegrees))
    throw SettingsError("--up and --fov: need --eye and --target");
  if (command.eye) {
    if (command.orbit || command.camerasAll || command.settings.camera)
      throw SettingsError("--eye/--target and " +
                          std::string(command.orbit        ? "--orbit"
                                      : command.camerasAll ? "--cameras all"
                                                           : "--camera") +
                          ": choose one way to place the camera");
    if (*command.eye == *command.target) throw SettingsError("--eye and --target are the same point");
    if (glm::length(glm::cross(*command.target - *command.eye, command.up.value_or(glm::vec3(0, 1, 0)))) <= 0.0f)
      throw SettingsError("--up is parallel to the view direction (from --eye to --target)");
  }
  if (command.shardIndexOmitted && command.shardIndexEnv.empty())
    throw SettingsError("--shard /" + std::to_string(command.shardCount) +
                        ": no shard index; give --shard I/N or --shard-index-env VAR");
  if (!command.shardIndexOmitted && !command.shardIndexEnv.empty() && command.shardIndex != 0)
    throw SettingsError("--shard " + std::to_string(command.shardIndex) + "/" + std::to_string(command.shardCount) +
                        " and --shard-index-env " + command.shardIndexEnv + ": give the index one way");
  return command;
}

std::string renderHelp(CommandKind kind) {
  std::ostringstream out;
  if (kind == CommandKind::Render)
    out << "usage: headlight render [SCENE...] [JOBS.jsonl...] [options]\n\n"
           "Renders SCENE (a .gltf/.glb file or builtin:NAME; default builtin:cornell) and writes\n"
           "position, normal, albedo, material, depth, [emissive], ssgi and lit .exr, preview.png and\n"
           "frame.json (the set's manifest, written last) into the output folder, printing one line per file.\n"
           "Several scenes, --views N --orbit, --cameras all and job files make a batch: one process, one\n"
           "GL context, each scene loaded once; each job writes into <out>/<scene>[/view_NNN|/camera_N]\n"
           "(job files name their own folders). A failed job is reported with its line and the others go\n"
           "on; the exit code is then 1. docs/BATCH.md has job files, sharding and --resume.\n\n";
  else
    out << "usage: headlight reference [SCENE] [options]\n\n"
           "Ray-traces (Embree) the ground truth for SCENE at the pixels `render` would draw with the same\n"
           "options, and writes ao_ref.exr, indirect_ref.exr and lit_ref.exr into the output folder\n"
           "(docs/ACCURACY.md defines them).\n\n";
  out << "Built-in scenes:";
  for (const std::string& name : builtinSceneNames()) out << " builtin:" << name;
  out << "\n\nExit codes: 0 ok, 1 runtime error (scene, GL, I/O, NaN/inf in a target; in a batch: any job "
         "failed), 2 usage error.\n\n";
  RenderCommand defaults;
  defaults.context.errorPolicy = GlErrorPolicy::Warn;
  out << commandOptionsHelp(renderCommandOptions(kind), defaults,
                            "render settings (also recorded in every EXR's metadata as headlight:setting:NAME)");
  return out.str();
}

}  // namespace headlight::cli

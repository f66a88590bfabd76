#pragma once
// What every command that renders a scene sets up the same way (render,
// reference, bench, tune): the flags that say how a scene may be loaded
// (--allow-external-paths and the resource limits), the scene load itself,
// the --verbose header, and atomic text writes. Written once here, so that a
// scene one command refuses, every command refuses with the same message.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

#include "headlight/context.hpp"
#include "headlight/limits.hpp"
#include "headlight/renderer.hpp"
#include "headlight/scene.hpp"
#include "headlight/scene_loader.hpp"
#include "settings/option_binding.hpp"

namespace headlight {

// --allow-external-paths, the scene-load rows (--strict-gltf, --scene) and
// the limit rows (--max-memory, ...), bound to a command's `sceneLoad` and
// `limits` members.
template <class Command>
std::vector<Option<Command>> sceneInputOptions() {
  std::vector<Option<Command>> rows;
  rows.push_back(bindOption<Command>(
      {.name = "allow-external-paths",
       .type = OptionType::Switch,
       .help = "let glTF URIs point outside the scene file's folder"},
      [](auto& c) -> auto& { return c.sceneLoad.allowExternalPaths; }));
  for (auto& row : liftOptions(sceneLoadOptions(), &Command::sceneLoad)) rows.push_back(std::move(row));
  for (auto& row : liftOptions(limitOptions(), &Command::limits)) rows.push_back(std::move(row));
  return rows;
}

// loadScene with the command's load options and limits; then, unless
// `quiet`, one "warning: FILE: ..." line on stderr per glTF feature the file
// uses that is not rendered (Scene::ignored).
Scene loadCommandScene(const std::string& nameOrPath, const SceneLoadOptions& options, const ResourceLimits& limits,
                       bool quiet);

// --verbose's header: what each context attempt said, the backend, GL_RENDERER
// and GL_VERSION, and the scene's size. Lines end in '\n'.
std::string verboseHeader(const Context& context, const Scene& scene);

// A text file written under a temporary name and renamed into place (the
// library's atomic writer): never half-written under `path`. Throws IoError.
void writeTextFile(const std::filesystem::path& path, std::string_view text);

}  // namespace headlight

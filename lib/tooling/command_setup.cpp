#include "tooling/command_setup.hpp"

#include <cstdio>

#include "headlight/scene_loader.hpp"
#include "io/atomic_file.hpp"
#include "tooling/large_pages.hpp"

namespace headlight {

Scene loadCommandScene(const std::string& nameOrPath, const SceneLoadOptions& options, const ResourceLimits& limits,
                       bool quiet) {
  Scene scene = loadScene(nameOrPath, options, limits);
  if (!quiet)
    for (const IgnoredFeature& feature : scene.ignored)
      std::fprintf(stderr, "warning: %s: %s\n", scene.source.c_str(), feature.describe().c_str());
  return scene;
}

std::string verboseHeader(const Context& context, const Scene& scene) {
  std::string text;
  for (const std::string& attempt : context.attempts()) text += "context: " + attempt + "\n";
  text += "backend: " + std::string(backendName(context.backend())) + " (" + context.description() + ")\n";
  text += "GL_RENDERER: " + context.renderer() + "\nGL_VERSION: " + context.version() + "\n";
  text += largePagesNote() + "\n";
  text += "scene: " + scene.source + ": " + std::to_string(scene.instances.size()) + " instances, " +
          std::to_string(scene.triangleCount()) + " triangles, " + std::to_string(scene.lights.size()) + " lights, " +
          std::to_string(scene.cameras.size()) + " cameras\n";
  if (!scene.materialVariants.empty()) {
    text += "material variants (--material-variant; default: the file's default materials):";
    for (const std::string& name : scene.materialVariants) text += " '" + name + "'";
    text += "\n";
  }
  if (!scene.animations.empty()) {
    text += "animations (--animation N|NAME --time SECONDS; default: the static pose):";
    for (std::size_t i = 0; i < scene.animations.size(); ++i) {
      char end[32];
      std::snprintf(end, sizeof end, "%g", double(scene.animations[i].end));
      text += (i == 0 ? " " : ", ") + std::to_string(i) +
              (scene.animations[i].name.empty() ? "" : " '" + scene.animations[i].name + "'") + " (0.." + end + " s)";
    }
    text += "\n";
  }
  return text;
}

void writeTextFile(const std::filesystem::path& path, std::string_view text) {
  detail::writeTextAtomically(path, text);
}

}  // namespace headlight

// SceneLoadOptions' rows in the one options table (headlight/options.hpp):
// the CLI's --strict-gltf, --scene, --material-variant, --animation and --time, and settings files, read them.
#include "headlight/scene_loader.hpp"
#include "settings/option_binding.hpp"

namespace headlight {

std::span<const Option<SceneLoadOptions>> sceneLoadOptions() {
  using T = OptionType;
  using O = SceneLoadOptions;
  static const Option<O> rows[] = {
      bindOption<O>(
          {.name = "strict-gltf",
           .type = T::Switch,
           .help = "refuse a glTF file that uses a feature Headlight does not render (default: warn, "
                   "naming each)"},
          [](auto& o) -> auto& { return o.strictGltf; }),
      bindOption<O>(
          {.name = "scene",
           .type = T::Text,
           .help = "which of the glTF file's scenes to render: an index or a name (default: the file's "
                   "`scene`, else 0)",
           .valueName = "N|NAME"},
          [](auto& o) -> auto& { return o.gltfScene; }),
      bindOption<O>(
          {.name = "environment",
           .type = T::Text,
           .help = "an equirectangular HDR image (.hdr, .exr; width = 2 x height) that lights the scene "
                   "and shows behind it instead of the procedural sky",
           .valueName = "FILE"},
          [](auto& o) -> auto& { return o.environment; }),
      bindOption<O>(
          {.name = "material-variant",
           .type = T::Text,
           .help = "the glTF file's KHR_materials_variants variant to draw (default: the file's default "
                   "materials; --verbose lists the variants)",
           .valueName = "NAME"},
          [](auto& o) -> auto& { return o.materialVariant; }),
      bindOption<O>(
          {.name = "animation",
           .type = T::Text,
           .help = "pose the glTF file by this animation (an index or a name; --verbose lists them) at "
                   "--time: node transforms, morph weights and skins (default: the static pose)",
           .valueName = "N|NAME"},
          [](auto& o) -> auto& { return o.animation; }),
      bindOption<O>(
          {.name = "time",
           .type = T::Float,
           .help = "seconds into --animation to pose the file at (before its first keyframe the first "
                   "holds, after its last the last)",
           .minimum = -1e7,
           .maximum = 1e7,
           .autoMeaning = "0 with --animation, else the static pose; a time alone plays animation 0"},
          [](auto& o) -> auto& { return o.animationTime; }),
  };
  return rows;
}

}  // namespace headlight

#pragma once
// Turning a scene name into a Scene: glTF 2.0 files (.gltf, .glb) through
// tinygltf, and the built-in scenes by name ("builtin:cornell").
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "headlight/export.hpp"
#include "headlight/limits.hpp"
#include "headlight/options.hpp"
#include "headlight/scene.hpp"

namespace headlight HEADLIGHT_PUBLIC {

struct SceneLoadOptions {
  // glTF URIs that resolve outside the asset's folder (../x.bin, /etc/x.png)
  // are refused unless this is set.
  bool allowExternalPaths = false;
  // A glTF feature the file uses that is not rendered (Scene::ignored) is a
  // SceneError naming all of them, instead of a warning.
  bool strictGltf = false;
  // Which of the file's scenes: an index or a name; empty: the file's
  // `scene` (else scene 0).
  std::string gltfScene;
  // An equirectangular .hdr or .exr (width = 2 x height) that lights the
  // scene and shows as its background instead of the procedural sky; empty:
  // none. Read by loadEnvironmentMap into Scene::environment.
  std::string environment;
  // KHR_materials_variants: the variant whose materials the primitives take;
  // empty: the file's default materials. A name the file lacks is a SceneError.
  std::string materialVariant;
  // An animation to pose the file by (glTF 2.0 §3.11): an index or a name;
  // empty: the static pose, unless animationTime is set (then animation 0).
  // Node transforms, morph weights and the skins that follow the joints are
  // posed at animationTime seconds (unset: 0); a name the file lacks is a
  // SceneError naming its animations.
  std::string animation;
  std::optional<float> animationTime;
};

// The rows (strict-gltf, scene, environment, material-variant, animation, time), for the CLI and settings files.
std::span<const Option<SceneLoadOptions>> sceneLoadOptions();

// "builtin:<name>" makes a built-in scene; anything else is read as a glTF
// file. Throws SceneError naming the file, the element and the problem.
// `limits` caps what the file may make the loader allocate (instances,
// triangles, texels, memory); exceeding one throws LimitError.
Scene loadScene(const std::string& nameOrPath, const SceneLoadOptions& options = {}, const ResourceLimits& limits = {});

// Reads an equirectangular environment map (.hdr, .exr: what OpenImageIO
// reads) as linear RGB. Only a regular file is opened; its header's size is
// checked (width = 2 x height, at most 16384 wide, the decoded size within
// limits.maxMemoryMiB) before any pixel is decoded, then every value must be
// finite and >= 0. Throws IoError (missing, not a regular file), LimitError
// (max-memory) or SceneError (unreadable, truncated, not 2:1, a bad value),
// each naming the file and the value.
std::shared_ptr<const EnvironmentMap> loadEnvironmentMap(const std::filesystem::path& path,
                                                         const ResourceLimits& limits = {});

// Reads a .gltf or .glb file. Every accessor, bufferView, index and image is
// validated before it is read, the JSON's structure before anything is
// decoded, and images last. Throws SceneError, or LimitError for a file that
// asks for more than `limits` allow.
Scene loadGltf(const std::filesystem::path& path, const SceneLoadOptions& options = {},
               const ResourceLimits& limits = {});

// The built-in scenes: "cornell" (the default) and "spheres". Throws
// SceneError for an unknown name, listing the known ones.
Scene makeBuiltinScene(std::string_view name);
std::vector<std::string> builtinSceneNames();

// Fills Primitive::normals with area-weighted vertex normals from the
// triangles (used when a file has none). Degenerate triangles add nothing; a
// vertex no triangle touches gets +Z.
void generateNormals(Primitive& primitive);

// Fills Primitive::tangents (which must be empty) from the normals and
// TEXCOORD_0 by MikkTSpace's rules (lib/scene/tangents.cpp): per-corner UV
// tangents projected onto the normal, angle-weighted, summed over corners
// that share position, normal, UV and handedness; w = handedness. A vertex
// used with both handednesses is split (positions, normals and texcoords
// grow, indices are remapped). Does nothing without normals and texcoords.
void generateTangents(Primitive& primitive);
// The same from the set `normalMap` samples (TEXCOORD_1 for texCoord 1) as
// its KHR_texture_transform maps it, so the tangent space follows the UVs
// the normal map is read at. Does nothing without normals and that set.
void generateTangents(Primitive& primitive, const TextureRef& normalMap);

}  // namespace HEADLIGHT_PUBLIC

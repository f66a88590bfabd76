// glTF 2.0 (.gltf, .glb) to Scene, through tinygltf for the JSON and the
// buffers and OpenImageIO (in the image module) for the images.
//
// The parts, one job each: gltf_prescan (the raw JSON, before tinygltf),
// gltf_files (the file sandbox), gltf_accessors (validated accessors),
// gltf_geometry (primitives), gltf_materials (materials and images),
// gltf_nodes (the node walk, cameras, lights), gltf_features (what is not
// rendered, named). This file puts them in order:
// structure first, images last, so a file that is refused is refused before
// any image is decoded.
#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include "gltf/animation_pose.hpp"
#include "gltf/draco.hpp"
#include "gltf/features.hpp"
#include "gltf/files.hpp"
#include "gltf/geometry.hpp"
#include "gltf/image_based_light.hpp"
#include "gltf/materials.hpp"
#include "gltf/meshopt.hpp"
#include "gltf/nodes.hpp"
#include "gltf/pose.hpp"
#include "gltf/prescan.hpp"
#include "gltf/stand_ins.hpp"
#include "gltf/texture_sources.hpp"
#include "gltf/variants.hpp"
#include "headlight/error.hpp"
#include "headlight/limits.hpp"
#include "headlight/scene_loader.hpp"
#include "io/fingerprint.hpp"
#include "scene/material_textures.hpp"

namespace headlight {

namespace fs = std::filesystem;

namespace {

using gltf::attributeAccessor;

constexpr std::string_view kBuiltinPrefix = "builtin:";

std::string lowercase(std::string text) {
  std::transform(text.begin(), text.end(), text.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return text;
}

// Key of a primitive's geometry: its POSITION, NORMAL, TEXCOORD_0, TANGENT,
// COLOR_0 and indices accessors, its mode, the pose (morph weights, skin) it is
// drawn in, and its TEXCOORD_1 accessor when its material samples that set
// (else -1: not decoded). Primitives with equal keys share decoding work.
using GeometryKey = std::tuple<int, int, int, int, int, int, int, std::vector<float>, int, int>;
// A mesh as one node draws it: mesh, morph weights, skin.
using MeshKey = std::tuple<int, std::vector<float>, int>;

class GltfReader {
 public:
  GltfReader(const gltf::Source& source, Scene& scene, const ResourceLimits& limits)
      : source_(source), model_(source.model), scene_(scene), limits_(limits), geometry_(source, limits) {}

  // Everything but the images, which loadGltf decodes last.
  void read(int sceneIndex) {
    for (std::size_t material = 0; material < model_.materials.size(); ++material) {
      scene_.materials.push_back(gltf::readMaterial(source_, static_cast<int>(material)));
    }
    // The ids target's tables: every mesh and mesh primitive of the file,
    // so that an id is the file's index + 1 (primitives numbered mesh by mesh).
    for (std::size_t mesh = 0; mesh < model_.meshes.size(); ++mesh) {
      firstMeshPrimitive_.push_back(int(scene_.meshPrimitiveNames.size()));
      scene_.meshNames.push_back({model_.meshes[mesh].name, int(mesh), -1});
      for (std::size_t primitive = 0; primitive < model_.meshes[mesh].primitives.size(); ++primitive)
        scene_.meshPrimitiveNames.push_back({"", int(mesh), int(primitive)});
    }
    lights_ = gltf::punctualLights(model_);
    const gltf::NodeWalk walk(source_);
    walk_ = &walk;
    for (int root : walk.rootNodes(sceneIndex)) {
      walk.traverse(root, [this](int node, const glm::mat4& worldFromNode) { visit(node, worldFromNode); });
    }
    walk_ = nullptr;
  }

 private:
  // Every texture reference a material samples: the rows of
  // materialTextureRows() whose reference it has and that are present.
  static std::vector<const TextureRef*> sampledTextures(const Material& m) {
    std::vector<const TextureRef*> refs;
    for (const MaterialTextureRow& row : materialTextureRows()) {
      if (const TextureRef* ref = row.ref(m); ref != nullptr && ref->present()) refs.push_back(ref);
    }
    return refs;
  }

  bool materialHasTextures(int material) const {
    if (material < 0) {
      return false;
    }
    return !sampledTextures(scene_.materials[static_cast<std::size_t>(material)]).empty();
  }

  bool materialSamplesTexcoord1(int material) const {
    if (material < 0) {
      return false;
    }
    for (const TextureRef* ref : sampledTextures(scene_.materials[static_cast<std::size_t>(material)])) {
      if (ref->texCoord == 1) return true;
    }
    return false;
  }

  // The geometry of a glTF primitive (decoded once per distinct set of
  // accessors) and the material it is drawn with.
  struct PlacedPrimitive {
    int geometry;
    int material;
  };

  PlacedPrimitive addPrimitive(int meshIndex, int primitiveIndex, const gltf::Pose& pose, int skin) {
    const tinygltf::Primitive& source =
        model_.meshes[static_cast<std::size_t>(meshIndex)].primitives[static_cast<std::size_t>(primitiveIndex)];
    const std::string primitiveName =
        "mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primitiveIndex);
    if (source.material != -1) {
      source_.checkIndex(source.material, model_.materials, primitiveName, "material");
    }
    const bool readsTexcoord1 = materialSamplesTexcoord1(source.material);
    const GeometryKey key{attributeAccessor(source, "POSITION"),
                          attributeAccessor(source, "NORMAL"),
                          attributeAccessor(source, "TEXCOORD_0"),
                          attributeAccessor(source, "TANGENT"),
                          attributeAccessor(source, "COLOR_0"),
                          source.indices,
                          source.mode,
                          pose.weights,
                          skin,
                          readsTexcoord1 ? attributeAccessor(source, "TEXCOORD_1") : -1};
    // Files often repeat one geometry under many materials (one mesh per
    // material); it is decoded and stored once, and each use is an instance.
    auto [cached, inserted] = geometryCache_.try_emplace(key, static_cast<int>(scene_.primitives.size()));
    if (inserted) {
      scene_.primitives.push_back(geometry_.read(source, primitiveName, pose, readsTexcoord1));
    }
    Primitive& primitive = scene_.primitives[static_cast<std::size_t>(cached->second)];
    // A normal map needs tangents; without TANGENT they are made as
    // MikkTSpace makes them (the glTF spec's rule for missing tangents),
    // from the UVs the normal map samples (its set, through its transform).
    if (primitive.mode == PrimitiveMode::Triangles && primitive.tangents.empty() && source.material >= 0) {
      const Material& material = scene_.materials[static_cast<std::size_t>(source.material)];
      if (material.normalTexture.present()) generateTangents(primitive, material.normalTexture);
      // KHR_materials_anisotropy's direction is in the same tangent space.
      else if (material.anisotropy)
        generateTangents(primitive);
    }
    // A textured material samples UVs; without the set it names it samples
    // (0, 0), which is glTF's answer too, so the shader always has texcoords
    // to read.
    if (primitive.texcoords.empty() && materialHasTextures(source.material)) {
      primitive.texcoords.assign(primitive.positions.size(), glm::vec2(0.0f));
    }
    if (primitive.texcoords1.empty() && readsTexcoord1) {
      primitive.texcoords1.assign(primitive.positions.size(), glm::vec2(0.0f));
    }
    return {cached->second, source.material};
  }

  // A mesh's primitives are added once per pose, however many nodes use it.
  const std::vector<PlacedPrimitive>& meshPrimitives(int meshIndex, int nodeIndex) {
    const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(nodeIndex)];
    gltf::Pose pose{gltf::morphWeights(source_, nodeIndex, meshIndex), nullptr};
    const int skin = node.skin;
    if (skin >= 0) {
      source_.checkIndex(skin, model_.skins, "node " + std::to_string(nodeIndex), "skin");
      auto [joints, fresh] = jointCache_.try_emplace(skin);
      if (fresh) {
        joints->second = gltf::jointMatrices(geometry_.accessors(), *walk_, skin);
      }
      pose.joints = &joints->second;
    }
    auto [entry, inserted] = meshCache_.try_emplace(MeshKey{meshIndex, pose.weights, skin});
    if (inserted) {
      const tinygltf::Mesh& mesh = model_.meshes[static_cast<std::size_t>(meshIndex)];
      for (std::size_t primitive = 0; primitive < mesh.primitives.size(); ++primitive) {
        const int mode = mesh.primitives[primitive].mode;
        if (mode < TINYGLTF_MODE_POINTS || mode > TINYGLTF_MODE_TRIANGLE_FAN) {
          source_.fail("mesh " + std::to_string(meshIndex) + " primitive " + std::to_string(primitive) + " has mode " +
                       std::to_string(mode) + ", expected 0..6");
        }
        entry->second.push_back(addPrimitive(meshIndex, static_cast<int>(primitive), pose, skin));
      }
    }
    return entry->second;
  }

  void visit(int nodeIndex, const glm::mat4& worldFromNode) {
    const tinygltf::Node& node = model_.nodes[static_cast<std::size_t>(nodeIndex)];
    const std::string nodeName = "node " + std::to_string(nodeIndex);
    if (node.mesh >= 0) {
      source_.checkIndex(node.mesh, model_.meshes, nodeName, "mesh");
      const std::vector<PlacedPrimitive>& placedPrimitives = meshPrimitives(node.mesh, nodeIndex);
      // A skinned mesh is posed in world space: glTF ignores its node's transform.
      const glm::mat4 worldFromMesh = node.skin >= 0 ? glm::mat4(1.0f) : worldFromNode;
      // Checked before the placements are read (instanceTransforms calls it with each attribute's count).
      const auto checkInstances = [&](std::size_t placementCount) {
        const std::uint64_t added = static_cast<std::uint64_t>(placedPrimitives.size()) * placementCount;
        if (scene_.instances.size() + added > static_cast<std::uint64_t>(limits_.maxInstances)) {
          source_.failLimit(nodeName + " places mesh " + std::to_string(node.mesh) + " as instance " +
                                std::to_string(scene_.instances.size() + added) + ", more than max-instances " +
                                std::to_string(limits_.maxInstances) + "; raise max-instances",
                            "max-instances");
        }
      };
      std::vector<glm::mat4> placements =
          gltf::instanceTransforms(geometry_.accessors(), source_, nodeIndex, checkInstances);
      const bool copies = !placements.empty();  // EXT_mesh_gpu_instancing: each copy is a mesh instance
      if (placements.empty()) {
        placements.push_back(glm::mat4(1.0f));
      }
      checkInstances(placements.size());
      for (std::size_t copy = 0; copy < placements.size(); ++copy) {
        const glm::mat4 worldFromLocal = worldFromMesh * placements[copy];
        const int meshInstance = int(scene_.meshInstanceNames.size());
        scene_.meshInstanceNames.push_back({node.name, nodeIndex, copies ? int(copy) : -1});
        for (int column = 0; column < 4; ++column) {
          if (!(glm::all(glm::lessThanEqual(glm::abs(worldFromLocal[column]), glm::vec4(kMaxWorldMagnitude))))) {
            source_.fail(nodeName + " EXT_mesh_gpu_instancing places an instance beyond magnitude " +
                         std::to_string(static_cast<long long>(kMaxWorldMagnitude)));
          }
        }
        for (std::size_t primitive = 0; primitive < placedPrimitives.size(); ++primitive)
          scene_.instances.push_back({placedPrimitives[primitive].geometry, worldFromLocal,
                                      placedPrimitives[primitive].material, meshInstance, node.mesh,
                                      firstMeshPrimitive_[std::size_t(node.mesh)] + int(primitive)});
      }
    }
    if (node.camera >= 0) {
      source_.checkIndex(node.camera, model_.cameras, nodeName, "camera");
      scene_.cameras.push_back(gltf::readCamera(source_, node.camera, worldFromNode, nodeName));
    }
    if (const int light = gltf::nodeLight(source_, node, nodeName, lights_); light >= 0) {
      // Before the next is placed: a light listed once can be placed by any number of nodes.
      if (scene_.lights.size() >= static_cast<std::uint64_t>(limits_.maxLights))
        source_.failLimit(nodeName + " places light " + std::to_string(light) + ", one more than the " +
                              std::to_string(limits_.maxLights) +
                              " punctual lights max-lights allows (each is evaluated at every pixel of every "
                              "view); raise max-lights",
                          "max-lights");
      scene_.lights.push_back(
          gltf::readLight(source_, lights_[static_cast<std::size_t>(light)], light, worldFromNode, nodeName));
    }
  }

  const gltf::Source& source_;
  const tinygltf::Model& model_;
  Scene& scene_;
  ResourceLimits limits_;
  gltf::GeometryReader geometry_;
  std::vector<tinygltf::Light> lights_;
  const gltf::NodeWalk* walk_ = nullptr;  // during read()
  std::map<int, std::vector<glm::mat4>> jointCache_;
  std::map<MeshKey, std::vector<PlacedPrimitive>> meshCache_;
  std::map<GeometryKey, int> geometryCache_;
  std::vector<int> firstMeshPrimitive_;  // per glTF mesh: its first primitive's index in Scene::meshPrimitiveNames
};

// --scene: an index, or the name of one of the file's scenes; -1 when not given.
int sceneIndex(const gltf::Source& source, const std::string& chosen) {
  if (chosen.empty()) {
    return -1;
  }
  const auto& scenes = source.model.scenes;
  for (std::size_t index = 0; index < scenes.size(); ++index) {
    if (scenes[index].name == chosen) {
      return static_cast<int>(index);
    }
  }
  int index = -1;
  const auto [end, error] = std::from_chars(chosen.data(), chosen.data() + chosen.size(), index);
  if (error != std::errc() || end != chosen.data() + chosen.size() || index < 0 ||
      static_cast<std::size_t>(index) >= scenes.size()) {
    std::string names;
    for (std::size_t i = 0; i < scenes.size(); ++i) {
      names += (i == 0 ? "" : ", ") + std::to_string(i) + (scenes[i].name.empty() ? "" : " '" + scenes[i].name + "'");
    }
    source.fail("scene " + chosen + ": the file has " + gltf::countOf(scenes.size(), "scene") +
                    (names.empty() ? "" : " (" + names + ")"),
                {"scene"});
  }
  return index;
}

}  // namespace

Scene loadGltf(const fs::path& path, const SceneLoadOptions& options, const ResourceLimits& limits) {
  const std::string file = path.string();
  const std::string extension = lowercase(path.extension().string());
  const std::vector<unsigned char> bytes = gltf::readAssetBytes(path, file, extension);
  // Before tinygltf: it recurses on nesting and lets some invalid values through.
  const std::string_view json = gltf::jsonText(bytes, extension == ".glb", file);
  gltf::checkNestingDepth(json, file);
  gltf::checkStructure(json, file);

  tinygltf::Model model;
  std::string warnings;
  // Compressed files' parts that tinygltf cannot parse (gltf/stand_ins.hpp).
  const gltf::StandIns standIns = gltf::standInsForTinygltf(bytes, json, extension == ".glb");
  gltf::parseSandboxed(model, standIns.bytes ? *standIns.bytes : bytes, extension == ".glb", path,
                       options.allowExternalPaths, file, warnings);

  Scene scene;
  scene.source = file;
  scene.sourceHash = textFingerprint(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
  const gltf::Source source{file, model};
  gltf::checkRequiredExtensions(source);
  // What the extensions change in the model, before anything reads it:
  // compressed bytes decoded into plain buffers, texture sources, variants.
  gltf::decodeMeshoptViews(model, source, standIns.placeholderBuffers, limits);
  gltf::decodeDracoPrimitives(model, source, limits);
  gltf::resolveTextureSources(model, source);
  scene.materialVariants = gltf::applyMaterialVariant(model, source, options.materialVariant);
  for (const tinygltf::Animation& animation : model.animations) {
    Scene::Animation summary{animation.name, 0.0f};
    for (const tinygltf::AnimationSampler& sampler : animation.samplers)
      if (sampler.input >= 0 && std::size_t(sampler.input) < model.accessors.size() &&
          !model.accessors[std::size_t(sampler.input)].maxValues.empty() &&
          std::isfinite(model.accessors[std::size_t(sampler.input)].maxValues[0]))
        summary.end = std::max(summary.end, float(model.accessors[std::size_t(sampler.input)].maxValues[0]));
    scene.animations.push_back(summary);
  }
  int playedAnimation = -1;
  if (!options.animation.empty() || options.animationTime) {
    if (model.animations.empty())
      source.fail(std::string(options.animation.empty() ? "time" : "animation") + ": the file has no animations",
                  {options.animation.empty() ? "time" : "animation"});
    playedAnimation = options.animation.empty() ? 0 : gltf::findAnimation(source, options.animation);
    gltf::applyAnimation(model, source, playedAnimation, options.animationTime.value_or(0.0f));
    scene.animation = playedAnimation;
    scene.animationTime = options.animationTime.value_or(0.0f);
  }
  scene.ignored = gltf::findIgnoredFeatures(model, playedAnimation);
  if (options.strictGltf && !scene.ignored.empty()) {
    std::string list;
    for (const IgnoredFeature& feature : scene.ignored) list += (list.empty() ? "" : "; ") + feature.describe();
    source.fail("strict-gltf: " + list, {"strict-gltf"});
  }
  const int drawnScene = sceneIndex(source, options.gltfScene);
  GltfReader(source, scene, limits).read(drawnScene);
  scene.images = gltf::readImages(model, file, warnings, limits);
  // --environment replaces the file's own image-based light (loadScene).
  if (options.environment.empty()) scene.environment = gltf::readImageBasedLight(source, drawnScene, scene.images);
  checkSceneRanges(scene);
  const std::uint64_t sceneBytes = estimateSceneBytes(scene);
  if (sceneBytes > maxMemoryBytes(limits)) {
    throw LimitError(file + ": the scene needs about " + std::to_string(sceneBytes >> 20) +
                         " MiB, more than max-memory allows (" + std::to_string(maxMemoryBytes(limits) >> 20) +
                         " MiB); raise max-memory",
                     {"max-memory"});
  }
  return scene;
}

Scene loadScene(const std::string& nameOrPath, const SceneLoadOptions& options, const ResourceLimits& limits) {
  const bool builtin = nameOrPath.rfind(kBuiltinPrefix, 0) == 0;
  // A glTF file's choices asked of a built-in scene would be ignored: the
  // caller meant another input.
  if (builtin && !options.gltfScene.empty())
    throw SettingsError(
        "scene " + options.gltfScene + ": " + nameOrPath + " is built in, not a glTF file with scenes to choose from",
        {"scene"});
  if (builtin && (!options.animation.empty() || options.animationTime))
    throw SettingsError(std::string(options.animation.empty() ? "time" : "animation") + ": " + nameOrPath +
                            " is a built-in scene and has no animations",
                        {options.animation.empty() ? "time" : "animation"});
  if (builtin && !options.materialVariant.empty())
    throw SettingsError("material-variant " + options.materialVariant + ": " + nameOrPath +
                            " is a built-in scene and has no KHR_materials_variants variants",
                        {"material-variant"});
  Scene scene = builtin ? makeBuiltinScene(std::string_view(nameOrPath).substr(kBuiltinPrefix.size()))
                        : loadGltf(nameOrPath, options, limits);
  if (!options.environment.empty()) scene.environment = loadEnvironmentMap(options.environment, limits);
  return scene;
}

}  // namespace headlight

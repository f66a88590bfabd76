#include "gltf/features.hpp"

#include <algorithm>
#include <array>
#include <map>
#include <span>
#include <string_view>

#include "gltf/animation_pose.hpp"
#include "gltf/draco.hpp"
#include "gltf/material_extensions.hpp"
#include "gltf/meshopt.hpp"
#include "gltf/texture_sources.hpp"

namespace headlight::gltf {

namespace {

// Extensions that are rendered: nothing about them is named.
// One line each: merged branches add lines, not sizes.
constexpr std::string_view kRenderedExtensions[]{
    "KHR_lights_punctual",
    "KHR_materials_emissive_strength",
    "EXT_mesh_gpu_instancing",
    "KHR_mesh_quantization",
    "KHR_texture_transform",
    "KHR_materials_unlit",
    "KHR_materials_variants",  // the default materials, or --material-variant's (gltf/variants.cpp)
    kTextureWebp,              // decoded by OpenImageIO (gltf/texture_sources.cpp)
    "EXT_lights_image_based",  // the scene's light, as an environment map (gltf/image_based_light.cpp)
                               // The KHR_materials_* extensions: gltf/material_extensions.cpp's rows.
};

// Rendered when the build has their decoder (meson options draco, meshopt).
bool decoderBuilt(const std::string& name) {
  return (name == "KHR_draco_mesh_compression" && dracoDecoding()) ||
         (name == "EXT_meshopt_compression" && meshoptDecoding());
}

// Why a required extension refuses the file, where more can be said than
// "not supported".
constexpr std::pair<std::string_view, const char*> kRefusalReasons[]{
    {kTextureBasisu, "its KTX2 Basis Universal images are not decoded: no Debian package decodes Basis Universal"},
    {"KHR_draco_mesh_compression", "this build has no Draco decoder (built with -Ddraco=disabled)"},
    {"EXT_meshopt_compression", "this build has no meshoptimizer decoder (built with -Dmeshopt=disabled)"},
};

// Extensions that are not rendered but leave the geometry right, so a file
// that requires them still loads (and names them): the picture is wrong only
// in the named way. Any other required extension (Draco, meshopt, BasisU:
// geometry or images that cannot be read without it) refuses the file.
constexpr std::array<std::string_view, 0> kDrawableWithout{};  // none since spec-gloss is rendered

// Extensions converted at load into something close: named with what was done.
constexpr std::pair<std::string_view, const char*> kApproximatedExtensions[]{
    {kTextureBasisu, "is not rendered (KTX2 is not decoded; the texture's core source image is drawn)"},
    {"KHR_draco_mesh_compression",
     "is not rendered (no Draco decoder in this build; the uncompressed accessors are drawn)"},
    {"EXT_meshopt_compression", "is not rendered (no meshoptimizer in this build; the fallback buffers are drawn)"},
};

const char* effectOf(const std::string& extension) {
  for (const auto& [name, effect] : kApproximatedExtensions) {
    if (name == extension) return effect;
  }
  return "is not rendered";
}

bool listed(std::span<const std::string_view> list, const std::string& name) {
  return std::find(list.begin(), list.end(), name) != list.end();
}

std::string named(const char* noun, std::size_t index, const std::string& name) {
  return std::string(noun) + " " + std::to_string(index) + (name.empty() ? "" : " '" + name + "'");
}

// Features in the order first met; each element counts once per feature.
class Tally {
 public:
  void add(const std::string& feature, const char* noun, const std::string& element,
           const char* effect = "is not rendered") {
    auto [entry, inserted] = index_.try_emplace(feature, features_.size());
    if (inserted) {
      features_.push_back({feature, noun, 0, element, effect});
      lastElement_.emplace_back();
    }
    if (lastElement_[entry->second] != element) {
      lastElement_[entry->second] = element;
      ++features_[entry->second].count;
    }
  }
  bool has(const std::string& feature) const { return index_.count(feature) != 0; }
  std::vector<IgnoredFeature> take() { return std::move(features_); }

 private:
  std::map<std::string, std::size_t> index_;
  std::vector<IgnoredFeature> features_;
  std::vector<std::string> lastElement_;
};

// The texture references glTF's core material makes, with their names.
std::array<std::pair<const char*, const tinygltf::ExtensionMap*>, 5> textureExtensions(const tinygltf::Material& m) {
  return {{{"baseColorTexture", &m.pbrMetallicRoughness.baseColorTexture.extensions},
           {"metallicRoughnessTexture", &m.pbrMetallicRoughness.metallicRoughnessTexture.extensions},
           {"normalTexture", &m.normalTexture.extensions},
           {"occlusionTexture", &m.occlusionTexture.extensions},
           {"emissiveTexture", &m.emissiveTexture.extensions}}};
}

// The texture set each core texture reference samples: its texCoord, or
// KHR_texture_transform's texCoord where that overrides it.
int sampledSet(int texCoord, const tinygltf::ExtensionMap& extensions) {
  const auto transform = extensions.find("KHR_texture_transform");
  if (transform != extensions.end() && transform->second.Has("texCoord") && transform->second.Get("texCoord").IsInt()) {
    return transform->second.Get("texCoord").GetNumberAsInt();
  }
  return texCoord;
}

std::array<std::pair<int, int>, 5> textureCoordinates(const tinygltf::Material& m) {
  const auto& pbr = m.pbrMetallicRoughness;
  const auto entry = [](const auto& info) { return std::pair{info.index, sampledSet(info.texCoord, info.extensions)}; };
  return {{entry(pbr.baseColorTexture), entry(pbr.metallicRoughnessTexture), entry(m.normalTexture),
           entry(m.occlusionTexture), entry(m.emissiveTexture)}};
}

// ---- Detectors: one per feature that is not rendered -------------------------

void findSecondaryTexcoords(const tinygltf::Model& model, int /*playedAnimation*/, Tally& tally) {
  for (std::size_t index = 0; index < model.materials.size(); ++index) {
    for (const auto& [texture, texCoord] : textureCoordinates(model.materials[index])) {
      // TEXCOORD_0 and TEXCOORD_1 are rendered (kTexcoordSets); further sets are not.
      if (texture >= 0 && texCoord >= kTexcoordSets) {
        tally.add("TEXCOORD_" + std::to_string(texCoord), "material",
                  named("material", index, model.materials[index].name),
                  "is not rendered (TEXCOORD_0 is sampled instead)");
      }
    }
  }
}

void findVertexColors(const tinygltf::Model& model, int /*playedAnimation*/, Tally& tally) {
  for (std::size_t mesh = 0; mesh < model.meshes.size(); ++mesh) {
    for (std::size_t primitive = 0; primitive < model.meshes[mesh].primitives.size(); ++primitive) {
      for (const auto& [attribute, accessor] : model.meshes[mesh].primitives[primitive].attributes) {
        // COLOR_0 is rendered; further colour sets are not.
        if (attribute.rfind("COLOR_", 0) == 0 && attribute != "COLOR_0") {
          tally.add(attribute, "primitive", named("mesh", mesh, "") + " primitive " + std::to_string(primitive));
        }
      }
    }
  }
}

// Only animations that start away from the static pose change what a still
// frame should show (gltf/animation_pose.hpp); the one played is not named.
void findAnimations(const tinygltf::Model& model, int playedAnimation, Tally& tally) {
  for (std::size_t index = 0; index < model.animations.size(); ++index) {
    if (int(index) == playedAnimation || !animationLeavesStaticPose(model, index)) continue;
    tally.add("animation", "animation", named("animation", index, model.animations[index].name),
              playedAnimation < 0 ? "is not played (the static pose is drawn; --animation N|NAME --time SECONDS "
                                    "poses the file by one)"
                                  : "is not played (--animation plays one at a time)");
  }
}

void addExtensions(const tinygltf::ExtensionMap& extensions, const char* noun, const std::string& element,
                   Tally& tally) {
  for (const auto& [name, value] : extensions) {
    if (!extensionRendered(name)) {
      tally.add(name, noun, element, effectOf(name));
    }
  }
}

// Extensions where elements carry them: materials (and their texture
// references), primitives, nodes, textures, cameras.
void findElementExtensions(const tinygltf::Model& model, int /*playedAnimation*/, Tally& tally) {
  for (std::size_t index = 0; index < model.materials.size(); ++index) {
    const tinygltf::Material& material = model.materials[index];
    const std::string element = named("material", index, material.name);
    addExtensions(material.extensions, "material", element, tally);
    for (const auto& [texture, extensions] : textureExtensions(material)) {
      addExtensions(*extensions, "material", element, tally);
    }
  }
  for (std::size_t mesh = 0; mesh < model.meshes.size(); ++mesh) {
    for (std::size_t primitive = 0; primitive < model.meshes[mesh].primitives.size(); ++primitive) {
      addExtensions(model.meshes[mesh].primitives[primitive].extensions, "primitive",
                    named("mesh", mesh, "") + " primitive " + std::to_string(primitive), tally);
    }
  }
  for (std::size_t node = 0; node < model.nodes.size(); ++node) {
    addExtensions(model.nodes[node].extensions, "node", named("node", node, model.nodes[node].name), tally);
  }
  for (std::size_t texture = 0; texture < model.textures.size(); ++texture) {
    addExtensions(model.textures[texture].extensions, "texture", named("texture", texture, ""), tally);
  }
  for (std::size_t camera = 0; camera < model.cameras.size(); ++camera) {
    addExtensions(model.cameras[camera].extensions, "camera", named("camera", camera, model.cameras[camera].name),
                  tally);
  }
  for (const auto& [name, value] : model.extensions) {
    if (!extensionRendered(name)) {
      tally.add(name, "", "on the file");
    }
  }
}

// What extensionsUsed lists that no element above carries (extensions
// inside other extensions, KHR_xmp, unknown ones).
void findListedExtensions(const tinygltf::Model& model, int /*playedAnimation*/, Tally& tally) {
  for (const std::string& name : model.extensionsUsed) {
    if (!extensionRendered(name) && !tally.has(name)) {
      tally.add(name, "", "listed in extensionsUsed");
    }
  }
}

// KHR_materials_transmission is rendered, except on the materials the
// transmission pass does not draw (Material::transmissive): alphaMode BLEND
// ones (the blend pass draws them, without it) and unlit ones (the
// specification excludes the pair; unlit wins).
void findUndrawnTransmission(const tinygltf::Model& model, int /*playedAnimation*/, Tally& tally) {
  for (std::size_t index = 0; index < model.materials.size(); ++index) {
    const tinygltf::Material& material = model.materials[index];
    if (material.extensions.count("KHR_materials_transmission") == 0) continue;
    if (material.alphaMode != "BLEND" && material.extensions.count("KHR_materials_unlit") == 0) continue;
    tally.add("KHR_materials_transmission", "material", named("material", index, material.name),
              "is not rendered on an alphaMode BLEND or unlit material (drawn as without it)");
  }
}

// The table: remove a row when its feature becomes rendered.
// `playedAnimation` is the animation the file is posed by (-1: none).
constexpr void (*kDetectors[])(const tinygltf::Model&, int playedAnimation, Tally&){
    findSecondaryTexcoords, findVertexColors,     findAnimations,
    findElementExtensions,  findListedExtensions, findUndrawnTransmission,
};

// " (texture 0, texture 2)": the textures that carry `extension`.
std::string usersOf(const tinygltf::Model& model, const std::string& extension) {
  std::string users;
  for (std::size_t index = 0; index < model.textures.size(); ++index) {
    if (model.textures[index].extensions.count(extension) != 0) {
      users += (users.empty() ? " (" : ", ") + named("texture", index, model.textures[index].name);
    }
  }
  return users.empty() ? "" : users + ")";
}

}  // namespace

bool extensionRendered(const std::string& name) {
  return listed(kRenderedExtensions, name) || listed(materialExtensionNames(), name) || decoderBuilt(name);
}

std::vector<IgnoredFeature> findIgnoredFeatures(const tinygltf::Model& model, int playedAnimation) {
  Tally tally;
  for (auto detect : kDetectors) {
    detect(model, playedAnimation, tally);
  }
  return tally.take();
}

void checkRequiredExtensions(const Source& source) {
  std::string refused;
  std::size_t count = 0;
  for (const std::string& required : source.model.extensionsRequired) {
    if (!extensionRendered(required) && !listed(kDrawableWithout, required)) {
      refused += (refused.empty() ? "" : ", ") + required;
      ++count;
    }
  }
  if (count == 0) {
    return;
  }
  std::string reasons;  // "; KHR_texture_basisu (texture 0): its KTX2 ..."
  for (const auto& [name, reason] : kRefusalReasons) {
    if (refused.find(name) != std::string::npos) {
      reasons += "; " + std::string(name) + usersOf(source.model, std::string(name)) + ": " + reason;
    }
  }
  std::string accepted;
  for (std::string_view name : kRenderedExtensions) accepted += (accepted.empty() ? "" : ", ") + std::string(name);
  for (std::string_view name : materialExtensionNames()) accepted += ", " + std::string(name);
  for (std::string_view name : {"KHR_draco_mesh_compression", "EXT_meshopt_compression"}) {
    if (decoderBuilt(std::string(name))) accepted += ", " + std::string(name);
  }
  for (std::string_view name : kDrawableWithout) accepted += ", " + std::string(name) + " (not rendered)";
  source.fail(std::string(count == 1 ? "requires extension " : "requires extensions ") + refused +
              (count == 1 ? ", which is" : ", which are") + " not supported" + reasons +
              " (accepted as required: " + accepted + ")");
}

}  // namespace headlight::gltf

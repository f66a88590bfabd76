#include "gltf/prescan.hpp"

#include <cstdint>
#include <cstring>
#include <limits>
#include <nlohmann/json.hpp>

#include "headlight/error.hpp"
#include "io/bounded_json.hpp"

namespace headlight::gltf {

namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& file, const std::string& message) { throw SceneError(file + ": " + message); }

std::uint32_t readU32(const unsigned char* at) {
  std::uint32_t value;
  std::memcpy(&value, at, sizeof value);  // GLB is little-endian, as every platform we build for
  return value;
}

std::string describe(const json& value) {
  if (value.is_string()) {
    // Built by appending: GCC 12 warns falsely (-Wrestrict, bug 105329) on "\"" + text.
    std::string text(1, '"');
    text.append(value.get_ref<const std::string&>(), 0, 32);
    text.append("\" (a string)");
    return text;
  }
  if (value.is_number()) return value.dump();
  if (value.is_boolean()) return value.dump() + " (a boolean)";
  if (value.is_null()) return "null";
  return value.is_array() ? "an array" : "an object";
}

// What an integer property may hold: an index into an array (tinygltf keeps
// them as int) or a byte count/offset (size_t, but files are < 4 GiB).
enum class IntegerKind { Index, Bytes };

class StructureCheck {
 public:
  explicit StructureCheck(const std::string& file) : file_(file) {}

  void run(const json& root) {
    if (!root.is_object()) fail(file_, "the top level is " + describe(root) + ", expected a JSON object");
    checkAsset(root);
    integer(root, "scene", "the file", IntegerKind::Index);
    forEach(root, "buffers", "buffer", [&](const json& buffer, const std::string& name) {
      integer(buffer, "byteLength", name, IntegerKind::Bytes);
    });
    forEach(root, "bufferViews", "bufferView", [&](const json& view, const std::string& name) {
      for (const char* key : {"buffer"}) integer(view, key, name, IntegerKind::Index);
      for (const char* key : {"byteOffset", "byteLength", "byteStride"}) integer(view, key, name, IntegerKind::Bytes);
    });
    forEach(root, "accessors", "accessor", [&](const json& accessor, const std::string& name) {
      integer(accessor, "bufferView", name, IntegerKind::Index);
      integer(accessor, "componentType", name, IntegerKind::Index);
      for (const char* key : {"byteOffset", "count"}) integer(accessor, key, name, IntegerKind::Bytes);
      if (const json* sparse = object(accessor, "sparse", name)) {
        integer(*sparse, "count", name + " sparse", IntegerKind::Bytes);
        for (const char* part : {"indices", "values"}) {
          if (const json* block = object(*sparse, part, name + " sparse")) {
            const std::string blockName = name + " sparse " + part;
            integer(*block, "bufferView", blockName, IntegerKind::Index);
            integer(*block, "byteOffset", blockName, IntegerKind::Bytes);
            integer(*block, "componentType", blockName, IntegerKind::Index);
          }
        }
      }
    });
    forEach(root, "meshes", "mesh", [&](const json& mesh, const std::string& name) {
      forEach(mesh, "primitives", name + " primitive", [&](const json& primitive, const std::string& primitiveName) {
        for (const char* key : {"indices", "material", "mode"})
          integer(primitive, key, primitiveName, IntegerKind::Index);
        if (const json* attributes = object(primitive, "attributes", primitiveName)) {
          for (const auto& [attribute, value] : attributes->items()) {
            integerValue(value, primitiveName + " attribute " + attribute, IntegerKind::Index);
          }
        }
      });
    });
    forEach(root, "nodes", "node", [&](const json& node, const std::string& name) {
      for (const char* key : {"mesh", "camera", "skin"}) integer(node, key, name, IntegerKind::Index);
      integerArray(node, "children", name);
      for (const char* key : {"matrix", "translation", "rotation", "scale", "weights"}) numberArray(node, key, name);
      if (const json* extensions = object(node, "extensions", name)) {
        if (const json* lights = object(*extensions, "KHR_lights_punctual", name + " extensions")) {
          integer(*lights, "light", name + " KHR_lights_punctual", IntegerKind::Index);
        }
      }
    });
    forEach(root, "scenes", "scene",
            [&](const json& scene, const std::string& name) { integerArray(scene, "nodes", name); });
    forEach(root, "textures", "texture", [&](const json& texture, const std::string& name) {
      for (const char* key : {"source", "sampler"}) integer(texture, key, name, IntegerKind::Index);
    });
    forEach(root, "images", "image", [&](const json& image, const std::string& name) {
      integer(image, "bufferView", name, IntegerKind::Index);
    });
    forEach(root, "samplers", "sampler", [&](const json& sampler, const std::string& name) {
      for (const char* key : {"magFilter", "minFilter", "wrapS", "wrapT"})
        integer(sampler, key, name, IntegerKind::Index);
    });
    forEach(root, "materials", "material",
            [&](const json& material, const std::string& name) { checkMaterial(material, name); });
    const auto nothingMore = [](const json&, const std::string&) {};
    forEach(root, "cameras", "camera", nothingMore);
    forEach(root, "skins", "skin", nothingMore);
    forEach(root, "animations", "animation", nothingMore);
    checkExtensions(root, "", false);
  }

 private:
  void checkAsset(const json& root) {
    const json* asset = object(root, "asset", "the file");
    if (asset == nullptr) fail(file_, "has no asset object, but glTF requires asset.version");
    const auto version = asset->find("version");
    if (version == asset->end()) fail(file_, "has no asset.version, but glTF requires it");
    checkVersion(*version, "asset.version");
    if (const auto minVersion = asset->find("minVersion"); minVersion != asset->end()) {
      checkVersion(*minVersion, "asset.minVersion");
      if (minVersion->get<std::string>() != "2.0") {
        fail(file_, "asset.minVersion is \"" + minVersion->get<std::string>() + "\", but this loader reads glTF 2.0");
      }
    }
  }

  // glTF versions are "<major>.<minor>"; this loader reads major 2 (a later
  // minor only adds, so it stays readable).
  void checkVersion(const json& value, const std::string& name) {
    const std::string text = value.is_string() ? value.get<std::string>() : std::string();
    const auto dot = text.find('.');
    const auto digits = [](std::string_view part) {
      return !part.empty() && part.size() <= 9 && part.find_first_not_of("0123456789") == std::string_view::npos;
    };
    if (!value.is_string() || dot == std::string::npos || !digits(std::string_view(text).substr(0, dot)) ||
        !digits(std::string_view(text).substr(dot + 1))) {
      fail(file_, name + " is " + describe(value) + ", expected \"<major>.<minor>\" such as \"2.0\"");
    }
    if (text.substr(0, dot) != "2") {
      fail(file_, name + " is \"" + text + "\", but this loader reads glTF 2.x only");
    }
  }

  void checkMaterial(const json& material, const std::string& name) {
    auto textureInfo = [&](const json& holder, const char* key) {
      if (const json* info = object(holder, key, name)) {
        const std::string infoName = name + " " + key;
        integer(*info, "index", infoName, IntegerKind::Index);
        integer(*info, "texCoord", infoName, IntegerKind::Index);
      }
    };
    for (const char* key : {"normalTexture", "occlusionTexture", "emissiveTexture"}) textureInfo(material, key);
    if (const json* pbr = object(material, "pbrMetallicRoughness", name)) {
      for (const char* key : {"baseColorTexture", "metallicRoughnessTexture"}) textureInfo(*pbr, key);
      numberArray(*pbr, "baseColorFactor", name + " pbrMetallicRoughness");
    }
    numberArray(material, "emissiveFactor", name);
  }

  // Extensions wherever they are. Each must be an object: tinygltf drops
  // any other value in silence (a KHR_texture_transform written [1, 2]
  // rendered untransformed, exit 0). tinygltf keeps a JSON integer as an
  // int, so one outside 32 bits wraps (an emissiveStrength of 4294967297 was
  // read as 1, an index of 2147483648 as -2147483648). The core's integers
  // are range-checked above by name; the extensions' are checked here, so
  // that no extension reader ever sees a wrapped value. A real number so
  // large keeps its value written with a decimal point (tinygltf reads that
  // as a double). Extras are the file's own data, not read.
  void checkExtensions(const json& value, const std::string& path, bool inExtensions) {
    if (value.is_object()) {
      for (const auto& [key, member] : value.items()) {
        if (key == "extras") continue;
        const std::string where = path.empty() ? key : path + "." + key;
        if (key == "extensions") checkExtensionObjects(member, where);
        checkExtensions(member, where, inExtensions || key == "extensions");
      }
    } else if (value.is_array()) {
      for (std::size_t index = 0; index < value.size(); ++index)
        checkExtensions(value[index], path + "[" + std::to_string(index) + "]", inExtensions);
    } else if (inExtensions && (value.is_number_integer() || value.is_number_unsigned())) {
      const bool fits = value.is_number_unsigned()
                            ? value.get<std::uint64_t>() <= std::uint64_t(std::numeric_limits<std::int32_t>::max())
                            : value.get<std::int64_t>() >= std::numeric_limits<std::int32_t>::min() &&
                                  value.get<std::int64_t>() <= std::numeric_limits<std::int32_t>::max();
      if (!fits)
        fail(file_, path + " is " + value.dump() +
                        ", an integer outside -2147483648..2147483647, which the glTF parser would wrap (a real "
                        "number this large is read as such written with a decimal point: " +
                        value.dump() + ".0)");
    }
  }

  // An element's "extensions" (`where`): an object of objects.
  void checkExtensionObjects(const json& extensions, const std::string& where) {
    if (!extensions.is_object()) fail(file_, where + " is " + describe(extensions) + ", expected an object");
    for (const auto& [name, extension] : extensions.items())
      if (!extension.is_object())
        fail(file_, where + "." + name + " is " + describe(extension) +
                        ", expected an object (the extension's properties), which the glTF parser would drop");
  }

  // An optional member that must be an object; nullptr where absent.
  const json* object(const json& holder, const char* key, const std::string& where) {
    const auto found = holder.find(key);
    if (found == holder.end()) return nullptr;
    if (!found->is_object()) fail(file_, where + " " + key + " is " + describe(*found) + ", expected an object");
    return &*found;
  }

  template <typename Check>
  void forEach(const json& holder, const char* key, const std::string& noun, Check check) {
    const auto found = holder.find(key);
    if (found == holder.end()) return;
    if (!found->is_array()) fail(file_, std::string(key) + " is " + describe(*found) + ", expected an array");
    for (std::size_t index = 0; index < found->size(); ++index) {
      const json& element = (*found)[index];
      const std::string name = noun + " " + std::to_string(index);
      if (!element.is_object()) fail(file_, name + " is " + describe(element) + ", expected an object");
      check(element, name);
    }
  }

  void integerValue(const json& value, const std::string& name, IntegerKind kind) {
    const double maximum = kind == IntegerKind::Index ? double(std::numeric_limits<std::int32_t>::max())
                                                      : double(std::numeric_limits<std::uint32_t>::max());
    bool ok = false;
    if (value.is_number_unsigned()) {
      ok = double(value.get<std::uint64_t>()) <= maximum;
    } else if (value.is_number_integer()) {
      ok = value.get<std::int64_t>() >= 0 && double(value.get<std::int64_t>()) <= maximum;
    } else if (value.is_number_float()) {
      // JSON does not tell 12 from 12.0; some writers emit the latter.
      const double number = value.get<double>();
      ok = number >= 0 && number <= maximum && number == double(std::int64_t(number));
    }
    if (!ok) {
      fail(file_,
           name + " is " + describe(value) + ", expected an integer in 0.." + std::to_string(std::int64_t(maximum)));
    }
  }

  void integer(const json& holder, const char* key, const std::string& where, IntegerKind kind) {
    const auto found = holder.find(key);
    if (found != holder.end()) integerValue(*found, where + " " + key, kind);
  }

  void integerArray(const json& holder, const char* key, const std::string& where) {
    const auto found = holder.find(key);
    if (found == holder.end()) return;
    if (!found->is_array()) fail(file_, where + " " + key + " is " + describe(*found) + ", expected an array");
    for (std::size_t index = 0; index < found->size(); ++index) {
      integerValue((*found)[index], where + " " + key + "[" + std::to_string(index) + "]", IntegerKind::Index);
    }
  }

  void numberArray(const json& holder, const char* key, const std::string& where) {
    const auto found = holder.find(key);
    if (found == holder.end()) return;
    if (!found->is_array())
      fail(file_, where + " " + key + " is " + describe(*found) + ", expected an array of numbers");
    for (std::size_t index = 0; index < found->size(); ++index) {
      if (!(*found)[index].is_number()) {
        fail(file_, where + " " + key + "[" + std::to_string(index) + "] is " + describe((*found)[index]) +
                        ", expected a number");
      }
    }
  }

  const std::string& file_;
};

}  // namespace

std::string_view jsonText(std::span<const unsigned char> bytes, bool binary, const std::string& file) {
  if (!binary) return {reinterpret_cast<const char*>(bytes.data()), bytes.size()};
  // glTF 2.0 §4.4: a 12-byte header (magic, version, length), then chunks of
  // (length, type, data); the first chunk is JSON.
  if (bytes.size() < 20) {
    fail(file,
         "GLB is " + std::to_string(bytes.size()) + " bytes, shorter than its 12-byte header and first chunk header");
  }
  if (std::memcmp(bytes.data(), "glTF", 4) != 0) fail(file, "GLB header magic is not 'glTF'");
  const std::uint32_t version = readU32(bytes.data() + 4);
  if (version != 2) {
    fail(file, "GLB header version is " + std::to_string(version) + ", expected 2 (glTF 2.0 binary container)");
  }
  const std::uint32_t length = readU32(bytes.data() + 8);
  if (length > bytes.size() || length < 20) {
    fail(file, "GLB header length is " + std::to_string(length) + ", but the file has " + std::to_string(bytes.size()) +
                   " bytes");
  }
  const std::uint32_t chunkLength = readU32(bytes.data() + 12);
  if (std::memcmp(bytes.data() + 16, "JSON", 4) != 0) fail(file, "GLB chunk 0 is not of type JSON");
  if (chunkLength > length - 20) {
    fail(file, "GLB JSON chunk length is " + std::to_string(chunkLength) + ", but only " + std::to_string(length - 20) +
                   " bytes follow its header");
  }
  return {reinterpret_cast<const char*>(bytes.data()) + 20, chunkLength};
}

void checkNestingDepth(std::string_view text, const std::string& file) {
  int depth = 0;
  bool inString = false;
  for (std::size_t at = 0; at < text.size(); ++at) {
    const char c = text[at];
    if (inString) {
      if (c == '\\') {
        ++at;  // skips the escaped character, which may be a quote
      } else if (c == '"') {
        inString = false;
      }
    } else if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > detail::kMaxJsonDepth) {
        fail(file, "JSON nests deeper than " + std::to_string(detail::kMaxJsonDepth) + " levels at byte " +
                       std::to_string(at) + " (of arrays and objects: extras, extensions or elsewhere)");
      }
    } else if (c == ']' || c == '}') {
      --depth;
    }
  }
}

void checkStructure(std::string_view text, const std::string& file) {
  json root;
  try {
    root = json::parse(text.begin(), text.end());
  } catch (const json::exception& error) {
    fail(file, "is not valid JSON: " + detail::jsonErrorText(error));
  }
  StructureCheck(file).run(root);
}

}  // namespace headlight::gltf

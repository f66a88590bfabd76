#include "gltf/material_extensions.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <sstream>

#include "gltf/materials.hpp"

namespace headlight::gltf {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// The values a property may take: [min, max], or (min, max] when the
// minimum is excluded (a distance that divides).
struct Range {
  float min = 0.0f;
  float max = kInfinity;
  bool minExcluded = false;
  bool zeroToo = false;  // 0 is allowed besides the range (glTF's ior)
  bool holds(double value) const {
    return std::isfinite(value) &&
           ((zeroToo && value == 0.0) || ((minExcluded ? value > min : value >= min) && value <= max));
  }
  std::string text() const {
    std::ostringstream out;
    if (min == -kInfinity && max == kInfinity) {
      out << "that is finite in float";  // not ">= -inf"
    } else if (max == kInfinity) {
      out << (minExcluded ? "> " : ">= ") << min << (zeroToo ? " or 0" : "");
    } else {
      out << "in " << min << ".." << max;
    }
    return out.str();
  }
};
constexpr Range kUnit{0.0f, 1.0f};
constexpr Range kNonNegative{0.0f, kInfinity};
constexpr Range kAnyFinite{-kInfinity, kInfinity};

std::string formatted(double value) {
  std::ostringstream out;
  out << value;
  return out.str();
}

// One extension object of one material: its properties read with the
// specification's defaults, every failure naming material, extension and
// property ("material 2 KHR_materials_volume attenuationDistance is -1, expected > 0").
class ExtensionReader {
 public:
  ExtensionReader(const Source& source, const tinygltf::Value& object, std::string user)
      : source_(source), object_(object), user_(std::move(user)) {
    if (!object_.IsObject()) source_.fail(user_ + " is not a JSON object");
  }

  float number(const char* key, float fallback, Range range) const {
    if (!object_.Has(key)) return fallback;
    return checked(object_.Get(key), key, range);
  }

  // An array of N numbers (a colour: N = 3, or 4 with alpha).
  template <int N = 3>
  glm::vec<N, float> color(const char* key, glm::vec<N, float> fallback, Range range) const {
    if (!object_.Has(key)) return fallback;
    const tinygltf::Value& array = object_.Get(key);
    if (!array.IsArray() || array.ArrayLen() != std::size_t(N))
      source_.fail(user_ + " " + key + " is not " + std::to_string(N) + " numbers");
    glm::vec<N, float> out;
    for (int c = 0; c < N; ++c) out[c] = checked(array.Get(c), key, range);
    return out;
  }

  // A textureInfo (or normalTextureInfo, whose scale goes to `scale`).
  TextureRef texture(const char* key, float* scale = nullptr) const {
    if (!object_.Has(key)) return {};
    const tinygltf::Value& info = object_.Get(key);
    const std::string user = user_ + " " + key;
    if (!info.IsObject() || !info.Has("index") || !info.Get("index").IsInt()) {
      source_.fail(user + " has no texture index");
    }
    const tinygltf::Value* transform = nullptr;
    if (info.Has("extensions") && info.Get("extensions").Has("KHR_texture_transform")) {
      transform = &info.Get("extensions").Get("KHR_texture_transform");
    }
    int texCoord = 0;
    if (info.Has("texCoord")) {
      if (!info.Get("texCoord").IsInt()) source_.fail(user + " texCoord is not an integer");
      texCoord = info.Get("texCoord").GetNumberAsInt();
    }
    if (scale && info.Has("scale")) *scale = checked(info.Get("scale"), "scale", kAnyFinite);
    return readTextureRef(source_, info.Get("index").GetNumberAsInt(), texCoord, transform, user);
  }

 private:
  float checked(const tinygltf::Value& value, const char* key, Range range) const {
    if (!value.IsNumber() && !value.IsInt()) source_.fail(user_ + " " + key + " is not a number");
    const double number = value.GetNumberAsDouble();
    if (!range.holds(number) || !std::isfinite(float(number))) {
      source_.fail(user_ + " " + key + " is " + formatted(number) + ", expected a number " + range.text());
    }
    return static_cast<float>(number);
  }

  const Source& source_;
  const tinygltf::Value& object_;
  std::string user_;
};

// ---- One reader per extension: the specification's properties and ranges ------

void readIor(const ExtensionReader& in, Material& out) {
  // glTF allows 0 besides >= 1 (F0 = 1); anything between is refused.
  out.ior = in.number("ior", 1.5f, Range{1.0f, kInfinity, false, true});
}

void readSpecular(const ExtensionReader& in, Material& out) {
  MaterialSpecular& s = out.specular.emplace();
  s.specularFactor = in.number("specularFactor", 1.0f, kUnit);
  s.specularTexture = in.texture("specularTexture");
  s.specularColorFactor = in.color("specularColorFactor", glm::vec3(1.0f), kNonNegative);
  s.specularColorTexture = in.texture("specularColorTexture");
}

void readClearcoat(const ExtensionReader& in, Material& out) {
  MaterialClearcoat& c = out.clearcoat.emplace();
  c.clearcoatFactor = in.number("clearcoatFactor", 0.0f, kUnit);
  c.clearcoatTexture = in.texture("clearcoatTexture");
  c.clearcoatRoughnessFactor = in.number("clearcoatRoughnessFactor", 0.0f, kUnit);
  c.clearcoatRoughnessTexture = in.texture("clearcoatRoughnessTexture");
  c.clearcoatNormalTexture = in.texture("clearcoatNormalTexture", &c.clearcoatNormalScale);
}

void readSheen(const ExtensionReader& in, Material& out) {
  MaterialSheen& s = out.sheen.emplace();
  s.sheenColorFactor = in.color("sheenColorFactor", glm::vec3(0.0f), kUnit);
  s.sheenColorTexture = in.texture("sheenColorTexture");
  s.sheenRoughnessFactor = in.number("sheenRoughnessFactor", 0.0f, kUnit);
  s.sheenRoughnessTexture = in.texture("sheenRoughnessTexture");
}

void readIridescence(const ExtensionReader& in, Material& out) {
  MaterialIridescence& i = out.iridescence.emplace();
  i.iridescenceFactor = in.number("iridescenceFactor", 0.0f, kUnit);
  i.iridescenceTexture = in.texture("iridescenceTexture");
  i.iridescenceIor = in.number("iridescenceIor", 1.3f, Range{1.0f, kInfinity});
  i.iridescenceThicknessMinimum = in.number("iridescenceThicknessMinimum", 100.0f, kNonNegative);
  i.iridescenceThicknessMaximum = in.number("iridescenceThicknessMaximum", 400.0f, kNonNegative);
  i.iridescenceThicknessTexture = in.texture("iridescenceThicknessTexture");
}

void readAnisotropy(const ExtensionReader& in, Material& out) {
  MaterialAnisotropy& a = out.anisotropy.emplace();
  a.anisotropyStrength = in.number("anisotropyStrength", 0.0f, kUnit);
  a.anisotropyRotation = in.number("anisotropyRotation", 0.0f, kAnyFinite);
  a.anisotropyTexture = in.texture("anisotropyTexture");
}

void readTransmission(const ExtensionReader& in, Material& out) {
  MaterialTransmission& t = out.transmission.emplace();
  t.transmissionFactor = in.number("transmissionFactor", 0.0f, kUnit);
  t.transmissionTexture = in.texture("transmissionTexture");
}

void readVolume(const ExtensionReader& in, Material& out) {
  MaterialVolume& v = out.volume.emplace();
  v.thicknessFactor = in.number("thicknessFactor", 0.0f, kNonNegative);
  v.thicknessTexture = in.texture("thicknessTexture");
  v.attenuationDistance = in.number("attenuationDistance", kInfinity, Range{0.0f, kInfinity, true});
  v.attenuationColor = in.color("attenuationColor", glm::vec3(1.0f), kUnit);
}

// KHR_materials_pbrSpecularGlossiness, rendered through the metallic-
// roughness model's own parts, as glTF-Transform's conversion does: the
// diffuse colour and texture are the base colour (metallic 0), the specular
// colour is KHR_materials_specular's F0 colour at full weight with
// KHR_materials_ior's 0 (F0 = the specular colour itself:
// ((0 - 1) / (0 + 1))^2 = 1), and roughness is 1 - glossiness. The
// specularGlossinessTexture serves twice: its sRGB RGB as the specular
// colour texture, its linear A (glossiness) through the metallic-roughness
// slot (Material::roughnessFromGlossiness). A pbrMetallicRoughness fallback
// in the same material is replaced. The diffuse lobe then takes 1 - F per
// channel, where the extension's reference takes 1 - max(specular)
// (docs/PIPELINE.md).
void readSpecularGlossiness(const ExtensionReader& in, Material& out) {
  out.baseColorFactor = in.color<4>("diffuseFactor", glm::vec4(1.0f), kUnit);
  out.baseColorTexture = in.texture("diffuseTexture");
  out.metallicFactor = 0.0f;
  out.metallicRoughnessTexture = {};  // a pbrMetallicRoughness fallback's is not this material's
  const float glossiness = in.number("glossinessFactor", 1.0f, kUnit);
  MaterialSpecular& s = out.specular.emplace();
  s.specularColorFactor = in.color("specularFactor", glm::vec3(1.0f), kUnit);
  s.specularColorTexture = in.texture("specularGlossinessTexture");
  out.ior = 0.0f;
  out.roughnessFromGlossiness = s.specularColorTexture.present();
  if (out.roughnessFromGlossiness) out.metallicRoughnessTexture = s.specularColorTexture;
  out.roughnessFactor = out.roughnessFromGlossiness ? glossiness : 1.0f - glossiness;
}

// The one table of material extensions read here (in order: an explicit
// KHR_materials_ior or _specular after specular-glossiness overrides it).
// Each is rendered (gltf/features.cpp takes the names from here): a new
// lobe's extension is a row and its reader.
struct ExtensionRow {
  std::string_view name;
  void (*read)(const ExtensionReader&, Material&);
};
constexpr ExtensionRow kExtensionRows[] = {
    {"KHR_materials_pbrSpecularGlossiness", readSpecularGlossiness},
    {"KHR_materials_ior", readIor},
    {"KHR_materials_specular", readSpecular},
    {"KHR_materials_clearcoat", readClearcoat},
    {"KHR_materials_sheen", readSheen},
    {"KHR_materials_iridescence", readIridescence},
    {"KHR_materials_anisotropy", readAnisotropy},
    {"KHR_materials_transmission", readTransmission},
    {"KHR_materials_volume", readVolume},
};

constexpr auto kExtensionNames = [] {
  std::array<std::string_view, std::size(kExtensionRows)> names{};
  for (std::size_t i = 0; i < names.size(); ++i) names[i] = kExtensionRows[i].name;
  return names;
}();

}  // namespace

std::span<const std::string_view> materialExtensionNames() { return kExtensionNames; }

void readMaterialExtensions(const Source& source, const tinygltf::Material& material, const std::string& name,
                            Material& out) {
  for (const ExtensionRow& row : kExtensionRows) {
    const auto found = material.extensions.find(std::string(row.name));
    if (found == material.extensions.end()) continue;
    row.read(ExtensionReader(source, found->second, name + " " + std::string(row.name)), out);
  }
}

}  // namespace headlight::gltf

#include "scene/material_textures.hpp"

namespace headlight {

namespace {

using B = gpu::MaterialBlock;
using T = MaterialTexture;

// The extensions' textures take the bits after the core ones: reading the
// k-th at kFirstExtensionBit + k, its TEXCOORD_1 at kFirstExtensionBit +
// kExtensionTextures + k (12: the ratified extensions' textures).
constexpr int kFirstExtensionBit = 17;
constexpr int kExtensionTextures = 12;
constexpr int kFirstExtensionTexture = int(T::Emissive) + 1;
[[maybe_unused]] constexpr FeatureBits readBit(T id) {
  return FeatureBits{1} << (kFirstExtensionBit + int(id) - kFirstExtensionTexture);
}
[[maybe_unused]] constexpr FeatureBits setBit(T id) {
  return FeatureBits{1} << (kFirstExtensionBit + kExtensionTextures + int(id) - kFirstExtensionTexture);
}
static_assert(kFirstExtensionBit + 2 * kExtensionTextures <= 64);
static_assert(kFeatureRoughnessFromGlossiness == FeatureBits{1} << (kFirstExtensionBit + 2 * kExtensionTextures),
              "the glossiness bit follows the extension textures' bits");

// A texture of an extension, when the material has it. A row reads
//   HL_EXTENSION_ROW(Clearcoat, "CLEARCOAT", kUnitClearcoatTexture, false, clearcoat,
//                    Clearcoat::clearcoatTexture, clearcoat),
// (id, define stem, unit, sRGB, Material's optional, member, block transform stem).
template <auto Extension, auto Member>
const TextureRef* extensionTexture(const Material& material) {
  const auto& extension = material.*Extension;
  return extension ? &(*extension.*Member) : nullptr;
}
template <auto Member>
const TextureRef* coreTexture(const Material& material) {
  return &(material.*Member);
}

#define HL_EXTENSION_ROW(id, define, unit, srgb, extension, member, block)                                \
  {T::id, define, gpu::unit, srgb, readBit(T::id), setBit(T::id),                                       \
   extensionTexture<&Material::extension, &Material##member>, &B::block##TransformU, &B::block##TransformV}

constexpr MaterialTextureRow kRows[] = {
    {T::BaseColor, "BASE_COLOR", gpu::kUnitBaseColorTexture, true, kFeatureBaseColorTexture,
     kFeatureBaseColorTexcoord1, coreTexture<&Material::baseColorTexture>, &B::baseColorTransformU,
     &B::baseColorTransformV},
    {T::MetallicRoughness, "METALLIC_ROUGHNESS", gpu::kUnitMetallicRoughnessTexture, false,
     kFeatureMetallicRoughnessTexture, kFeatureMetallicRoughnessTexcoord1,
     coreTexture<&Material::metallicRoughnessTexture>, &B::metallicRoughnessTransformU,
     &B::metallicRoughnessTransformV},
    {T::Normal, "NORMAL", gpu::kUnitNormalTexture, false, kFeatureNormalTexture, kFeatureNormalTexcoord1,
     coreTexture<&Material::normalTexture>, &B::normalTransformU, &B::normalTransformV},
    {T::Occlusion, "OCCLUSION", gpu::kUnitOcclusionTexture, false, kFeatureOcclusionTexture,
     kFeatureOcclusionTexcoord1, coreTexture<&Material::occlusionTexture>, &B::occlusionTransformU,
     &B::occlusionTransformV},
    {T::Emissive, "EMISSIVE", gpu::kUnitEmissiveTexture, true, kFeatureEmissiveTexture, kFeatureEmissiveTexcoord1,
     coreTexture<&Material::emissiveTexture>, &B::emissiveTransformU, &B::emissiveTransformV},
    HL_EXTENSION_ROW(Specular, "SPECULAR", kUnitSpecularTexture, false, specular, Specular::specularTexture, specular),
    HL_EXTENSION_ROW(SpecularColor, "SPECULAR_COLOR", kUnitSpecularColorTexture, true, specular,
                     Specular::specularColorTexture, specularColor),
    HL_EXTENSION_ROW(Clearcoat, "CLEARCOAT", kUnitClearcoatTexture, false, clearcoat, Clearcoat::clearcoatTexture,
                     clearcoat),
    HL_EXTENSION_ROW(ClearcoatRoughness, "CLEARCOAT_ROUGHNESS", kUnitClearcoatRoughnessTexture, false, clearcoat,
                     Clearcoat::clearcoatRoughnessTexture, clearcoatRoughness),
    HL_EXTENSION_ROW(ClearcoatNormal, "CLEARCOAT_NORMAL", kUnitClearcoatNormalTexture, false, clearcoat,
                     Clearcoat::clearcoatNormalTexture, clearcoatNormal),
    HL_EXTENSION_ROW(SheenColor, "SHEEN_COLOR", kUnitSheenColorTexture, true, sheen, Sheen::sheenColorTexture,
                     sheenColor),
    HL_EXTENSION_ROW(SheenRoughness, "SHEEN_ROUGHNESS", kUnitSheenRoughnessTexture, false, sheen,
                     Sheen::sheenRoughnessTexture, sheenRoughness),
    HL_EXTENSION_ROW(Iridescence, "IRIDESCENCE", kUnitIridescenceTexture, false, iridescence,
                     Iridescence::iridescenceTexture, iridescence),
    HL_EXTENSION_ROW(IridescenceThickness, "IRIDESCENCE_THICKNESS", kUnitIridescenceThicknessTexture, false,
                     iridescence, Iridescence::iridescenceThicknessTexture, iridescenceThickness),
    HL_EXTENSION_ROW(Anisotropy, "ANISOTROPY", kUnitAnisotropyTexture, false, anisotropy,
                     Anisotropy::anisotropyTexture, anisotropy),
    HL_EXTENSION_ROW(Transmission, "TRANSMISSION", kUnitTransmissionTexture, false, transmission,
                     Transmission::transmissionTexture, transmission),
    HL_EXTENSION_ROW(Thickness, "THICKNESS", kUnitThicknessTexture, false, volume, Volume::thicknessTexture,
                     thickness),
};
#undef HL_EXTENSION_ROW
static_assert(std::size(kRows) == kMaterialTextureCount);
constexpr bool inOrder() {
  for (std::size_t i = 0; i < std::size(kRows); ++i)
    if (std::size_t(kRows[i].id) != i) return false;
  return true;
}
static_assert(inOrder(), "kRows is indexed by MaterialTexture");

}  // namespace

std::span<const MaterialTextureRow> materialTextureRows() { return kRows; }

}  // namespace headlight
